#include "gail/discriminator.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace vaegail {

namespace {

constexpr double kStdFloor = 1e-6;  // a constant component standardises to 0, not to NaN

torch::Tensor bounds(const std::vector<double>& values, int act_dim, double fallback, const char* name) {
  if (values.empty()) return torch::full({act_dim}, fallback, torch::kFloat32);
  if (static_cast<int>(values.size()) != act_dim)
    throw std::invalid_argument(std::string("Discriminator: ") + name + " has " + std::to_string(values.size()) +
                                " values, the action " + std::to_string(act_dim));
  return torch::tensor(values, torch::kFloat64).to(torch::kFloat32);
}

torch::Tensor selected_indices(const std::vector<int>& indices, int obs_dim) {
  if (indices.empty()) return torch::arange(obs_dim, torch::kLong);
  for (int i : indices)
    if (i < 0 || i >= obs_dim)
      throw std::invalid_argument("Discriminator: state index " + std::to_string(i) + " outside the observation (" +
                                  std::to_string(obs_dim) + " components)");
  return torch::tensor(std::vector<int64_t>(indices.begin(), indices.end()), torch::kLong);
}

// Binary cross-entropy from logits, labels 1 for demos and 0 for the policy, in the stable
// softplus form: -log σ(l) = softplus(-l), -log(1 - σ(l)) = softplus(l). Each side's mean is over
// `count` pairs, of which these logits may be one rank's share (rl/distributed.h).
torch::Tensor bce(const torch::Tensor& demo_logits, const torch::Tensor& policy_logits, int64_t count) {
  return (torch::softplus(-demo_logits).sum() + torch::softplus(policy_logits).sum()) / count;
}

// Summed over the ranks: the run's loss and accuracies.
DiscriminatorStats stats_of(const torch::Tensor& demo_logits, const torch::Tensor& policy_logits, int64_t count) {
  const auto sums = all_sum(torch::stack({bce(demo_logits, policy_logits, count).to(torch::kFloat64),
                                          (demo_logits > 0).to(torch::kFloat64).sum() / count,
                                          (policy_logits < 0).to(torch::kFloat64).sum() / count}));
  return {sums[0].item<double>(), sums[1].item<double>(), sums[2].item<double>()};
}

}  // namespace

Discriminator::Discriminator(const DiscriminatorOptions& o)
    : obs_dim_(o.obs_dim), act_dim_(o.act_dim), latent_dim_(o.latent_dim) {
  if (o.obs_dim < 1 || o.act_dim < 1 || o.latent_dim < 0)
    throw std::invalid_argument("Discriminator: needs obs_dim, act_dim >= 1 and latent_dim >= 0");
  const double inf = std::numeric_limits<double>::infinity();
  state_indices_ = register_buffer("state_indices", selected_indices(o.state_indices, o.obs_dim));
  action_low_ = register_buffer("action_low", bounds(o.action_low, o.act_dim, -inf, "action_low"));
  action_high_ = register_buffer("action_high", bounds(o.action_high, o.act_dim, inf, "action_high"));
  const int feature_dim = static_cast<int>(state_indices_.size(0)) + o.act_dim;
  feature_mean_ = register_buffer("feature_mean", torch::zeros({feature_dim}));
  feature_std_ = register_buffer("feature_std", torch::ones({feature_dim}));
  net_ = register_module("net", std::make_shared<Mlp>(feature_dim + o.latent_dim, o.hidden, 1, o.activation));
}

torch::Tensor Discriminator::features(const torch::Tensor& observations, const torch::Tensor& actions) const {
  const auto device = feature_mean_.device();
  const auto state = observations.to(device, torch::kFloat32).index_select(-1, state_indices_);
  const auto action = torch::max(torch::min(actions.to(device, torch::kFloat32), action_high_), action_low_);
  return torch::cat({state, action}, -1);
}

void Discriminator::fit_normalization(const torch::Tensor& observations, const torch::Tensor& actions) {
  torch::NoGradGuard no_grad;
  const auto x = features(observations, actions).to(torch::kFloat64);
  feature_mean_.copy_(x.mean(0));
  feature_std_.copy_(x.std(0, /*unbiased=*/false).clamp_min(kStdFloor));
}

torch::Tensor Discriminator::forward(const torch::Tensor& observations, const torch::Tensor& actions,
                                     const torch::Tensor& z) {
  auto input = (features(observations, actions) - feature_mean_) / feature_std_;
  if (latent_dim_ > 0) {
    if (!z.defined() || z.dim() != 2 || z.size(1) != latent_dim_)
      throw std::invalid_argument("Discriminator: expects z [B, " + std::to_string(latent_dim_) + "]");
    input = torch::cat({input, z.to(input.device(), torch::kFloat32)}, -1);
  }
  return net_->forward(input).squeeze(-1);
}

DiscriminatorStats evaluate_discriminator(Discriminator& discriminator, const DiscriminatorData& demos,
                                          const DiscriminatorData& policy, int64_t global_count) {
  torch::NoGradGuard no_grad;
  const auto demo_logits = discriminator.forward(demos), policy_logits = discriminator.forward(policy);
  return stats_of(demo_logits, policy_logits, global_count > 0 ? global_count : policy.size());
}

DiscriminatorTrainer::DiscriminatorTrainer(std::shared_ptr<Discriminator> discriminator, double learning_rate)
    : discriminator_(std::move(discriminator)),
      optimizer_(discriminator_->parameters(), torch::optim::AdamOptions(learning_rate)) {}

DiscriminatorStats DiscriminatorTrainer::train(const DiscriminatorData& demos, const DiscriminatorData& policy,
                                               int steps, int minibatches, at::Generator& generator,
                                               const RowSlice& rows) {
  if (minibatches < 1) throw std::invalid_argument("DiscriminatorTrainer: minibatches must be positive");
  if (demos.size() != policy.size())
    throw std::invalid_argument("DiscriminatorTrainer: one demonstration sample per policy sample");
  const RowSlice slice = rows.global_rows.defined() ? rows : RowSlice::whole(policy.size());
  const DiscriminatorStats before = evaluate_discriminator(*discriminator_, demos, policy, slice.global_size);
  const int64_t n = slice.global_size, batch = std::max<int64_t>(n / minibatches, 1);
  const auto order = minibatches > 1 ? torch::randperm(n, generator, torch::kLong) : torch::Tensor();
  const auto parameters = discriminator_->parameters();
  const auto take = [&](const DiscriminatorData& d, const torch::Tensor& local) {
    return local.defined() ? DiscriminatorData{d.observations.index_select(0, local),
                                               d.actions.index_select(0, local), d.z.index_select(0, local)}
                           : d;
  };
  for (int step = 0; step < steps; ++step) {
    const auto local = order.defined()
                           ? slice.local_rows(order.narrow(0, (step % minibatches) * batch, batch)).to(policy.observations.device())
                           : torch::Tensor();
    const auto loss = bce(discriminator_->forward(take(demos, local)), discriminator_->forward(take(policy, local)),
                          order.defined() ? batch : n);
    optimizer_.zero_grad();
    loss.backward();
    all_sum_gradients(parameters);
    optimizer_.step();
  }
  return before;
}

}  // namespace vaegail
