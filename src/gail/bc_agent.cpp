#include "gail/bc_agent.h"

#include "gail/run_dir.h"
#include "util/rng.h"

namespace vaegail {

void to_json(nlohmann::json& j, const BcOptions& o) {
  j = {{"hidden", o.hidden},           {"epochs", o.epochs},
       {"batch_size", o.batch_size},   {"learning_rate", o.learning_rate},
       {"init_log_std", o.init_log_std}, {"seed", o.seed},
       {"device", o.device},           {"demos_path", o.demos_path}};
}

void from_json(const nlohmann::json& j, BcOptions& o) {
  const BcOptions d;
  o.hidden = j.value("hidden", d.hidden);
  o.epochs = j.value("epochs", d.epochs);
  o.batch_size = j.value("batch_size", d.batch_size);
  o.learning_rate = j.value("learning_rate", d.learning_rate);
  o.init_log_std = j.value("init_log_std", d.init_log_std);
  o.seed = j.value("seed", d.seed);
  o.device = j.value("device", d.device);
  o.demos_path = j.value("demos_path", d.demos_path);
}

std::shared_ptr<Agent> make_bc_agent(const BcOptions& options, const torch::Tensor& observations, int act_dim) {
  torch::manual_seed(derive_seed(options.seed, 0));
  AgentOptions a;
  a.obs_dim = static_cast<int>(observations.size(1));
  a.act_dim = act_dim;
  a.policy_hidden = options.hidden;
  a.critic_hidden = {};
  a.init_log_std = options.init_log_std;
  auto agent = Agent::make_gaussian(a);
  agent->normalizer().update(observations);
  agent->normalizer().set_frozen(true);
  agent->to(torch::Device(options.device));
  return agent;
}

std::shared_ptr<Agent> load_bc_agent(const std::string& run, int obs_dim, int act_dim, torch::Device device) {
  const RunFile file = open_run(run, "bc");
  BcOptions options = run_options<BcOptions>(file);
  options.device = device.str();
  auto agent = make_bc_agent(options, torch::zeros({2, obs_dim}), act_dim);
  load_run_agent(file.path, *agent, device);
  return agent;
}

}  // namespace vaegail
