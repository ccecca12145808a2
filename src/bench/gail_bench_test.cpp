#include "bench/gail_bench.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "env/walker.h"
#include "gail/test_support.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

int bench_dirs_in_temp() {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    n += entry.path().filename().string().rfind("vaegail-bench-gail-", 0) == 0;
  return n;
}

GailBenchOptions tiny_bench(GailMode mode) {
  GailBenchOptions o;
  o.env.task = "walker";
  o.env.episode_length = 8;
  o.iterations = 2;
  o.physics_seconds = 0.05;
  o.gail.mode = mode;
  o.gail.num_envs = 3;
  o.gail.policy_hidden = o.gail.critic_hidden = {16};
  o.gail.discriminator_hidden = {8};
  return o;
}

TEST(GailBench, TimesEveryPhaseOfTheTimedIterationsAndLeavesNoRunDirectory) {
  const auto env = make_env(tiny_bench(GailMode::Diverse).env);
  const DemoSet demos = random_walker_demos(*env, 4);
  const int before = bench_dirs_in_temp();
  for (const GailMode mode : {GailMode::Diverse, GailMode::Plain}) {
    const GailBenchOptions o = tiny_bench(mode);
    const vae::TrajectoryVae model(tiny_vae_config(env->obs_dim(), env->act_dim()));
    const GailBenchResult r = run_gail_bench(o, demos, mode == GailMode::Diverse ? model : vae::TrajectoryVae(nullptr));
    EXPECT_EQ(r.iterations, 2);
    EXPECT_EQ(r.steps_per_iteration, 3 * 8);  // the warm-up's: steps per iteration, not cumulative
    EXPECT_GT(r.phases.rollout, 0);
    EXPECT_GT(r.phases.policy_update, 0);
    EXPECT_GT(r.phases.discriminator, 0);
    EXPECT_GT(r.phases.bookkeeping, 0);
    EXPECT_DOUBLE_EQ(r.env_steps_per_s(), 24.0 * 2 / r.phases.total());
    EXPECT_GT(r.physics.raw_control_steps_per_s, 0);
    EXPECT_NE(format_gail_bench(o, r).find("env steps/s"), std::string::npos);
  }
  EXPECT_EQ(bench_dirs_in_temp(), before);
}

}  // namespace
}  // namespace vaegail
