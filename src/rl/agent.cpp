#include "rl/agent.h"

#include <stdexcept>

#include "util/checkpoint_file.h"

namespace vaegail {

Agent::Agent(std::shared_ptr<StochasticPolicy> policy, std::shared_ptr<Critic> critic,
             std::shared_ptr<ObsNormalizer> normalizer)
    : policy_(register_module("policy", std::move(policy))),
      critic_(register_module("critic", std::move(critic))),
      normalizer_(register_module("obs_normalizer", std::move(normalizer))) {
  if (policy_->input_dim() < normalizer_->dim() || critic_->input_dim() != policy_->input_dim())
    throw std::invalid_argument("Agent: policy input " + std::to_string(policy_->input_dim()) + ", critic input " +
                                std::to_string(critic_->input_dim()) + ", observation " +
                                std::to_string(normalizer_->dim()) + " do not fit together");
}

std::shared_ptr<Agent> Agent::make_gaussian(const AgentOptions& o) {
  const int input_dim = o.obs_dim + o.condition_dim;
  GaussianPolicyOptions policy;
  policy.input_dim = input_dim;
  policy.act_dim = o.act_dim;
  policy.hidden = o.policy_hidden;
  policy.activation = o.activation;
  policy.init_log_std = o.init_log_std;
  CriticOptions critic;
  critic.input_dim = input_dim;
  critic.hidden = o.critic_hidden;
  critic.activation = o.activation;
  return std::make_shared<Agent>(std::make_shared<GaussianPolicy>(policy), std::make_shared<Critic>(critic),
                                 std::make_shared<ObsNormalizer>(o.obs_dim, o.obs_clip));
}

torch::Device Agent::device() const { return normalizer_->mean().device(); }

torch::Tensor Agent::input(const torch::Tensor& observations, const torch::Tensor& conditions) const {
  const auto obs = normalizer_->normalize(observations.to(device(), torch::kFloat32));
  return torch::cat({obs, conditions.to(device(), torch::kFloat32)}, -1);
}

void Agent::save_checkpoint(const std::string& path) const {
  torch::serialize::OutputArchive archive;
  save(archive);
  write_checkpoint(path, [&](std::ostream& out) { archive.save_to(out); });
}

void Agent::load_checkpoint(const std::string& path) {
  torch::serialize::InputArchive archive;
  archive.load_from(path, device());
  load(archive);
}

}  // namespace vaegail
