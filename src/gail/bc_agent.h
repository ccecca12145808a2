// The agent of a `bc train` run, apart from its trainer (behavior_cloning.h) so that the
// deployment library (src/controller) loads it without the training code: the options as
// config.json stores them, the agent they build, and the trained one of a run directory.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rl/agent.h"

namespace vaegail {

struct BcOptions {
  std::vector<int> hidden = {200, 100};  // the GAIL policy's sizes (Table 2, walker)
  int epochs = 100;
  int batch_size = 256;
  double learning_rate = 1e-3;  // Adam; the paper gives no BC settings
  double init_log_std = -1.0;
  std::uint64_t seed = 0;
  std::string device = "cpu";
  std::string demos_path;  // for the record
};

// config.json: every field under its own name; a missing key takes the struct's default.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(BcOptions, hidden, epochs, batch_size, learning_rate, init_log_std, seed,
                                                device, demos_path)

// The BC agent before training: normaliser frozen at observations' [M, obs_dim] statistics.
std::shared_ptr<Agent> make_bc_agent(const BcOptions& options, const torch::Tensor& observations, int act_dim);

// The trained agent of a `bc train` run (its directory, RUN/checkpoints/latest.pt or its weights
// file: gail/run_dir.h's open_run), on `device`. Throws naming the file.
std::shared_ptr<Agent> load_bc_agent(const std::string& run, int obs_dim, int act_dim, torch::Device device);

}  // namespace vaegail
