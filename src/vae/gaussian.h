// Diagonal Gaussians: log-density, KL to the standard normal, reparameterised samples.
#pragma once

#include <torch/torch.h>

namespace vaegail::vae {

// log N(x | mean, exp(log_std)^2) per element (same shape as the broadcast of the inputs);
// sum over the last dimension for a diagonal Gaussian over vectors.
torch::Tensor gaussian_log_prob(const torch::Tensor& x, const torch::Tensor& mean,
                                const torch::Tensor& log_std);

// KL( N(mean, diag(exp(log_std)^2)) || N(0, I) ), summed over the last dimension:
// 0.5 * sum(mean^2 + sigma^2 - 1 - 2 log sigma).  [..., Z] -> [...]
torch::Tensor kl_to_standard_normal(const torch::Tensor& mean, const torch::Tensor& log_std);

// mean + exp(log_std) * noise, noise ~ N(0, I) of the same shape (the caller draws it, so
// the random stream is the caller's to seed).
torch::Tensor reparameterize(const torch::Tensor& mean, const torch::Tensor& log_std,
                             const torch::Tensor& noise);

// Maps an unbounded network output into [low, high] smoothly (scaled tanh), so a
// log-std can neither collapse to -inf on a deterministic dimension nor explode.
torch::Tensor soft_bound(const torch::Tensor& raw, double low, double high);

}  // namespace vaegail::vae
