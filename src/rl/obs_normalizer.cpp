#include "rl/obs_normalizer.h"

#include "rl/distributed.h"
#include "util/world.h"

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
  merge(x.mean(0), x.var(0, /*unbiased=*/false), static_cast<double>(x.size(0)));
}

void ObsNormalizer::update_over_ranks(const torch::Tensor& rank_batch) {
  if (!World::get().distributed()) return update(rank_batch);
  if (frozen_) return;
  torch::NoGradGuard no_grad;
  const auto x = rank_batch.reshape({-1, dim_}).to(torch::kCPU, torch::kFloat64);
  const double m = all_sum(static_cast<double>(x.size(0)));
  if (m == 0) return;
  const auto batch_mean = all_sum(x.sum(0)) / m;
  const auto batch_var = all_sum((x - batch_mean).pow(2).sum(0)) / m;
  merge(batch_mean.to(mean_.device()), batch_var.to(mean_.device()), m);
}

void ObsNormalizer::merge(const torch::Tensor& batch_mean, const torch::Tensor& batch_var, double m) {
  const double n = count(), total = n + m;
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
