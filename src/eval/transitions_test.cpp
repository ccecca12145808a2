#include "eval/transitions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "data/record.h"
#include "env/humanoid.h"
#include "env/walker.h"
#include "vae/toy_trajectories.h"
#include "vae/trained_vae.h"

namespace vaegail::eval {
namespace {

// 40-step episodes that run to their end whatever happens, so that a rollout always reaches
// its blend.
WalkerOptions unending_short_episodes() {
  WalkerOptions o;
  o.episode_length = 40;
  o.terminate_on_fall = false;
  return o;
}

// Random-action demonstrations at target speeds -1, 1, 3 and 1.
DemoSet random_demos(const Env& env) {
  RecordRequest r;
  r.expert_id = "random";
  for (const double target : {-1.0, 1.0, 3.0, 1.0}) {
    r.seeds.push_back(100 + r.seeds.size());
    r.contexts.push_back({target});
  }
  return {"random.h5", header_for(env), record_episodes(env, r, random_policy(env, 7))};
}

torch::Tensor zero_walker_actions(const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 6}); }

TEST(BlendSchedule, ConditionsOnAThenBlendsLinearlyToBAtMidEpisode) {
  const auto blend = mid_episode_blend(400);
  EXPECT_EQ(blend.start, 200);
  EXPECT_EQ(blend.width, 20);
  EXPECT_EQ(blend.end(), 220);
  EXPECT_EQ(mid_episode_blend(41).start, 20);
  EXPECT_THROW(mid_episode_blend(400, 0), std::invalid_argument);
  for (int t = 0; t <= 400; ++t) {  // the closed form
    const double expected = t < 200 ? 0.0 : t >= 220 ? 1.0 : (t - 199) / 20.0;
    EXPECT_DOUBLE_EQ(blend.alpha(t), expected) << "step " << t;
  }

  torch::manual_seed(3);
  const auto z_a = torch::randn({2, 3}), z_b = torch::randn({2, 3});
  const std::vector<int64_t> steps{0, 199, 200, 209, 219, 220, 399};
  const auto rows = torch::tensor(std::vector<int64_t>{0, 1, 0, 1, 0, 1, 0});
  const auto z = blended_latents(z_a, z_b, rows, torch::tensor(steps), blend);
  ASSERT_EQ(z.sizes(), (std::vector<int64_t>{7, 3}));
  for (int64_t i = 0; i < 7; ++i) {
    const auto a = z_a[rows[i].item<int64_t>()], b = z_b[rows[i].item<int64_t>()];
    const double alpha = blend.alpha(static_cast<int>(steps[i]));
    if (alpha == 0) EXPECT_TRUE(torch::equal(z[i], a)) << "step " << steps[i];
    if (alpha == 1) EXPECT_TRUE(torch::equal(z[i], b)) << "step " << steps[i];
    EXPECT_TRUE(torch::allclose(z[i], (1 - alpha) * a + alpha * b, 1e-6, 1e-6)) << "step " << steps[i];
  }
}

TEST(Transitions, APairWithIdenticalEmbeddingsIsPlainImitationBitForBit) {
  torch::manual_seed(0);
  const WalkerEnv env(unending_short_episodes());
  const auto demos = random_demos(env);
  vae::TrajectoryVae model(vae::testing::tiny_vae_config(env.obs_dim(), env.act_dim()));
  model->eval();
  const auto policy = vae::vae_mean_policy(model, torch::kCPU);
  const auto z_a = vae::encode_episodes(model, demos, {0});
  const auto blend = mid_episode_blend(env.episode_length());

  const auto plain = vae::roll_out_latent_policy(env, vae::rollout_starts(demos, {0}), z_a, policy);
  const auto same = roll_out_transitions(env, demos, {{0, 0}}, z_a, z_a.clone(), policy, blend);
  ASSERT_EQ(same[0].episode.length(), env.episode_length());
  EXPECT_EQ(same[0].episode.observations, plain[0].episode.observations);
  EXPECT_EQ(same[0].episode.actions, plain[0].episode.actions);
  EXPECT_EQ(same[0].episode.features, plain[0].episode.features);

  // Another z_B leaves the trajectory alone up to the blend and changes it from the blend's first step.
  const auto moved = roll_out_transitions(env, demos, {{0, 1}}, z_a, z_a + 1.0, policy, blend);
  const auto& a = plain[0].episode.actions;
  const auto& b = moved[0].episode.actions;
  const size_t split = static_cast<size_t>(blend.start) * env.act_dim();
  EXPECT_TRUE(std::equal(a.begin(), a.begin() + split, b.begin()));
  EXPECT_FALSE(std::equal(a.begin() + split, a.begin() + split + env.act_dim(), b.begin() + split));
}

