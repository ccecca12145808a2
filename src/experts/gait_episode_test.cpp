// The gait controller on the humanoid, whole episodes through the environment's physics-step
// hook: the walk stands, walks at the commanded speed and heading, and survives pushes.
#include "experts/gait_episode.h"
#include "experts/gait_eval.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vaegail {
namespace {

// The default walk from reset seed `seed`, with `pushes` random pushes.
GaitEpisodeResult default_walk(HumanoidEnv& env, std::uint64_t seed, int pushes) {
  GaitEpisodeOptions o;
  o.seed = seed;
  o.pushes = pushes;  // 200 N for 0.1 s each, at a time in [2, 8] s and a direction drawn from the seed
  return run_gait_episode(env, GaitParameters{}, o);
}

TEST(GaitEpisode, TheDefaultWalkStaysUpTenSecondsFromPerturbedStartsAboveOneMetrePerSecond) {
  HumanoidEnv env;
  for (std::uint64_t seed : {11, 12}) {
    const GaitEpisodeResult r = default_walk(env, seed, 0);
    EXPECT_FALSE(r.fallen) << seed;
    EXPECT_EQ(r.control_steps, env.episode_length());
    EXPECT_NEAR(r.time_up, 10.02, 1e-9);
    EXPECT_GT(r.speed, 1.0);
    EXPECT_GT(r.distance, 10.0);
    EXPECT_LT(std::abs(r.lateral_drift), 0.5);
    EXPECT_LT(r.heading_error, 0.1);
    EXPECT_GT(r.step_length, 0.35);
    EXPECT_NEAR(r.cadence, 60.0 * r.steps / r.time_up, 0.1 * r.cadence);
    EXPECT_NEAR(r.pelvis_height, r.style[kRootHeight], 1e-12);
    EXPECT_NEAR(r.signature[0], 1.2, 0.2);  // forward_speed over every step, the start included
  }
}

TEST(GaitEpisode, TheWalkSurvivesA200NewtonPushOnThePelvis) {
  HumanoidEnv env;
  for (std::uint64_t seed : {21, 22}) {
    const GaitEpisodeResult calm = default_walk(env, seed, 0), pushed = default_walk(env, seed, 1);
    EXPECT_FALSE(pushed.fallen) << seed;
    EXPECT_GT(std::abs(pushed.distance - calm.distance) + std::abs(pushed.lateral_drift - calm.lateral_drift), 0.02);
  }
}

TEST(GaitEpisode, TheCommandsSetTheSpeedAndTheHeading) {
  HumanoidEnv env;
  const GaitEpisodeResult slow = run_gait_episode(env, gait_parameters_from_json({{"speed", 0.8}}, "slow"), {});
  EXPECT_FALSE(slow.fallen);
  EXPECT_NEAR(slow.speed, 0.8, 0.15);
  const GaitEpisodeResult turned = run_gait_episode(env, gait_parameters_from_json({{"heading", 0.4}}, "turned"), {});
  EXPECT_FALSE(turned.fallen);
  EXPECT_LT(turned.final_heading_error, 0.1);
  EXPECT_NEAR(env.heading(), 0.4, 0.1);
  EXPECT_GT(turned.distance, 8.0);  // along the new heading
}

// DART's record: the noise moves the body off the clean walk, and each step's action is the
// clean controller's from the state the step starts in, not what the noise made of it.
TEST(GaitEpisode, UnderActionNoiseTheRecordIsTheCleanControllersActionAlongTheNoisyPath) {
  HumanoidEnv env;
  struct Record {
    std::vector<std::vector<float>> actions, observations;
    std::vector<std::vector<double>> applied;  // the ctrl of each step's last physics step
  };
  const auto walk = [&](double noise) {
    GaitEpisodeOptions o;
    o.seed = 21;
    o.steps = 30;
    o.action_noise = noise;
    Record r;
    run_gait_episode(env, GaitParameters{}, o, [&](const HumanoidEnv& at, const float* action, const StepOutcome*) {
      r.observations.push_back(at.observation());
      if (!action) return;
      r.actions.emplace_back(action, action + at.act_dim());
      r.applied.emplace_back(at.data()->ctrl, at.data()->ctrl + at.act_dim());
    });
    return r;
  };
  const Record clean = walk(0), noisy = walk(0.2), again = walk(0.2);
  ASSERT_EQ(noisy.actions.size(), 30u);
  EXPECT_EQ(noisy.actions, again.actions);  // the noise is drawn from the seed
  EXPECT_EQ(noisy.actions[0], clean.actions[0]);  // the same start: the clean action bit for bit
  EXPECT_EQ(noisy.observations[0], clean.observations[0]);
  EXPECT_NE(noisy.observations[1], clean.observations[1]);  // then the noise moves the body
  EXPECT_NE(noisy.actions[1], clean.actions[1]);            // and the labels follow the state
  // What the motors got differs from the label by about the noise (0.2 x sqrt(2 / pi) = 0.16 on
  // average, less where the box clips), while the clean walk applies its labels' neighbourhood.
  double noisy_gap = 0, clean_gap = 0;
  for (size_t t = 0; t < 30; ++t)
    for (size_t a = 0; a < noisy.actions[t].size(); ++a) {
      noisy_gap += std::abs(noisy.applied[t][a] - noisy.actions[t][a]) / (30.0 * noisy.actions[t].size());
      clean_gap += std::abs(clean.applied[t][a] - clean.actions[t][a]) / (30.0 * clean.actions[t].size());
    }
  EXPECT_GT(noisy_gap, 0.1);
  EXPECT_LT(noisy_gap, 0.2);
  EXPECT_LT(clean_gap, 0.05);
  for (const auto& action : noisy.actions)
    for (float a : action) ASSERT_LE(std::abs(a), 1.0f);  // labels are in the action box
}

// DAgger's record: on the learner's turns the motors get its action, held over the step and
// chosen from the step's first observation; every step records the clean controller's answer.
TEST(GaitEpisode, WithALearnerItActsOnItsShareOfStepsAndTheRecordIsTheControllersLabel) {
  HumanoidEnv env;
  static constexpr float kLearnerCommand = 0.05f;  // no gait controller holds every motor at one value
  struct Record {
    std::vector<std::vector<float>> labels, observations, asked;  // asked: what the learner was shown
    std::vector<bool> learner_acted;  // every physics step's ctrl was the learner's
  };
  const auto walk = [&](double share) {
    Record r;
    GaitEpisodeOptions o;
    o.seed = 31;
    o.steps = 20;
    o.learner_share = share;
    o.learner = [&](const float* observation, float* action) {
      r.asked.emplace_back(observation, observation + env.obs_dim());
      std::fill(action, action + env.act_dim(), kLearnerCommand);
    };
    run_gait_episode(env, GaitParameters{}, o, [&](const HumanoidEnv& at, const float* label, const StepOutcome*) {
      r.observations.push_back(at.observation());
      if (!label) return;
      r.labels.emplace_back(label, label + at.act_dim());
      const double* ctrl = at.data()->ctrl;
      r.learner_acted.push_back(std::all_of(ctrl, ctrl + at.act_dim(), [](double c) { return c == kLearnerCommand; }));
    });
    return r;
  };
  const Record alone = walk(0), always = walk(1), half = walk(0.5), again = walk(0.5);
  EXPECT_TRUE(alone.asked.empty());
  EXPECT_EQ(std::count(alone.learner_acted.begin(), alone.learner_acted.end(), true), 0);
  ASSERT_GE(always.labels.size(), 5u);  // it falls soon, but not at once
  EXPECT_EQ(std::count(always.learner_acted.begin(), always.learner_acted.end(), false), 0);
  ASSERT_EQ(always.asked.size(), always.labels.size());
  for (size_t t = 0; t < always.asked.size(); ++t) EXPECT_EQ(always.asked[t], always.observations[t]) << t;
  EXPECT_EQ(always.labels[0], alone.labels[0]);  // the same start: the controller's own first action
  EXPECT_NE(always.labels[3], alone.labels[3]);  // then labels of the states the learner led to
  for (const auto& label : always.labels)
    EXPECT_GT(*std::max_element(label.begin(), label.end()) - *std::min_element(label.begin(), label.end()), 0.1f);
  ASSERT_EQ(half.labels.size(), 20u);
  const auto turns = std::count(half.learner_acted.begin(), half.learner_acted.end(), true);
  EXPECT_EQ(turns, static_cast<long>(half.asked.size()));
  EXPECT_GE(turns, 4);  // Binomial(20, 0.5): 4 to 16 with probability 0.997
  EXPECT_LE(turns, 16);
  EXPECT_EQ(half.learner_acted, again.learner_acted);  // the turns are drawn from the seed
  EXPECT_EQ(half.labels, again.labels);
}

TEST(GaitEval, AStyleIsWalkedFromEachStartWithAndWithoutPushesAndItsMeansReported) {
  GaitEvalOptions o;
  o.episodes = 2;
  o.replay = true;
  int done = 0;
  const GaitStyleEvaluation e = evaluate_gait_style("walk", GaitParameters{}, o, [&] { ++done; });
  EXPECT_EQ(done, 2);
  EXPECT_EQ(e.falls, 0);
  EXPECT_EQ(e.pushed_falls, 0);
  EXPECT_GT(e.speed, 1.0);
  EXPECT_GT(e.cadence, 100.0);
  EXPECT_GT(e.control_steps_per_s, 0.0);
  // Held, the mean actions drift off within the episode (the prototype: 32-39 control steps).
  EXPECT_GT(e.replay_min, 5);
  EXPECT_LT(e.replay_max, 200);
  const auto row = gait_evaluation_row(e);
  EXPECT_EQ(row.front().first, "episodes");
  EXPECT_EQ(row.back().first, "signature_arm_swing");
  GaitStyleEvaluation measured = e;
  measured.raw_control_steps_per_s = 2000.0;
  const std::string table = format_gait_evaluations({e, measured});
  EXPECT_NE(table.find("walk                2/2      2/2"), std::string::npos) << table;
  EXPECT_EQ(table.find("ratio"), table.rfind("ratio"));  // only the style whose raw figure was measured
  EXPECT_NE(table.find(fmt::format("ratio {:.2f}", e.control_steps_per_s / 2000.0)), std::string::npos) << table;
}

}  // namespace
}  // namespace vaegail
