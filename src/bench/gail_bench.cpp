#include "bench/gail_bench.h"

#include <filesystem>
#include <fmt/format.h>
#include <random>

#include "util/world.h"

namespace vaegail {

namespace fs = std::filesystem;

namespace {

// Removes the bench's run directory however the bench ends.
struct ScratchDir {
  fs::path path;
  ScratchDir() : path(fs::temp_directory_path() / ("vaegail-bench-gail-" + std::to_string(std::random_device{}()))) {}
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

}  // namespace

GailBenchResult run_gail_bench(const GailBenchOptions& options, const DemoSet& demos, vae::TrajectoryVae vae) {
  if (options.iterations < 1) throw std::invalid_argument("bench gail: iterations must be positive");
  GailBenchResult r;
  r.ranks = World::get().size();
  if (r.ranks == 1) {
    PhysicsBenchOptions physics;
    physics.env = options.env;
    physics.seconds = options.physics_seconds;
    physics.num_envs = options.gail.num_envs;
    physics.threads = options.gail.env_threads;
    r.physics = run_physics_bench(physics);
  }

  const auto env = make_env(options.env);
  const ScratchDir scratch;
  GailOptions gail = options.gail;
  gail.iterations = options.iterations + 1;
  gail.minutes = 0;
  GailTrainer trainer(demos, vae, *env, gail, scratch.path.string());
  const GailMetrics warm_up = trainer.iterate();
  r.steps_per_iteration = warm_up.steps;
  for (r.iterations = 0; r.iterations < options.iterations; ++r.iterations) {
    trainer.iterate();
    r.phases += trainer.last_phase_seconds();
  }
  return r;
}

std::string format_gail_bench(const GailBenchOptions& o, const GailBenchResult& r) {
  const double per_it = r.seconds_per_iteration();
  const auto share = [&](double seconds) { return 100.0 * seconds / r.phases.total(); };
  const auto phase = [&](const char* name, double seconds) {
    return fmt::format("  {:<16} {:8.3f} s  {:5.1f}%\n", name, seconds / r.iterations, share(seconds));
  };
  const std::string head = fmt::format(
      "bench gail: {}, {} mode, {} environments x {} steps per iteration on {} rank(s) x {} env thread(s), "
      "{} timed iterations (after one warm-up), {} Torch thread(s)\n"
      "per iteration      {:8.3f} s\n",
      o.env.task, to_string(o.gail.mode), o.gail.num_envs, r.steps_per_iteration / o.gail.num_envs, r.ranks, o.gail.env_threads,
      r.iterations, torch::get_num_threads(), per_it);
  const std::string phases = phase("rollout", r.phases.rollout) + phase("TRPO + critic", r.phases.policy_update) +
                             phase("discriminator", r.phases.discriminator) +
                             phase("log + checkpoint", r.phases.bookkeeping);
  if (r.ranks > 1)
    return head + phases +
           fmt::format("env steps/s        {:8.0f} during fine-tuning (rank 0's clock)\n"
                       "ceilings           not measured under mpirun: see scripts/bench/gail_ranks.sh\n",
                       r.env_steps_per_s());
  return head + phases +
         fmt::format(
             "env steps/s        {:8.0f} during fine-tuning\n"
             "ceilings           {:8.0f} control steps/s raw physics on {} cores at once ({:.0f} on one), {:.0f} VecEnv + 2x{} tanh MLP\n"
             "ratio              {:8.3f} of the all-core raw physics ceiling{}, {:.3f} of one core's, {:.3f} of VecEnv + MLP\n",
             r.env_steps_per_s(), r.physics.all_core_control_steps_per_s, r.physics.cores,
             r.physics.raw_control_steps_per_s, r.physics.vec_control_steps_per_s, PhysicsBenchOptions().hidden,
             r.all_core_ratio(), r.all_core_ratio() >= 0.7 ? " (goal >= 0.7: met)" : " (goal >= 0.7: NOT met)",
             r.env_steps_per_s() / r.physics.raw_control_steps_per_s,
             r.env_steps_per_s() / r.physics.vec_control_steps_per_s);
}

nlohmann::json gail_bench_json(const GailBenchOptions& o, const GailBenchResult& r) {
  nlohmann::json j = {{"task", o.env.task},
                      {"mode", to_string(o.gail.mode)},
                      {"envs", o.gail.num_envs},
                      {"env_threads", o.gail.env_threads},
                      {"ranks", r.ranks},
                      {"iterations", r.iterations},
                      {"steps_per_iteration", r.steps_per_iteration},
                      {"seconds_per_iteration", r.seconds_per_iteration()},
                      {"env_steps_per_s", r.env_steps_per_s()},
                      {"rollout_s", r.phases.rollout / r.iterations},
                      {"policy_update_s", r.phases.policy_update / r.iterations},
                      {"discriminator_s", r.phases.discriminator / r.iterations},
                      {"bookkeeping_s", r.phases.bookkeeping / r.iterations}};
  if (r.ranks == 1) {
    j["all_core_control_steps_per_s"] = r.physics.all_core_control_steps_per_s;
    j["raw_control_steps_per_s"] = r.physics.raw_control_steps_per_s;
    j["all_core_ratio"] = r.all_core_ratio();
  }
  return j;
}

}  // namespace vaegail
