// `vaegail bench vae`: training throughput of the trajectory VAE against this machine's
// matrix-multiply ceiling, measured in one run (recorded figures: docs/benchmarks.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "vae/vae_config.h"

namespace vaegail {

struct VaeBenchOptions {
  vae::VaeConfig config = vae::VaeConfig::walker();
  int batch = 32;          // trajectories per training step
  int steps = 400;         // steps per trajectory (the walker's 10 s episodes)
  double seconds = 3.0;    // measuring time per part (at least one timed run each)
  int epoch_episodes = 1200;  // the paper-scale walker set the epoch time is projected for
  int epoch_steps = 400;
  double epoch_target_seconds = 120.0;  // the bar
};

struct VaeBenchResult {
  int threads = 1;
  double sgemm_model_gflops = 0;   // torch::mm [B*T*D, 2C] x [2C, 2C]: the state decoder's GEMM
  double sgemm_square_gflops = 0;  // torch::mm 1024^3: the machine's ceiling
  double step_seconds = 0;         // a whole training step: forward, backward, Adam
  // forward + backward of each part alone on the same batch (they do not sum to the step
  // exactly: the step adds the loss glue and Adam)
  double encoder_seconds = 0, action_decoder_seconds = 0, state_decoder_seconds = 0;
  double state_decoder_gflops = 0;  // analytic matmul FLOPs / state_decoder_seconds
  double reference_state_decoder_seconds = 0;  // the conv1d implementation, same batch
  double peak_rss_mb = 0;

  double steps_per_second(const VaeBenchOptions& o) const { return o.batch * o.steps / step_seconds; }
  double epoch_seconds(const VaeBenchOptions& o) const {
    return o.epoch_episodes * static_cast<double>(o.epoch_steps) / steps_per_second(o);
  }
};

VaeBenchResult run_vae_bench(const VaeBenchOptions& options);
std::string format_vae_bench(const VaeBenchOptions& options, const VaeBenchResult& result);

// `vaegail bench vae --trainer-batches N`: the trainer itself (vae/vae_trainer.h: each rank's
// share of a batch, the gradients summed over the ranks, Adam) on random trajectories of the
// bench's shape, in a temporary run directory: two epochs of N batches of options.batch, the
// faster one kept. Under mpirun the ranks train one run together; scripts/bench/vae_ranks.sh sets
// K ranks against one process in the same window.
struct VaeTrainerBenchResult {
  int ranks = 1;  // processes of the run (mpirun -np), util/world.h
  int batches = 0;
  double seconds = 0;  // the faster epoch's minibatches (EpochMetrics::train_seconds)
  double trajectory_steps_per_s(const VaeBenchOptions& o) const {
    return static_cast<double>(batches) * o.batch * o.steps / seconds;
  }
};
VaeTrainerBenchResult run_vae_trainer_bench(const VaeBenchOptions& options, int batches);
std::string format_vae_trainer_bench(const VaeBenchOptions& options, const VaeTrainerBenchResult& result);
// The figures as JSON (name -> value), for scripts.
nlohmann::json vae_trainer_bench_json(const VaeBenchOptions& options, const VaeTrainerBenchResult& result);

// Matmul FLOPs of one forward + backward of the state decoder on `positions` (x_t, x_{t+1})
// pairs (backward counted as twice the forward).
double state_decoder_flops(const vae::VaeConfig& config, double positions);

}  // namespace vaegail
