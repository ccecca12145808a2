// `vaegail bench gail`: wall-clock per fine-tuning iteration (Algorithm 1) and environment steps
// per second, split by phase and set against the physics ceiling measured in the same run.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bench/physics_bench.h"
#include "data/demos.h"
#include "env/registry.h"
#include "gail/diverse_gail.h"
#include "vae/trajectory_vae.h"

namespace vaegail {

struct GailBenchOptions {
  GailOptions gail;         // mode, environments, network sizes as `gail train`
  EnvRequest env;           // the demonstrations' environment
  int iterations = 5;       // timed, after one untimed warm-up iteration
  double physics_seconds = 3.0;
};

struct GailBenchResult {
  int ranks = 1;                       // processes of the run (mpirun -np), util/world.h
  int iterations = 0;
  std::int64_t steps_per_iteration = 0;
  GailPhaseSeconds phases;             // summed over the timed iterations
  PhysicsBenchResult physics;          // same machine, same run; not measured under ranks
  double seconds_per_iteration() const { return phases.total() / iterations; }
  double env_steps_per_s() const { return steps_per_iteration / seconds_per_iteration(); }
  double all_core_ratio() const { return env_steps_per_s() / physics.all_core_control_steps_per_s; }
};

// Trains in a temporary run directory that is removed afterwards; `vae` is needed in diverse mode.
// Under mpirun the ranks train one run together and the physics ceilings are not measured (each
// rank's would compete with the others' for the cores): scripts/bench/gail_ranks.sh sets a
// ranked run against a single process in the same window.
GailBenchResult run_gail_bench(const GailBenchOptions& options, const DemoSet& demos, vae::TrajectoryVae vae);
std::string format_gail_bench(const GailBenchOptions& options, const GailBenchResult& result);
// The figures as JSON (name → value), for scripts.
nlohmann::json gail_bench_json(const GailBenchOptions& options, const GailBenchResult& result);

}  // namespace vaegail
