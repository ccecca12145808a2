#include "gail/weights_export.h"

#include <torch/torch.h>

#include <stdexcept>
#include <utility>

#include "gail/bc_agent.h"
#include "gail/gail_agent.h"
#include "gail/run_dir.h"
#include "util/checkpoint_file.h"
#include "vae/trained_vae.h"

namespace vaegail {

namespace {

// The observation and action sizes of the agent in a checkpoint or weights file, which the
// loaders otherwise take from the task: its normaliser's mean and its policy's log σ.
std::pair<int, int> agent_sizes(const std::string& file) {
  torch::Tensor mean, log_std;
  read_checkpoint(file, [&](const std::string& path) {
    torch::serialize::InputArchive root, agent, normalizer, policy;
    root.load_from(path);
    root.read("agent", agent);
    agent.read("obs_normalizer", normalizer);
    normalizer.read("mean", mean, /*is_buffer=*/true);
    agent.read("policy", policy);
    policy.read("log_std", log_std);
  });
  return {static_cast<int>(mean.numel()), static_cast<int>(log_std.numel())};
}

// The VAE a diverse-GAIL run was fine-tuned on, for its sizes.
vae::TrajectoryVae run_vae(const std::string& run_dir, const GailOptions& options, const std::string& vae) {
  const std::string path = vae.empty() ? options.vae_path : vae;
  if (path.empty())
    throw std::invalid_argument(run_dir + "/config.json: a diverse-GAIL run that records no vae_path (pass --vae)");
  return vae::load_trained_vae(path);
}

}  // namespace

std::string run_kind(const std::string& run_dir) {
  const auto config = read_run_config_json(run_dir);
  if (config.contains("mode")) return "gail";
  if (config.contains("latent_dim")) return "vae";
  if (config.contains("hidden")) return "bc";
  throw std::runtime_error(run_dir + "/config.json: not the config of a vae, gail or bc run");
}

std::string export_weights(const std::string& run_dir, const std::string& out, const std::string& vae) {
  const std::string kind = run_kind(run_dir);
  if (kind == "vae") {
    save_vae_weights(vae::load_trained_vae(run_dir), out);
    return kind;
  }
  const RunFile run = open_run(run_dir, kind);
  const auto [obs_dim, act_dim] = agent_sizes(run.path);
  if (kind == "bc") {
    save_agent_weights(out, kind, run.config, *load_bc_agent(run_dir, obs_dim, act_dim, torch::kCPU));
    return kind;
  }
  const auto options = run_options<GailOptions>(run);
  vae::TrajectoryVae model = recorded_vae(run);
  if (options.mode == GailMode::Diverse && model.is_empty()) model = run_vae(run_dir, options, vae);
  const auto agent = load_gail_agent(run_dir, obs_dim, act_dim, model, torch::kCPU);
  save_agent_weights(out, kind, run.config, *agent, model.is_empty() ? "" : model->config().to_json());
  return kind;
}

}  // namespace vaegail
