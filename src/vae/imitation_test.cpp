#include "vae/imitation.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "data/record.h"
#include "env/walker.h"

namespace vaegail::vae {
namespace {

constexpr int kEpisodes = 5;

WalkerOptions episodes_of(int length) {
  WalkerOptions o;
  o.episode_length = length;
  return o;
}

// Random-action demonstrations with their own seeds and target speeds.
DemoSet random_demos(const Env& env) {
  RecordRequest r;
  for (int i = 0; i < kEpisodes; ++i) {
    r.seeds.push_back(900 + 7 * i);
    r.contexts.push_back({i % 2 ? 3.0 : -1.0});
  }
  r.num_envs = 2;
  return DemoSet{"random", header_for(env), record_episodes(env, r, random_policy(env, 5))};
}

std::vector<int64_t> all(const DemoSet& d) {
  std::vector<int64_t> i(d.episodes.size());
  for (size_t j = 0; j < i.size(); ++j) i[j] = static_cast<int64_t>(j);
  return i;
}

// z = the episode's index; replays that episode's recorded actions step by step.
LatentPolicy open_loop(const DemoSet& demos, std::vector<int>& steps) {
  return [&demos, &steps](const torch::Tensor& obs, const torch::Tensor& z) {
    const int64_t A = demos.header.act_dim();
    auto out = torch::empty({obs.size(0), A});
    for (int64_t r = 0; r < obs.size(0); ++r) {
      const int i = static_cast<int>(z[r][0].item<float>());
      const float* a = demos.episodes[i].actions.data() + steps[i]++ * A;
      std::copy(a, a + A, out[r].data_ptr<float>());
    }
    return out;
  };
}

torch::Tensor index_latents(int64_t n) { return torch::arange(n, torch::kFloat).unsqueeze(1); }

TEST(ImitationTest, RolloutsStartFromTheDemonstrationsInitialStates) {
  const WalkerEnv env(episodes_of(60));
  const auto demos = random_demos(env);
  const auto zero = [](const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 6}); };
  const auto out = roll_out_latent_policy(env, rollout_starts(demos, all(demos)), torch::zeros({kEpisodes, 2}), zero);
  ASSERT_EQ(out.size(), static_cast<size_t>(kEpisodes));
  for (int i = 0; i < kEpisodes; ++i) {
    const auto& demo = demos.episodes[i].observations;
    const auto& rollout = out[i].episode.observations;
    EXPECT_TRUE(std::equal(demo.begin(), demo.begin() + 18, rollout.begin())) << "episode " << i;
    EXPECT_EQ(out[i].episode.context, demos.episodes[i].context);
  }
  // ...and they differ between demonstrations, so the check above can fail.
  EXPECT_FALSE(std::equal(demos.episodes[0].observations.begin(), demos.episodes[0].observations.begin() + 18,
                          demos.episodes[1].observations.begin()));
}

TEST(ImitationTest, AStartSeedDrawsFreshInitialStatesRepeatably) {
  const WalkerEnv env(episodes_of(20));
  const auto demos = random_demos(env);
  const auto zero = [](const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 6}); };
  const auto starts = rollout_starts(demos, all(demos));
  const auto z = torch::zeros({kEpisodes, 2});
  ImitationOptions seeded;
  seeded.start_seed = 1;
  const auto a = roll_out_latent_policy(env, starts, z, zero, seeded);
  const auto again = roll_out_latent_policy(env, starts, z, zero, seeded);
  seeded.start_seed = 2;
  const auto other = roll_out_latent_policy(env, starts, z, zero, seeded);
  for (int i = 0; i < kEpisodes; ++i) {
    const auto first = [](const std::vector<float>& o) { return std::vector<float>(o.begin(), o.begin() + 18); };
    const auto demo = first(demos.episodes[i].observations);
    EXPECT_NE(first(a[i].episode.observations), demo) << "episode " << i;
    EXPECT_NE(first(a[i].episode.observations), first(other[i].episode.observations)) << "episode " << i;
    EXPECT_EQ(a[i].episode.observations, again[i].episode.observations) << "episode " << i;
    EXPECT_EQ(a[i].episode.context, demos.episodes[i].context);
    // the same distribution: the walker's reset (joint angles +-0.1 rad, velocities +-0.05) about the same pose
    for (size_t k = 0; k < demo.size(); ++k) EXPECT_NEAR(a[i].episode.observations[k], demo[k], 0.2) << k;
  }
}

TEST(ImitationTest, ReplayingTheDemoActionsReproducesTheDemoSpeed) {
  const WalkerEnv env(episodes_of(60));
  const auto demos = random_demos(env);
  std::vector<int> steps(kEpisodes, 0);
  ImitationOptions o;
  o.num_envs = 3;  // fewer than the episodes: slots are reused
  const auto out = roll_out_latent_policy(env, rollout_starts(demos, all(demos)), index_latents(kEpisodes),
                                          open_loop(demos, steps), o);
  for (int i = 0; i < kEpisodes; ++i) {
    const Episode& demo = demos.episodes[i];
    EXPECT_EQ(out[i].achieved_speed, demo.attributes.at("mean_com_speed")) << "episode " << i;
    EXPECT_EQ(out[i].episode.observations, demo.observations);
    EXPECT_EQ(out[i].fell, static_cast<bool>(demo.terminations.back()));
  }
}

TEST(ImitationTest, ALimpWalkerFalls) {
  const WalkerEnv env(episodes_of(300));
  const auto demos = random_demos(env);
  const auto limp = [](const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 6}); };
  const auto out = roll_out_latent_policy(env, rollout_starts(demos, {0, 1}), torch::zeros({2, 1}), limp);
  EXPECT_TRUE(out[0].fell && out[1].fell);
  EXPECT_LT(out[0].episode.length(), 300);
}

TEST(ImitationTest, RejectsMismatchedLatentsAndActions) {
  const WalkerEnv env(episodes_of(5));
  const auto demos = random_demos(env);
  const auto starts = rollout_starts(demos, {0, 1});
  const auto wrong = [](const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 5}); };
  const auto zero = [](const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 6}); };
  EXPECT_THROW(roll_out_latent_policy(env, starts, torch::zeros({3, 1}), zero), std::invalid_argument);
  EXPECT_THROW(roll_out_latent_policy(env, starts, torch::zeros({2, 1}), wrong), std::invalid_argument);
}

TEST(ImitationTest, MedianAbsoluteDifference) {
  EXPECT_EQ(median_abs_difference({1, 2, 3}, {1.5, 0, 3}), 0.5);
  EXPECT_EQ(median_abs_difference({0, 0, 0, 0}, {1, -2, 3, 4}), 2.5);
  EXPECT_EQ(median_abs_difference({}, {}), 0.0);
}

}  // namespace
}  // namespace vaegail::vae
