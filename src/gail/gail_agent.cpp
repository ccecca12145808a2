#include "gail/gail_agent.h"

#include <stdexcept>

#include "gail/residual_policy.h"
#include "util/rng.h"

namespace vaegail {

std::string to_string(GailMode mode) { return mode == GailMode::Diverse ? "diverse" : "plain"; }

GailMode parse_gail_mode(const std::string& name) {
  if (name == "diverse") return GailMode::Diverse;
  if (name == "plain") return GailMode::Plain;
  throw std::invalid_argument("GAIL mode must be diverse or plain, not '" + name + "'");
}

std::shared_ptr<Agent> make_gail_agent(const GailOptions& o, int obs_dim, int act_dim,
                                       const torch::Tensor& demo_observations, vae::TrajectoryVae vae) {
  torch::manual_seed(derive_seed(o.seed, kGailInitStream));
  auto normalizer = std::make_shared<ObsNormalizer>(obs_dim);
  normalizer->update(demo_observations);
  normalizer->set_frozen(true);
  std::shared_ptr<StochasticPolicy> policy;
  if (o.mode == GailMode::Diverse) {
    if (vae.is_empty()) throw std::invalid_argument("diverse GAIL needs a VAE");
    ResidualPolicyOptions p;
    p.hidden = o.policy_hidden;
    p.init_log_std = o.init_log_std;
    policy = std::make_shared<ResidualPolicy>(vae, normalizer, p);
  } else {
    GaussianPolicyOptions p;
    p.input_dim = obs_dim;
    p.act_dim = act_dim;
    p.hidden = o.policy_hidden;
    p.init_log_std = o.init_log_std;
    policy = std::make_shared<GaussianPolicy>(p);
  }
  CriticOptions c;
  c.input_dim = policy->input_dim();
  c.hidden = o.critic_hidden;
  auto agent = std::make_shared<Agent>(policy, std::make_shared<Critic>(c), normalizer);
  agent->to(torch::Device(o.device));
  return agent;
}

std::shared_ptr<Agent> load_gail_agent(const std::string& run, int obs_dim, int act_dim,
                                       vae::TrajectoryVae vae, torch::Device device) {
  const RunFile file = open_run(run, "gail");
  GailOptions options = run_options<GailOptions>(file);
  options.device = device.str();
  if (options.mode != GailMode::Diverse) vae = vae::TrajectoryVae(nullptr);
  else if (vae.is_empty()) vae = recorded_vae(file);
  // The normaliser's statistics come from the checkpoint; these only give it its shape.
  auto agent = make_gail_agent(options, obs_dim, act_dim, torch::zeros({2, obs_dim}), vae);
  load_run_agent(file.path, *agent, device);
  return agent;
}

vae::TrajectoryVae recorded_vae(const RunFile& run) {
  if (run.vae_config.empty()) return vae::TrajectoryVae(nullptr);
  return vae::TrajectoryVae(vae::VaeConfig::from_json(run.vae_config));
}

vae::LatentPolicy agent_mean_policy(std::shared_ptr<Agent> agent) {
  return [agent](const torch::Tensor& obs, const torch::Tensor& z) {
    const auto condition = agent->condition_dim() > 0 ? z : torch::zeros({obs.size(0), 0});
    return agent->policy().distribution(agent->input(obs, condition)).mean;
  };
}

}  // namespace vaegail
