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
// `last`: rows logged by a run killed before its checkpoint, which the resumed run redoes;
// and a last line without its newline (torn by the kill). A first column that is not a
// number throws one line naming the file and the line.
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
// run_dir/checkpoints/latest.pt, the checkpoint a trainer rotates (util/checkpoint_file.h:
// the one before it is previous_checkpoint_for(it)).
std::string run_checkpoint(const std::string& run_dir);

// Loads the "agent" archive of run_dir's latest checkpoint into `agent` (built to the run's
// config) on `device`, and puts it in evaluation mode. A missing, truncated or corrupt
// checkpoint throws one line naming it (util/checkpoint_file.h's read_checkpoint).
void load_run_agent(const std::string& run_dir, Agent& agent, torch::Device device);

}  // namespace vaegail
