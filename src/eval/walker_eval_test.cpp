#include "eval/walker_eval.h"

#include <gtest/gtest.h>

#include "data/record.h"
#include "env/walker.h"

namespace vaegail::eval {
namespace {

WalkerOptions short_episodes() {
  WalkerOptions o;
  o.episode_length = 40;
  return o;
}

// Zero-action demonstrations of three "experts"; the last one held out.
DemoSet zero_demos(const Env& env) {
  DemoSet demos{"zero", header_for(env), {}};
  for (int expert = 0; expert < 3; ++expert) {
    RecordRequest r;
    r.expert_id = "expert" + std::to_string(expert);
    for (int i = 0; i < 3; ++i) {
      r.seeds.push_back(100 * expert + i);
      r.contexts.push_back({double(expert)});
    }
    for (auto& e : record_episodes(env, r, zero_policy(env))) {
      e.attributes["held_out"] = expert == 2;
      demos.episodes.push_back(std::move(e));
    }
  }
  return demos;
}

torch::Tensor zero_actions(const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 6}); }
torch::Tensor full_actions(const torch::Tensor& obs, const torch::Tensor&) { return torch::ones({obs.size(0), 6}); }

TEST(WalkerEval, TakesTheFirstEpisodesOfEveryExpert) {
  const WalkerEnv env(short_episodes());
  const auto demos = zero_demos(env);
  EXPECT_EQ(episodes_per_expert(demos, 2), (std::vector<int64_t>{0, 1, 3, 4, 6, 7}));
  EXPECT_EQ(episodes_per_expert(demos, 5).size(), 9u);
}

TEST(WalkerEval, ReplayingTheDemonstratorMatchesItsSpeedExactly) {
  const WalkerEnv env(short_episodes());
  const auto demos = zero_demos(env);
  const auto episodes = episodes_per_expert(demos, 2);
  const auto z = torch::zeros({static_cast<int64_t>(episodes.size()), 3});
  const auto rows = imitate_with_policies(env, demos, episodes, z, {{"same", zero_actions}, {"other", full_actions}});
  ASSERT_EQ(rows.size(), 2 * episodes.size());
  for (size_t j = 0; j < episodes.size(); ++j) {
    // The same policy from the same initial state reproduces the demonstration.
    EXPECT_EQ(rows[j].policy, "same");
    EXPECT_NEAR(rows[j].abs_difference(), 0.0, 1e-9);
    EXPECT_EQ(rows[j].held_out, demos.episodes[episodes[j]].expert_id == "expert2");
    EXPECT_EQ(rows[j].target, demos.episodes[episodes[j]].context[0]);
    EXPECT_GT(rows[episodes.size() + j].abs_difference(), 1e-3);
  }

  const auto summaries = summarize(rows);
  ASSERT_EQ(summaries.size(), 4u);  // {same, other} x {training, held out}
  EXPECT_EQ(summaries[0].policy, "same");
  EXPECT_FALSE(summaries[0].held_out);
  EXPECT_EQ(summaries[0].demonstrations, 4);
  EXPECT_EQ(summaries[1].demonstrations, 2);
  EXPECT_NEAR(summaries[0].median_abs_difference, 0.0, 1e-9);
  EXPECT_GT(summaries[2].mean_abs_difference, 1e-3);
  const auto table = summary_table(summaries);
  EXPECT_NE(table.find("held-out experts (one-shot)"), std::string::npos);
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 6);
  EXPECT_EQ(table.find("target"), std::string::npos);

  const auto by_target = summarize(rows, /*by_target=*/true);
  int demonstrations = 0;
  for (const auto& s : by_target) {
    demonstrations += s.demonstrations;
    for (const auto& r : rows)  // every row of a group has its target
      if (r.policy == s.policy && r.held_out == s.held_out && r.target == s.target) EXPECT_FALSE(std::isnan(s.target));
  }
  EXPECT_EQ(demonstrations, static_cast<int>(rows.size()));
  EXPECT_GT(by_target.size(), summaries.size());
  EXPECT_NE(summary_table(by_target).find("target (m/s)"), std::string::npos);
}

