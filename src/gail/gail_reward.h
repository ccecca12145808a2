// The GAIL reward of paper section 3.2, r(x, a | z) = -log(1 - D(x, a | z)), clipped above.
//
// -log(1 - sigmoid(l)) = softplus(l) for the discriminator's logit l: exact and finite for
// any l, where computing 1 - D in floating point would give log(0) once D rounds to 1.
// The reward is positive, so it also pays the walker for every step it stays up.
#pragma once

#include <memory>

#include "gail/discriminator.h"
#include "rl/rollout.h"

namespace vaegail {

// Default upper bound: -log(1 - D) = 5 at D ≈ 0.993. The paper clips without giving the bound;
// this one keeps a handful of states the discriminator is sure about from dominating the
// returns (the unclipped reward grows without limit as D → 1), while leaving the range the
// discriminator spends most of its time in (D around 1/2, r ≈ 0.7) untouched.
constexpr double kDefaultGailRewardClip = 5.0;

// [T, N, d] → [T·N, d], also for d = 0 (a plain-GAIL rollout's conditions).
torch::Tensor flatten_steps(const torch::Tensor& x);

// logits [...] → rewards [...]: min(softplus(logit), clip).
torch::Tensor gail_reward(const torch::Tensor& logits, double clip = kDefaultGailRewardClip);

// Scores every (observation, action, condition) step of a rollout: [T, N] rewards. The
// rollout's conditions are the episodes' z (ignored by an unconditional discriminator).
class GailReward : public RewardSource {
 public:
  GailReward(std::shared_ptr<Discriminator> discriminator, double clip = kDefaultGailRewardClip);
  torch::Tensor rewards(const Rollout& rollout) override;

 private:
  std::shared_ptr<Discriminator> discriminator_;
  double clip_;
};

}  // namespace vaegail
