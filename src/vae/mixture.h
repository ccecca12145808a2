// Mixtures of Gaussians over scalars: the output distribution of the state decoder, one
// mixture per state component (the paper's replacement for WaveNet's softmax).
#pragma once

#include <torch/torch.h>

namespace vaegail::vae {

// K components per scalar; all three tensors have shape [..., K].
struct MixtureParams {
  torch::Tensor logits;    // unnormalised log mixture weights
  torch::Tensor means;
  torch::Tensor log_stds;

  int64_t components() const { return logits.size(-1); }
};

// log sum_k softmax(logits)_k N(x | mean_k, exp(log_std_k)^2), computed as one logsumexp
// over k of log_softmax + Gaussian log-density, so it stays finite when every component
// is far from x.  x: [...]  ->  [...]
torch::Tensor mixture_log_prob(const torch::Tensor& x, const MixtureParams& mixture);

// One draw per scalar: a component from the softmax weights, then that Gaussian.
// [..., K] -> [...]. Uses `generator` (CPU) when given, torch's default otherwise.
torch::Tensor mixture_sample(const MixtureParams& mixture,
                             c10::optional<at::Generator> generator = c10::nullopt);

}  // namespace vaegail::vae
