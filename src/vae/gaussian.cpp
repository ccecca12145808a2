#include "vae/gaussian.h"

#include <cmath>

namespace vaegail::vae {

namespace {
constexpr double kHalfLog2Pi = 0.91893853320467274178;  // 0.5 * log(2 pi)
}

torch::Tensor gaussian_log_prob(const torch::Tensor& x, const torch::Tensor& mean,
                                const torch::Tensor& log_std) {
  const auto z = (x - mean) * torch::exp(-log_std);
  return -0.5 * z.square() - log_std - kHalfLog2Pi;
}

torch::Tensor kl_to_standard_normal(const torch::Tensor& mean, const torch::Tensor& log_std) {
  return 0.5 * (mean.square() + torch::exp(2.0 * log_std) - 1.0 - 2.0 * log_std).sum(-1);
}

torch::Tensor reparameterize(const torch::Tensor& mean, const torch::Tensor& log_std,
                             const torch::Tensor& noise) {
  return mean + torch::exp(log_std) * noise;
}

torch::Tensor soft_bound(const torch::Tensor& raw, double low, double high) {
  const double mid = 0.5 * (low + high), half = 0.5 * (high - low);
  return mid + half * torch::tanh(raw / half);
}

}  // namespace vaegail::vae
