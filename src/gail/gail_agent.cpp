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

void to_json(nlohmann::json& j, const GailOptions& o) {
  j = {{"mode", to_string(o.mode)},
       {"iterations", o.iterations},
       {"minutes", o.minutes},
       {"num_envs", o.num_envs},
       {"env_threads", o.env_threads},
       {"steps_per_env", o.steps_per_env},
       {"policy_hidden", o.policy_hidden},
       {"critic_hidden", o.critic_hidden},
       {"discriminator_hidden", o.discriminator_hidden},
       {"discriminator_state_indices", o.discriminator_state_indices},
       {"init_log_std", o.init_log_std},
       {"gamma", o.gamma},
       {"lambda", o.lambda},
       {"max_kl", o.max_kl},
       {"critic_learning_rate", o.critic_learning_rate},
       {"discriminator_steps", o.discriminator_steps},
       {"discriminator_minibatches", o.discriminator_minibatches},
       {"discriminator_learning_rate", o.discriminator_learning_rate},
       {"reward_clip", o.reward_clip},
       {"seed", o.seed},
       {"device", o.device},
       {"demos_path", o.demos_path},
       {"vae_path", o.vae_path}};
}

void from_json(const nlohmann::json& j, GailOptions& o) {
  const GailOptions d;
  o.mode = parse_gail_mode(j.value("mode", to_string(d.mode)));
  o.iterations = j.value("iterations", d.iterations);
  o.minutes = j.value("minutes", d.minutes);
  o.num_envs = j.value("num_envs", d.num_envs);
  o.env_threads = j.value("env_threads", d.env_threads);
  o.steps_per_env = j.value("steps_per_env", d.steps_per_env);
  o.policy_hidden = j.value("policy_hidden", d.policy_hidden);
  o.critic_hidden = j.value("critic_hidden", d.critic_hidden);
  o.discriminator_hidden = j.value("discriminator_hidden", d.discriminator_hidden);
  o.discriminator_state_indices = j.value("discriminator_state_indices", d.discriminator_state_indices);
  o.init_log_std = j.value("init_log_std", d.init_log_std);
  o.gamma = j.value("gamma", d.gamma);
  o.lambda = j.value("lambda", d.lambda);
  o.max_kl = j.value("max_kl", d.max_kl);
  o.critic_learning_rate = j.value("critic_learning_rate", d.critic_learning_rate);
  o.discriminator_steps = j.value("discriminator_steps", d.discriminator_steps);
  o.discriminator_minibatches = j.value("discriminator_minibatches", 1);  // older runs: the full batch
  o.discriminator_learning_rate = j.value("discriminator_learning_rate", d.discriminator_learning_rate);
  o.reward_clip = j.value("reward_clip", d.reward_clip);
  o.seed = j.value("seed", d.seed);
  o.device = j.value("device", d.device);
  o.demos_path = j.value("demos_path", d.demos_path);
  o.vae_path = j.value("vae_path", d.vae_path);
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