TEST(WalkerEval, SummaryMediansAgainstHandComputedValues) {
  auto row = [](const char* policy, double target, double demo, double achieved, bool fell) {
    ImitationRow r;
    r.policy = policy;
    r.target = target;
    r.demo_speed = demo;
    r.achieved_speed = achieved;
    r.fell = fell;
    return r;
  };
  const std::vector<ImitationRow> rows = {row("p", 1, 1.0, 0.5, false), row("p", 1, 1.0, 0.9, true),
                                          row("p", 3, 3.0, 1.0, true)};
  const auto all = summarize(rows);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(all[0].median_abs_difference, 0.5, 1e-12);  // |Δ| = 0.5, 0.1, 2.0
  EXPECT_NEAR(all[0].mean_abs_difference, 2.6 / 3, 1e-12);
  EXPECT_NEAR(all[0].median_achieved_speed, 0.9, 1e-12);
  EXPECT_NEAR(all[0].fall_rate, 2.0 / 3, 1e-12);
  EXPECT_TRUE(std::isnan(all[0].target));
  const auto by_target = summarize(rows, /*by_target=*/true);
  ASSERT_EQ(by_target.size(), 2u);
  EXPECT_EQ(by_target[0].target, 1);
  EXPECT_NEAR(by_target[0].median_abs_difference, 0.3, 1e-12);
  EXPECT_NEAR(by_target[0].median_achieved_speed, 0.7, 1e-12);
  EXPECT_NEAR(by_target[1].fall_rate, 1.0, 1e-12);
}

TEST(WalkerEval, RejectsEmbeddingsOfTheWrongCount) {
  const WalkerEnv env(short_episodes());
  const auto demos = zero_demos(env);
  EXPECT_THROW(imitate_with_policies(env, demos, {0, 1}, torch::zeros({3, 2}), {{"same", zero_actions}}),
               std::invalid_argument);
}

TEST(ModeCoverage, CountsATargetWhenEnoughSpeedsLieNearIt) {
  const std::vector<double> targets{-1, 0, 1, 3};
  // 18 speeds near 1 m/s and one each near -1 and 3: 5% of 20 is exactly one speed.
  std::vector<double> speeds(18, 1.2);
  speeds.push_back(-0.6);
  speeds.push_back(3.5);
  const auto c = mode_coverage("p", speeds, targets);
  EXPECT_EQ(c.fractions, (std::vector<double>{0.05, 0.0, 0.9, 0.05}));
  EXPECT_EQ(c.covered, 3);
  // A collapsed policy covers one mode.
  EXPECT_EQ(mode_coverage("p", std::vector<double>(20, 0.1), targets).covered, 1);
  ModeCoverageOptions strict;
  strict.min_fraction = 0.1;
  EXPECT_EQ(mode_coverage("p", speeds, targets, strict).covered, 1);
}

TEST(ModeCoverage, ComparesEachPolicyWithTheTrainingDemonstrations) {
  std::vector<ImitationRow> rows;
  for (const double target : {0.0, 1.0}) {
    for (const std::string policy : {"vae", "plain_gail"}) {
      ImitationRow r;
      r.policy = policy;
      r.target = target;
      r.demo_speed = target;
      r.achieved_speed = policy == "vae" ? target : 0.0;
      rows.push_back(r);
    }
  }
  ImitationRow held = rows.front();
  held.held_out = true;
  held.target = 7;
  rows.push_back(held);
  const auto coverages = mode_coverages(rows);
  ASSERT_EQ(coverages.size(), 3u);
  EXPECT_EQ(coverages[0].source, "demonstrations");
  EXPECT_EQ(coverages[0].covered, 2);
  EXPECT_EQ(coverages[1].covered, 2);
  EXPECT_EQ(coverages[2].source, "plain_gail");
  EXPECT_EQ(coverages[2].covered, 1);
  const auto table = mode_table(coverages, {0, 1});
  EXPECT_NE(table.find("| plain_gail | 100% | 0% | 1 of 2 |"), std::string::npos) << table;
}

}  // namespace
}  // namespace vaegail::eval