TEST(Transitions, WalkerJudgeMeasuresTheSpeedAfterAStepAndMatchesWithinTheTolerance) {
  const WalkerEnv env(unending_short_episodes());
  const auto judge = walker_speed_judge(env.feature_names(), 0.25);
  EXPECT_EQ(judge.noun, "speed");
  Episode e;
  e.rewards.assign(5, 0.0);
  for (int t = 0; t <= 5; ++t) e.features.insert(e.features.end(), {double(t), 1.2, 0.0});  // com_speed = t
  EXPECT_DOUBLE_EQ(judge.of_rollout(e, 2).speed, 4.0);  // steps 3, 4, 5
  EXPECT_TRUE(std::isnan(judge.of_rollout(e, 5).speed));
  EXPECT_TRUE(judge.matches({"", 1.2}, {"1", 1.0}));
  EXPECT_FALSE(judge.matches({"", 1.3}, {"1", 1.0}));
  EXPECT_FALSE(judge.matches({"", std::nan("")}, {"1", 1.0}));

  const auto demos = random_demos(env);
  const auto d = judge.of_demonstration(demos, 2);
  EXPECT_EQ(d.label, "3");
  EXPECT_DOUBLE_EQ(d.speed, demos.episodes[2].attributes.at("mean_com_speed"));
  EXPECT_EQ(behaviour_judge(env, demos).noun, "speed");
  EXPECT_THROW(walker_speed_judge({"torso_height"}), std::invalid_argument);
}

// A humanoid style as two of the gait signature's statistics: forward speed and hand height.
struct Style {
  double speed, hand_z;
};
constexpr Style kWalk{1.2, -0.3}, kChicken{0.6, 0.1};

// A 20-step humanoid episode (its features only) in style `before` up to state `switch_at`, then
// in `after`; `wobble` moves the speed a little, as one demonstration differs from the next.
Episode styled_episode(const std::vector<std::string>& names, Style before, Style after, int switch_at,
                       double wobble = 0) {
  const auto col = [&](const char* name) { return std::find(names.begin(), names.end(), name) - names.begin(); };
  Episode e;
  e.rewards.assign(20, 0.0);
  e.features.assign(21 * names.size(), 0.0);
  for (int t = 0; t <= 20; ++t) {
    const Style& s = t <= switch_at ? before : after;
    double* row = e.features.data() + t * names.size();
    row[col("forward_speed")] = s.speed + wobble;
    row[col("root_height")] = 0.9;
    row[col("lhand_z")] = row[col("rhand_z")] = s.hand_z;
  }
  return e;
}

TEST(Transitions, HumanoidJudgeNamesTheStyleAfterTheBlendByTheDemonstrationsClassifier) {
  const HumanoidEnv env;
  const auto& names = env.feature_names();
  DemoSet demos{"styles.h5", header_for(env), {}};
  for (int i = 0; i < 6; ++i) {
    const Style s = i % 2 ? kChicken : kWalk;
    demos.episodes.push_back(styled_episode(names, s, s, 20, 0.02 * i));
    demos.episodes.back().expert_id = i % 2 ? "train/chicken" : "train/walk";
  }
  const auto judge = behaviour_judge(env, demos);
  EXPECT_EQ(judge.noun, "style");
  EXPECT_EQ(judge.speed_feature, "forward_speed");
  const Behaviour walk = judge.of_demonstration(demos, 0), chicken = judge.of_demonstration(demos, 1);
  EXPECT_EQ(walk.label, "train/walk");
  EXPECT_EQ(chicken.label, "train/chicken");
  EXPECT_NEAR(chicken.speed, 0.62, 1e-12);  // the mean forward speed

  // Walks, then (from step 12 on) does the chicken: named chicken after step 12, walk before 8.
  const Episode transition = styled_episode(names, kWalk, kChicken, 12);
  const Behaviour after = judge.of_rollout(transition, 12);
  EXPECT_EQ(after.label, "train/chicken");
  EXPECT_NEAR(after.speed, 0.6, 1e-12);
  EXPECT_TRUE(judge.matches(after, chicken));
  EXPECT_FALSE(judge.matches(after, walk));
  EXPECT_EQ(judge.of_rollout(transition, 0).label, "train/walk");  // 12 of its 20 steps walk
  EXPECT_EQ(judge.of_rollout(styled_episode(names, kChicken, kWalk, 4), 8).label, "train/walk");
  // A rollout that ended before the stretch has no style and matches nothing.
  Episode fell = transition;
  fell.rewards.resize(10);
  fell.features.resize(11 * names.size());
  EXPECT_EQ(judge.of_rollout(fell, 12).label, "");
  EXPECT_FALSE(judge.matches(judge.of_rollout(fell, 12), chicken));
  // Pairs are drawn between styles.
  EXPECT_EQ(sample_pairs({0, 1, 2}, {walk.label, chicken.label, walk.label}, 10, 1).size(), 4u);
}

TEST(TransitionPairs, AllOrderedPairsSamplesOfDifferentLabelsAndReferences) {
  EXPECT_EQ(all_ordered_pairs({3, 5, 7}),
            (std::vector<TransitionPair>{{3, 5}, {3, 7}, {5, 3}, {5, 7}, {7, 3}, {7, 5}}));
  const std::vector<int64_t> episodes{10, 11, 12, 13};
  const std::vector<std::string> labels{"a", "a", "b", "c"};
  const auto sample = sample_pairs(episodes, labels, 4, 1);
  ASSERT_EQ(sample.size(), 4u);
  std::set<std::pair<int64_t, int64_t>> distinct;
  for (const auto& p : sample) {
    EXPECT_NE(labels[p.from - 10], labels[p.to - 10]);
    distinct.insert({p.from, p.to});
  }
  EXPECT_EQ(distinct.size(), 4u);
  EXPECT_EQ(sample_pairs(episodes, labels, 4, 1), sample);
  EXPECT_NE(sample_pairs(episodes, labels, 10, 2), sample_pairs(episodes, labels, 10, 1));
  EXPECT_EQ(sample_pairs(episodes, labels, 100, 1).size(), 10u);  // 16 ordered pairs less 6 of one label
  EXPECT_THROW(sample_pairs(episodes, {"a"}, 1, 1), std::invalid_argument);

  EXPECT_EQ(with_references({{1, 2}, {3, 2}, {2, 1}}),
            (std::vector<TransitionPair>{{1, 2}, {3, 2}, {2, 1}, {2, 2}, {1, 1}}));
}

TEST(Transitions, RowsMeasureEachPairAndTheCsvHasItsColumns) {
  const WalkerEnv env(unending_short_episodes());
  const auto demos = random_demos(env);
  const auto pairs = with_references({{0, 1}, {1, 2}, {1, 3}});  // plus (1, 1), (2, 2), (3, 3)
  const auto z = torch::zeros({static_cast<int64_t>(pairs.size()), 2});
  TransitionOptions options;
  options.blend_width = 4;
  options.settle = 5;  // measured over steps 30..40
  const auto judge = walker_speed_judge(env.feature_names());
  const auto rows =
      run_transitions(env, demos, pairs, z, z, {{"still", zero_walker_actions}}, judge, options);
  ASSERT_EQ(rows.size(), pairs.size());
  const auto rollouts = roll_out_transitions(env, demos, pairs, z, z, zero_walker_actions, mid_episode_blend(40, 4));
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    EXPECT_EQ(r.pair, pairs[i]);
    EXPECT_EQ(r.to.label, judge.of_demonstration(demos, pairs[i].to).label);
    EXPECT_EQ(r.fell, rollouts[i].fell);
    EXPECT_EQ(r.up_at_blend, !r.fell || r.fall_step > 20);
    EXPECT_DOUBLE_EQ(r.after.speed, judge.of_rollout(rollouts[i].episode, 29).speed);
    EXPECT_EQ(r.matched, !r.fell && std::abs(r.after.speed - r.to.speed) <= 0.25);
  }
  EXPECT_TRUE(rows[0].different());
  EXPECT_FALSE(rows[2].different());  // 1 m/s to 1 m/s
  EXPECT_TRUE(rows[3].reference());

  std::istringstream csv(transitions_csv(rows));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line,
            "policy,from_episode,to_episode,from_expert,to_expert,from_behaviour,to_behaviour,from_speed,to_speed,"
            "fell,fall_step,speed_after,behaviour_after,matched");
  int lines = 0;
  while (std::getline(csv, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 13) << line;
    ++lines;
  }
  EXPECT_EQ(lines, static_cast<int>(rows.size()));
  EXPECT_EQ(transitions_csv(rows).find("still,0,1,random,random,-1,1,"), transitions_csv({}).size());

  options.settle = 16;  // 20 + 4 + 16 leaves no step of 40 to measure
  EXPECT_THROW(run_transitions(env, demos, pairs, z, z, {{"still", zero_walker_actions}}, judge, options),
               std::invalid_argument);
}

