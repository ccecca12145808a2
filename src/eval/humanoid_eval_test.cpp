#include "eval/humanoid_eval.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "env/humanoid.h"

namespace vaegail::eval {
namespace {

constexpr int kLength = 20, kFallStep = 5;

const std::vector<std::string>& humanoid_features() {
  static const std::vector<std::string> names = HumanoidEnv().feature_names();
  return names;
}

// A stand-in for the humanoid with its feature names whose features follow the action, so that
// what each imitation does is known: the forward speed is the last action, and a negative action
// falls at control step 5 (the fallen feature, and the episode terminates).
class ScriptedHumanoid : public Env {
 public:
  const std::string& id() const override { return id_; }
  const BoxSpec& observation_spec() const override { return obs_; }
  const BoxSpec& action_spec() const override { return act_; }
  const std::vector<std::string>& feature_names() const override { return features_; }
  const std::vector<std::string>& context_names() const override { return context_names_; }
  double control_timestep() const override { return 0.03; }
  int episode_length() const override { return kLength; }
  void set_context(const std::vector<double>&) override {}
  const std::vector<double>& context() const override { return context_; }
  void reset(std::uint64_t) override { steps_ = 0, speed_ = 0; }
  StepOutcome step(const float* action) override {
    ++steps_;
    speed_ = action[0];
    StepOutcome o;
    o.terminated = fallen();
    o.truncated = !o.terminated && steps_ == kLength;
    return o;
  }
  void observe(float* out) const override { out[0] = static_cast<float>(speed_); }
  void features(double* out) const override {
    std::fill(out, out + features_.size(), 0.0);
    out[0] = speed_;  // forward_speed
    out[2] = 0.9;     // root_height
    out[3] = fallen();
  }
  int steps_taken() const override { return steps_; }
  std::unique_ptr<Env> clone() const override { return std::make_unique<ScriptedHumanoid>(); }

 private:
  bool fallen() const { return speed_ < 0 && steps_ >= kFallStep; }
  std::string id_ = "humanoid";
  BoxSpec obs_{{"speed"}, {-10}, {10}}, act_{{"a"}, {-10}, {10}};
  std::vector<std::string> features_ = humanoid_features(), context_names_;
  std::vector<double> context_;
  int steps_ = 0;
  double speed_ = 0;
};

// Two controllers: "train/fast" walks at 1.2 m/s, "train/slow" at 0.6, episodes alternating.
DemoSet two_controllers(const Env& env) {
  DemoSet demos{"train.h5", {}, {}};
  demos.header.feature_names = env.feature_names();
  const size_t n = env.feature_names().size();
  for (int i = 0; i < 4; ++i) {
    Episode e;
    e.expert_id = i % 2 ? "train/slow" : "train/fast";
    e.seed = i;
    e.rewards.assign(kLength, 0.0);
    e.features.assign((kLength + 1) * n, 0.0);
    for (int t = 1; t <= kLength; ++t) e.features[t * n] = (i % 2 ? 0.6 : 1.2) + 0.01 * i;
    demos.episodes.push_back(e);
  }
  return demos;
}

torch::Tensor constant(const torch::Tensor& obs, float a) { return torch::full({obs.size(0), 1}, a); }

TEST(HumanoidEval, CountsFallsWithTheirTimeAndNamesTheStyleOfTheImitationsThatStayedUp) {
  const ScriptedHumanoid env;
  const DemoSet demos = two_controllers(env);
  // z: the demonstration's speed, which the conditioned policy walks at.
  const auto z = torch::tensor({1.2f, 0.6f, 1.2f, 0.6f}).unsqueeze(1);
  const std::vector<NamedPolicy> policies = {
      {"vae", [](const torch::Tensor& obs, const torch::Tensor&) { return constant(obs, 1.2f); }},
      {"diverse_gail", [](const torch::Tensor&, const torch::Tensor& latent) { return latent.clone(); }},
      {"faller", [](const torch::Tensor& obs, const torch::Tensor&) { return constant(obs, -1.f); }}};
  const auto rows = evaluate_humanoid(env, demos, "train", {0, 1, 2, 3}, z, policies);
  ASSERT_EQ(rows.size(), 12u);
  for (const auto& r : rows) {
    SCOPED_TRACE(r.policy + " " + std::to_string(r.episode));
    EXPECT_EQ(r.set, "train");
    EXPECT_EQ(r.style, demos.episodes[r.episode].expert_id);
    if (r.policy == "faller") {
      EXPECT_TRUE(r.fell);
      EXPECT_EQ(r.fall_step, kFallStep);
      EXPECT_NEAR(r.fall_seconds, kFallStep * 0.03, 1e-12);
      EXPECT_EQ(r.named_style, "");  // a fall is not a gait
      EXPECT_FALSE(r.kept_style());
    } else {
      EXPECT_FALSE(r.fell);
      EXPECT_EQ(r.fall_step, -1);
      EXPECT_EQ(r.steps, kLength);
      // The unconditioned policy walks fast whatever it imitates; the conditioned one keeps each style.
      EXPECT_EQ(r.named_style, r.policy == "vae" ? "train/fast" : r.style);
    }
  }

  const auto summaries = summarize_humanoid(rows);
  ASSERT_EQ(summaries.size(), 9u);  // (fast, slow, all) x 3 policies
  const auto find = [&](const std::string& style, const std::string& policy) {
    return *std::find_if(summaries.begin(), summaries.end(),
                         [&](const HumanoidSummary& s) { return s.style == style && s.policy == policy; });
  };
  EXPECT_EQ(find("train/slow", "vae").kept_style, 0);
  EXPECT_DOUBLE_EQ(find("all", "vae").kept_style_rate(), 0.5);
  EXPECT_DOUBLE_EQ(find("all", "diverse_gail").kept_style_rate(), 1.0);
  EXPECT_DOUBLE_EQ(find("all", "faller").fall_rate(), 1.0);
  EXPECT_NEAR(find("all", "faller").mean_fall_seconds, 0.15, 1e-12);
  EXPECT_TRUE(std::isnan(find("all", "faller").kept_style_rate()));  // none stayed up to be named

  const std::string table = humanoid_table(summaries);
  EXPECT_NE(table.find("| train | all | faller | 4 | 100.0% (4) | 0.15 s | 0 | - (0 of 0) |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| train | train/slow | vae | 2 | 0.0% (0) | - | 2 | 0.0% (0 of 2) |"), std::string::npos)
      << table;
  const std::string csv = humanoid_rows_csv(rows);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "set,policy,episode,style,fell,fall_step,fall_seconds,steps,demo_steps,named_style,kept_style");
  EXPECT_NE(csv.find("train,faller,1,train/slow,1,5,0.15,5,20,,0"), std::string::npos) << csv;
  const std::string bars = humanoid_falls_csv(summaries);
  EXPECT_NE(bars.find("train/fast,faller,100.00\n"), std::string::npos) << bars;
  EXPECT_EQ(bars.find("all,"), std::string::npos);  // controllers only
  EXPECT_EQ(humanoid_json(summaries)["summaries"][8]["fall_rate"], 1.0);
}

}  // namespace
}  // namespace vaegail::eval
