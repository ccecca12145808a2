// What the GAIL and BC run directories share: a config a rerun must agree with, a metrics
// log cut back to the last checkpoint, and the trained agent.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "rl/agent.h"

namespace vaegail {

// Writes `config` to path. If path already holds a config (a resumed run), it must equal
// `config` except on `resumable_keys` (settings that do not change what an iteration
// computes); otherwise std::invalid_argument names the first differing setting.
void check_or_write_config(const std::string& path, const nlohmann::json& config,
                           const std::vector<std::string>& resumable_keys);

// Drops the rows of a metrics CSV whose first column (the iteration or epoch) exceeds
// `last`: rows logged by a run killed before its checkpoint, which the resumed run redoes.
void truncate_metrics(const std::string& path, int last);

// run_dir/config.json parsed; throws naming the file when it is missing or malformed.
nlohmann::json read_run_config_json(const std::string& run_dir);
template <class Options>
Options read_run_config(const std::string& run_dir) {
  const auto j = read_run_config_json(run_dir);
  try {
    return j.get<Options>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(run_dir + "/config.json: " + e.what());
  }
}
// run_dir/checkpoints/latest.pt; throws naming it when it does not exist.
std::string run_checkpoint(const std::string& run_dir);

// Loads the "agent" archive of run_dir's checkpoint into `agent` (built to the run's config)
// on `device`, and puts it in evaluation mode.
void load_run_agent(const std::string& run_dir, Agent& agent, torch::Device device);

}  // namespace vaegail
