#include "gail/bc_agent.h"

#include "gail/run_dir.h"
#include "util/rng.h"

namespace vaegail {

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
