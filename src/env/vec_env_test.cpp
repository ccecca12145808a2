#include "env/vec_env.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "env/walker.h"
#include "util/rng.h"

namespace vaegail {
namespace {

// A fixed deterministic feedback policy, so trajectories depend on the observations.
void policy(const float* obs, float* action) {
  for (int a = 0; a < 6; ++a) {
    double s = 0;
    for (int k = 0; k < 18; ++k) s += std::sin(1.7 * a + 0.3 * k) * obs[k];
    action[a] = static_cast<float>(std::tanh(0.5 * s));
  }
}

using Trajectory = std::vector<float>;  // concatenated observations and rewards

std::vector<Trajectory> run(int num_envs, int threads, int steps) {
  WalkerEnv proto;
  VecEnv vec(proto, num_envs, threads);
  vec.set_auto_reset(true);
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < num_envs; ++i) seeds.push_back(1000 + i);
  vec.reset(seeds);
  std::vector<Trajectory> out(num_envs);
  std::vector<float> actions(num_envs * 6);
  for (int t = 0; t < steps; ++t) {
    for (int i = 0; i < num_envs; ++i) policy(&vec.observations()[i * 18], &actions[i * 6]);
    vec.step(actions.data());
    for (int i = 0; i < num_envs; ++i) {
      const float* o = &vec.observations()[i * 18];
      out[i].insert(out[i].end(), o, o + 18);
      out[i].push_back(vec.rewards()[i]);
    }
  }
  return out;
}

TEST(VecEnv, TrajectoriesAreBitIdenticalWhateverTheEnvAndThreadCounts) {
  const int steps = 300;  // long enough for several falls and automatic resets
  const auto reference = run(1, 1, steps);
  for (auto [n, threads] : {std::pair{3, 1}, {3, 2}, {8, 4}, {8, 8}}) {
    const auto other = run(n, threads, steps);
    EXPECT_EQ(other[0], reference[0]) << n << " envs, " << threads << " threads";
  }
  const auto a = run(8, 2, steps), b = run(8, 3, steps);
  EXPECT_EQ(a, b);
}

TEST(VecEnv, AutoResetFollowsTheDocumentedSeedStream) {
  WalkerEnv proto;
  VecEnv vec(proto, 1, 1);
  vec.set_auto_reset(true);
  vec.reset({77});
  WalkerEnv solo;
  solo.reset(77);
  const std::vector<float> limp(6, 0.f);
  while (vec.episode_index(0) == 0) {
    vec.step(limp.data());
    solo.step(limp.data());
  }
  // The finished episode's last observation is kept, the next episode starts from seed k=1.
  EXPECT_EQ(std::vector<float>(vec.final_observations().begin(), vec.final_observations().end()), solo.observation());
  EXPECT_TRUE(vec.terminated()[0]);
  solo.reset(derive_seed(77, 1));
  EXPECT_EQ(std::vector<float>(vec.observations().begin(), vec.observations().end()), solo.observation());
}

TEST(VecEnv, RejectsAWrongNumberOfSeeds) {
  WalkerEnv proto;
  VecEnv vec(proto, 2, 1);
  EXPECT_THROW(vec.reset({1}), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail
