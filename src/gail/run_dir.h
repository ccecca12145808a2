// What the GAIL and BC run directories share: a config a rerun must agree with and the trained
// agent (their metrics log is cut back to the last checkpoint by util/csv_log.h's truncate_metrics).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "rl/agent.h"

namespace vaegail {

// Writes `config` to path. If path already holds a config (a resumed run), it must equal
// `config` except on `resumable_keys` (settings that do not change what an iteration
// computes); otherwise std::invalid_argument names the first differing setting. The stored
// config is compared as `normalize` reads it: a key an older run lacks takes the value that
// run was read with, rather than counting as a difference.
void check_or_write_config(const std::string& path, const nlohmann::json& config,
                           const std::vector<std::string>& resumable_keys,
                           const std::function<nlohmann::json(const nlohmann::json&)>& normalize);

// The same for an options struct with JSON conversions: the stored config read as Options.
template <class Options>
void check_or_write_config(const std::string& path, const Options& options,
                           const std::vector<std::string>& resumable_keys) {
  check_or_write_config(path, nlohmann::json(options), resumable_keys,
                        [](const nlohmann::json& stored) { return nlohmann::json(stored.get<Options>()); });
}

// run_dir/config.json parsed; throws naming the file when it is missing or malformed.
nlohmann::json read_run_config_json(const std::string& run_dir);
// run_dir/checkpoints/latest.pt, the checkpoint a trainer rotates (util/checkpoint_file.h:
// the one before it is previous_checkpoint_for(it)).
std::string run_checkpoint(const std::string& run_dir);

// A trained policy's run as the loaders take it: a run directory, a trainer checkpoint in one
// (RUN/checkpoints/NAME.pt, whose options are RUN/config.json) or a weights file
// (util/checkpoint_file.h), which carries its own.
struct RunFile {
  std::string path;        // the file holding the weights (util/checkpoint_file.h's model_file)
  std::string kind;        // a weights file's kind ("gail", "bc", "vae"); empty for a trainer checkpoint
  nlohmann::json config;   // the run's options
  std::string vae_config;  // a diverse-GAIL weights file: its frozen VAE's VaeConfig JSON; else empty
};
// Throws one line naming the file when it is missing or damaged, or when it is the weights file
// of another kind than `kind`.
RunFile open_run(const std::string& run, const std::string& kind);
template <class Options>
Options run_options(const RunFile& run) {
  try {
    return run.config.get<Options>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(run.path + ": its config: " + e.what());
  }
}

// Loads the "agent" archive of `run` (as open_run takes it) into `agent` (built to the run's
// config) on `device`, and puts it in evaluation mode. A missing, truncated or corrupt
// file throws one line naming it (util/checkpoint_file.h's read_checkpoint).
void load_run_agent(const std::string& run, Agent& agent, torch::Device device);

// Writes the weights file of a trained policy to `path`, atomically: `kind` ("gail" or "bc"),
// the run's options, the agent, and for diverse GAIL its VAE's config (`vae_config`, JSON).
void save_agent_weights(const std::string& path, const std::string& kind, const nlohmann::json& config,
                        const Agent& agent, const std::string& vae_config = "");

}  // namespace vaegail
