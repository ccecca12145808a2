#include "rl/obs_normalizer.h"

namespace vaegail {

namespace {
constexpr double kVarEpsilon = 1e-8;
}

ObsNormalizer::ObsNormalizer(int dim, double clip)
    : dim_(dim),
      clip_(clip),
      mean_(register_buffer("mean", torch::zeros({dim}, torch::kFloat64))),
      var_(register_buffer("var", torch::ones({dim}, torch::kFloat64))),
      count_(register_buffer("count", torch::zeros({}, torch::kFloat64))) {}

void ObsNormalizer::update(const torch::Tensor& batch) {
  if (frozen_ || batch.size(0) == 0) return;
  torch::NoGradGuard no_grad;
  const auto x = batch.reshape({-1, dim_}).to(mean_.device(), torch::kFloat64);
  const double n = count(), m = static_cast<double>(x.size(0)), total = n + m;
  const auto batch_mean = x.mean(0);
  const auto batch_var = x.var(0, /*unbiased=*/false);
  const auto delta = batch_mean - mean_;
  // In-place so the registered buffers stay the same tensors.
  var_.copy_((var_ * n + batch_var * m + delta.pow(2) * (n * m / total)) / total);
  mean_.add_(delta * (m / total));
  count_.fill_(total);
}

torch::Tensor ObsNormalizer::normalize(const torch::Tensor& x) const {
  const auto z = (x.to(torch::kFloat64) - mean_) / torch::sqrt(var_ + kVarEpsilon);
  return z.clamp(-clip_, clip_).to(x.scalar_type());
}

}  // namespace vaegail
