#include <torch/torch.h>

#include <cstdio>

#include "bench/physics_bench.h"
#include "cli/commands.h"
#include "cli/task_options.h"

namespace vaegail::cli {

namespace {
struct PhysicsFlags {
  TaskOptions task;
  PhysicsBenchOptions bench;
};
}  // namespace

void add_bench_commands(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "measure throughput against this machine's ceilings");
  bench->require_subcommand(1);
  auto flags = std::make_shared<PhysicsFlags>();
  CLI::App* physics = bench->add_subcommand(
      "physics", "raw mj_step throughput vs VecEnv rollouts with a 2-layer tanh MLP policy in the loop");
  add_task_options(*physics, flags->task);
  physics->add_option("--seconds", flags->bench.seconds, "measuring time per configuration")
      ->check(CLI::Range(0.1, 3600.0))->capture_default_str();
  physics->add_option("--envs", flags->bench.num_envs, "environments in the VecEnv")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  physics->add_option("--threads", flags->bench.threads, "threads stepping the environments")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  physics->add_option("--hidden", flags->bench.hidden, "policy layer width")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  physics->callback([flags] {
    flags->bench.env = flags->task.request();
    const PhysicsBenchResult r = run_physics_bench(flags->bench);
    std::fputs(format_physics_bench(flags->bench, r).c_str(), stdout);
  });
}

}  // namespace vaegail::cli
