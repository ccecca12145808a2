#include "rl/trpo.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "rl/distributed.h"

namespace vaegail {

namespace {

torch::Tensor flatten(const std::vector<torch::Tensor>& tensors) {
  std::vector<torch::Tensor> flat;
  for (const auto& t : tensors) flat.push_back(t.reshape({-1}));
  return torch::cat(flat);
}

// Gradient of a scalar as one flat vector; parameters it does not depend on get zeros.
torch::Tensor flat_grad(const torch::Tensor& scalar, const std::vector<torch::Tensor>& params, bool create_graph) {
  auto grads = torch::autograd::grad({scalar}, params, {}, /*retain_graph=*/true, create_graph, /*allow_unused=*/true);
  for (size_t i = 0; i < grads.size(); ++i)
    if (!grads[i].defined()) grads[i] = torch::zeros_like(params[i]);
  return flatten(grads);
}

void assign(const std::vector<torch::Tensor>& params, const torch::Tensor& flat) {
  torch::NoGradGuard no_grad;
  int64_t offset = 0;
  for (const auto& p : params) {
    p.copy_(flat.slice(0, offset, offset + p.numel()).view_as(p));
    offset += p.numel();
  }
}

// This rank's share of the run's mean surrogate (the sum over ranks is the mean).
torch::Tensor surrogate(StochasticPolicy& policy, const UpdateBatch& batch, const torch::Tensor& frozen,
                        double entropy_coef) {
  const auto dist = policy.distribution_with(batch.inputs, frozen);
  const auto ratio = torch::exp(dist.log_prob(batch.actions) - batch.old_log_probs);
  return ((ratio * batch.advantages).sum() + entropy_coef * dist.entropy().sum()) / batch.global_size();
}

// The given rows (all of an undefined tensor: a policy without a frozen part).
torch::Tensor rows_of(const torch::Tensor& x, const torch::Tensor& rows) {
  return x.defined() ? x.index_select(0, rows.to(x.device())) : x;
}

}  // namespace

LinearOperator fisher_vector_product(StochasticPolicy& policy, const torch::Tensor& inputs,
                                     const torch::Tensor& frozen, double damping, int64_t global_count) {
  const auto params = policy.trainable_parameters();
  const auto dist = policy.distribution_with(inputs, frozen);
  const double count = static_cast<double>(global_count > 0 ? global_count : inputs.size(0));
  const auto kl = kl_divergence(dist.detached(), dist).sum() / count;
  // First backward pass once, with its graph kept; each product is a second pass through it.
  const auto kl_grad = flat_grad(kl, params, /*create_graph=*/true);
  return [params, kl_grad, damping](const torch::Tensor& v) {
    return all_sum(flat_grad((kl_grad * v).sum(), params, /*create_graph=*/false)) + damping * v;
  };
}

torch::Tensor conjugate_gradient(const LinearOperator& A, const torch::Tensor& b, int iterations,
                                 double residual_tol) {
  auto x = torch::zeros_like(b);
  auto r = b.clone();
  auto p = b.clone();
  double rr = r.dot(r).item<double>();
  for (int i = 0; i < iterations && rr > residual_tol; ++i) {
    const auto Ap = A(p);
    const double alpha = rr / p.dot(Ap).item<double>();
    x += alpha * p;
    r -= alpha * Ap;
    const double rr_next = r.dot(r).item<double>();
    p = r + (rr_next / rr) * p;
    rr = rr_next;
  }
  return x;
}

Trpo::Trpo(std::shared_ptr<StochasticPolicy> policy, std::shared_ptr<Critic> critic, TrpoOptions options)
    : policy_(std::move(policy)),
      critic_(std::move(critic)),
      options_(options),
      critic_optimizer_(critic_->parameters(), torch::optim::AdamOptions(options.critic_learning_rate)),
      generator_(at::detail::createCPUGenerator(options.seed)) {
  if (options_.fisher_stride < 1) throw std::invalid_argument("TRPO: fisher_stride must be positive");
}

void Trpo::reseed(std::uint64_t seed) { generator_ = at::detail::createCPUGenerator(seed); }

TrpoStats Trpo::update(const UpdateBatch& batch) {
  TrpoStats stats;
  const auto frozen = policy_->frozen_mean(batch.inputs);
  step_policy(batch, frozen, stats);
  fit_critic(batch, stats);
  return stats;
}

void Trpo::step_policy(const UpdateBatch& batch, const torch::Tensor& frozen, TrpoStats& stats) {
  const auto params = policy_->trainable_parameters();
  const auto old_params = flatten(params).detach();
  const auto distribution = [&] { return policy_->distribution_with(batch.inputs, frozen); };
  const auto old_dist = distribution().detached();
  const auto surrogate_before = surrogate(*policy_, batch, frozen, options_.entropy_coef);
  const auto gradient = all_sum(flat_grad(surrogate_before, params, /*create_graph=*/false));
  // The mean KL and the surrogate's change over the run's batch, in one sum over the ranks.
  const auto kl_and_improvement = [&](double before) {
    const auto kl = kl_divergence(old_dist, distribution()).sum() / batch.global_size();
    const auto both = all_sum(torch::stack({kl, surrogate(*policy_, batch, frozen, options_.entropy_coef)}));
    return std::pair{both[0].item<double>(), both[1].item<double>() - before};
  };

  const auto [fisher_rows, fisher_count] = batch.every(options_.fisher_stride);
  const auto fisher = fisher_vector_product(*policy_, rows_of(batch.inputs, fisher_rows), rows_of(frozen, fisher_rows),
                                            options_.cg_damping, fisher_count);
  const auto direction = conjugate_gradient(fisher, gradient, options_.cg_iterations);
  const double curvature = direction.dot(fisher(direction)).item<double>();
  if (std::isfinite(curvature) && curvature > 0) {
    // The quadratic model ½·sᵀFs of the KL reaches max_kl at this length.
    const auto full_step = direction * std::sqrt(2.0 * options_.max_kl / curvature);
    stats.expected_improvement = gradient.dot(full_step).item<double>();
    torch::NoGradGuard no_grad;
    const double before = all_sum(surrogate_before.item<double>());
    double fraction = 1.0;
    for (int k = 0; k < options_.line_search_steps; ++k, fraction *= options_.backtrack_ratio) {
      assign(params, old_params + fraction * full_step);
      const auto [kl, improvement] = kl_and_improvement(before);
      if (std::isfinite(improvement) && improvement > 0 && kl <= options_.max_kl) {
        stats.accepted = true;
        stats.surrogate_improvement = improvement;
        stats.kl = kl;
        stats.line_search_steps = k;
        break;
      }
    }
  }
  torch::NoGradGuard no_grad;
  if (!stats.accepted) assign(params, old_params);
  stats.entropy = all_sum(distribution().entropy().sum().item<double>()) / batch.global_size();
}

void Trpo::fit_critic(const UpdateBatch& batch, TrpoStats& stats) {
  // This rank's share of the mean squared error over the run's (mini)batch.
  const auto loss = [&](const UpdateBatch& b) {
    return (critic_->forward(b.inputs) - b.returns).pow(2).sum() / b.global_size();
  };
  const auto parameters = critic_->parameters();
  {
    torch::NoGradGuard no_grad;
    stats.value_loss_before = all_sum(loss(batch).item<double>());
  }
  for (int epoch = 0; epoch < options_.critic_epochs; ++epoch) {
    for (const auto& minibatch : batch.minibatches(options_.critic_minibatches, generator_)) {
      critic_optimizer_.zero_grad();
      loss(minibatch).backward();
      all_sum_gradients(parameters);
      critic_optimizer_.step();
    }
  }
  torch::NoGradGuard no_grad;
  stats.value_loss_after = all_sum(loss(batch).item<double>());
}

}  // namespace vaegail
