#include "gail/gail_reward.h"

#include <stdexcept>

namespace vaegail {

torch::Tensor flatten_steps(const torch::Tensor& x) { return x.reshape({x.size(0) * x.size(1), x.size(2)}); }

torch::Tensor gail_reward(const torch::Tensor& logits, double clip) {
  return torch::softplus(logits).clamp_max(clip);
}

GailReward::GailReward(std::shared_ptr<Discriminator> discriminator, double clip)
    : discriminator_(std::move(discriminator)), clip_(clip) {
  if (!(clip > 0)) throw std::invalid_argument("GailReward: the reward clip must be positive");
}

torch::Tensor GailReward::rewards(const Rollout& rollout) {
  torch::NoGradGuard no_grad;
  const auto logits = discriminator_->forward(flatten_steps(rollout.observations), flatten_steps(rollout.actions),
                                              flatten_steps(rollout.conditions));
  return gail_reward(logits, clip_).reshape(rollout.env_rewards.sizes()).to(rollout.env_rewards.device());
}

}  // namespace vaegail
