#include "data/record.h"

#include <cmath>

#include <gtest/gtest.h>

#include "env/walker.h"

namespace vaegail {
namespace {

RecordRequest request(int episodes, int envs, int threads) {
  RecordRequest r;
  for (int i = 0; i < episodes; ++i) r.seeds.push_back(500 + i);
  for (int i = 0; i < episodes; ++i) r.contexts.push_back({i % 2 ? 1.0 : -1.0});
  r.expert_id = "random";
  r.num_envs = envs;
  r.num_threads = threads;
  return r;
}

TEST(Record, EpisodesDoNotDependOnBatchingOrThreads) {
  WalkerEnv env;
  const auto a = record_episodes(env, request(5, 1, 1), random_policy(env, 3));
  const auto b = record_episodes(env, request(5, 4, 2), random_policy(env, 3));
  ASSERT_EQ(a.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(a[i].observations, b[i].observations);
    EXPECT_EQ(a[i].actions, b[i].actions);
    EXPECT_EQ(a[i].features, b[i].features);
    EXPECT_EQ(a[i].context, (std::vector<double>{i % 2 ? 1.0 : -1.0}));
  }
}

TEST(Record, EpisodeMatchesAHandRolledEpisodeAndTheFormat) {
  WalkerEnv env;
  const auto episodes = record_episodes(env, request(1, 1, 1), zero_policy(env));
  const Episode& e = episodes[0];
  validate_episode(e, header_for(env), "recorded");
  WalkerEnv solo;
  solo.set_context({-1.0});
  solo.reset(500);
  const std::vector<float> zero(6, 0.f);
  for (int t = 0; t < e.length(); ++t) solo.step(zero.data());
  const auto last = solo.observation();
  EXPECT_EQ(std::vector<float>(e.observations.end() - 18, e.observations.end()), last);
  // A limp walker falls: the last step terminates, and the episode carries its mean speed.
  EXPECT_TRUE(e.terminations.back());
  EXPECT_EQ(e.attributes.count("mean_com_speed"), 1u);
}

TEST(Record, ExecutionNoiseMovesTheStatesButNotTheRecordedActions) {
  WalkerEnv env;
  const auto clean = record_episodes(env, request(3, 1, 1), zero_policy(env));
  RecordRequest noisy = request(3, 1, 1);
  noisy.execution_noise_std = 0.3;
  noisy.execution_noise_seed = 9;
  const auto a = record_episodes(env, noisy, zero_policy(env));
  RecordRequest rebatched = request(3, 3, 2);
  rebatched.execution_noise_std = 0.3;
  rebatched.execution_noise_seed = 9;
  const auto b = record_episodes(env, rebatched, zero_policy(env));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a[i].actions, std::vector<float>(a[i].actions.size(), 0.f));  // the label is the policy's
    EXPECT_NE(a[i].observations, clean[i].observations);                   // the execution was not
    EXPECT_EQ(a[i].observations, b[i].observations);                       // noise per episode
  }
}

TEST(Record, AnEpisodeOffsetIsConstantWithinAnEpisodeAndRecorded) {
  WalkerEnv env;
  const BoxSpec box = env.action_spec();
  const int act_dim = box.dim(), episodes = 40;
  const auto a = record_episodes(env, request(episodes, 1, 1), with_episode_offset(zero_policy(env), box, 0.1, 4));
  const auto b = record_episodes(env, request(episodes, 7, 2), with_episode_offset(zero_policy(env), box, 0.1, 4));
  double sum_sq = 0;
  for (int i = 0; i < episodes; ++i) {
    const std::vector<float> first(a[i].actions.begin(), a[i].actions.begin() + act_dim);
    for (int t = 1; t < a[i].length(); ++t)
      EXPECT_EQ(std::vector<float>(a[i].actions.begin() + t * act_dim, a[i].actions.begin() + (t + 1) * act_dim), first);
    EXPECT_EQ(a[i].actions, b[i].actions);  // drawn per episode, not per batch
    if (i > 0) EXPECT_NE(std::vector<float>(a[i - 1].actions.begin(), a[i - 1].actions.begin() + act_dim), first);
    for (float u : first) sum_sq += u * u;
  }
  // 240 draws of N(0, 0.1^2): the sample std lies within 0.1 +- 0.015 (about 3 standard errors).
  EXPECT_NEAR(std::sqrt(sum_sq / (episodes * act_dim)), 0.1, 0.015);
}

}  // namespace
}  // namespace vaegail
