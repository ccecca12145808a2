#include "rl/ppo.h"

#include "rl/distributed.h"

namespace vaegail {

namespace {

std::vector<torch::Tensor> joint_parameters(StochasticPolicy& policy, Critic& critic) {
  auto params = policy.trainable_parameters();
  for (const auto& p : critic.parameters()) params.push_back(p);
  return params;
}

}  // namespace

Ppo::Ppo(std::shared_ptr<StochasticPolicy> policy, std::shared_ptr<Critic> critic, PpoOptions options)
    : policy_(std::move(policy)),
      critic_(std::move(critic)),
      options_(options),
      parameters_(joint_parameters(*policy_, *critic_)),
      optimizer_(parameters_, torch::optim::AdamOptions(options.learning_rate)),
      generator_(at::detail::createCPUGenerator(options.seed)) {}

PpoStats Ppo::update(const UpdateBatch& batch) {
  PpoStats stats;
  for (int epoch = 0; epoch < options_.epochs && !stats.stopped_early; ++epoch) {
    double epoch_kl = 0.0;
    int epoch_steps = 0;
    for (const auto& mb : batch.minibatches(options_.minibatches, generator_)) {
      // Means over the run's minibatch: this rank's sums over the global count, added over ranks.
      const auto mean = [&](const torch::Tensor& per_row) { return per_row.sum() / mb.global_size(); };
      const auto dist = policy_->distribution(mb.inputs);
      const auto log_ratio = dist.log_prob(mb.actions) - mb.old_log_probs;
      const auto ratio = torch::exp(log_ratio);
      const auto clipped = torch::clamp(ratio, 1 - options_.clip, 1 + options_.clip);
      const auto policy_loss = -mean(torch::min(ratio * mb.advantages, clipped * mb.advantages));
      const auto value_loss = mean((critic_->forward(mb.inputs) - mb.returns).pow(2));
      const auto entropy = mean(dist.entropy());
      const auto clip_fraction = mean(((ratio - 1).abs() > options_.clip).to(torch::kFloat32));
      const auto means = all_sum(torch::stack({policy_loss, value_loss, entropy, mean((ratio - 1) - log_ratio),
                                               clip_fraction}).detach().to(torch::kFloat64));
      const double approx_kl = means[3].item<double>();

      optimizer_.zero_grad();
      (policy_loss + options_.value_coef * value_loss - options_.entropy_coef * entropy).backward();
      all_sum_gradients(parameters_);
      torch::nn::utils::clip_grad_norm_(parameters_, options_.max_grad_norm);
      optimizer_.step();

      stats.policy_loss += means[0].item<double>();
      stats.value_loss += means[1].item<double>();
      stats.entropy += means[2].item<double>();
      stats.approx_kl += approx_kl;
      stats.clip_fraction += means[4].item<double>();
      ++stats.minibatch_steps;
      epoch_kl += approx_kl;
      ++epoch_steps;
    }
    // The stop reads the whole epoch's KL, as CleanRL does: one minibatch's estimate (128 rows
    // of a 56-dimensional action for the humanoid) is noisy enough to end whole updates after a
    // single step, the critic's training with them.
    stats.stopped_early = options_.target_kl > 0 && epoch_steps > 0 && epoch_kl / epoch_steps > 1.5 * options_.target_kl;
  }
  if (stats.minibatch_steps > 0) {
    for (double* mean : {&stats.policy_loss, &stats.value_loss, &stats.entropy, &stats.approx_kl, &stats.clip_fraction})
      *mean /= stats.minibatch_steps;
  }
  return stats;
}

}  // namespace vaegail