TEST(Transitions, SummariesCountPairsOfDifferentBehavioursApartFromTheReferences) {
  auto row = [](const char* policy, int64_t from, int64_t to, const char* from_label, const char* to_label,
                bool fell, bool matched) {
    TransitionRow r;
    r.policy = policy;
    r.pair = {from, to};
    r.from.label = from_label;
    r.to.label = to_label;
    r.fell = fell;
    r.up_at_blend = !fell || from == 1;  // of the falls, only the one from episode 1 came after the blend began
    r.matched = matched;
    return r;
  };
  const std::vector<TransitionRow> rows{
      row("p", 0, 1, "-1", "1", false, true), row("p", 1, 0, "1", "-1", true, false),
      row("p", 2, 1, "-1", "1", false, false), row("p", 3, 1, "1", "1", false, true),
      row("p", 1, 1, "1", "1", false, true),   row("q", 0, 1, "-1", "1", true, false)};
  const auto all = summarize_transitions(rows);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].pairs, "different");
  EXPECT_EQ(all[0].n, 3);
  EXPECT_DOUBLE_EQ(all[0].up_at_blend, 1.0);
  EXPECT_DOUBLE_EQ(all[0].stayed_up, 2.0 / 3);
  EXPECT_DOUBLE_EQ(all[0].matched, 1.0 / 3);
  EXPECT_EQ(all[1].pairs, "same");
  EXPECT_EQ(all[2].pairs, "none");
  EXPECT_EQ(all[2].n, 1);
  // p's reference (1, 1) matched: of the two transitions to 1, one matched.
  EXPECT_EQ(all[0].b_alone, 2);
  EXPECT_EQ(all[0].matched_b_alone, 1);
  EXPECT_EQ(all[1].b_alone, 1);  // (3, 1), same speed
  EXPECT_EQ(all[3].b_alone, 0);  // q has no reference
  EXPECT_EQ(all[3].policy, "q");
  const auto table = transition_table(all, "speed");
  EXPECT_NE(table.find("| p | A, B of different speeds | 3 | 100.0% | 66.7% | 33.3% | 1 of 2 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| p | none: B from B's start (reference) | 1 | 100.0% | 100.0% | 100.0% | - |"),
            std::string::npos) << table;
  EXPECT_NE(table.find("| q | A, B of different speeds | 1 | 0.0% | 0.0% | 0.0% | 0 of 0 |"), std::string::npos) << table;

  const auto by_labels = summarize_transitions(rows, /*by_labels=*/true);
  ASSERT_EQ(by_labels.size(), 3u);  // p: -1 -> 1, 1 -> -1; q: -1 -> 1
  EXPECT_EQ(by_labels[0].from_label, "-1");
  EXPECT_EQ(by_labels[0].n, 2);
  EXPECT_DOUBLE_EQ(by_labels[0].matched, 0.5);
  EXPECT_EQ(by_labels[1].from_label, "1");
  EXPECT_EQ(by_labels[2].policy, "q");
  EXPECT_NE(transition_table(by_labels, "speed").find("| p | 1 | -1 | 1 | 100.0% | 0.0% | 0.0% | 0 of 0 |"), std::string::npos);
}

}  // namespace
}  // namespace vaegail::eval
