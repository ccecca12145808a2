#include "experts/style_tuner.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "util/atomic_file.h"
#include "util/json_file.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

GaitEpisodeResult upright_episode() {
  GaitEpisodeResult e;
  e.time_up = 10;
  e.speed = 1.0;
  e.cadence = 100;
  e.style[kHandSpread] = 0.3;
  e.signature[7] = 0.05;
  return e;
}

TEST(StyleTuner, AnEpisodeCostsItsFallItsMissesItsDriftAndItsEffortByHand) {
  const std::vector<StyleTarget> targets = {{"speed", 1.2, 0.1}, {"hand_spread", 0.3, 0.05}};
  GaitEpisodeResult e = upright_episode();
  // speed misses by two tolerances: 4; the hands are on target: 0.
  EXPECT_NEAR(style_episode_cost(e, targets, 10), 4.0, 1e-12);
  e.heading_error = 0.1;  // half the heading tolerance: 0.25
  e.lateral_drift = -2;   // twice the drift tolerance: 4
  e.effort = 0.3;
  EXPECT_NEAR(style_episode_cost(e, targets, 10), 4.0 + 0.25 + 4.0 + 0.3, 1e-12);
  // Up half the episode: half the fall weight on top.
  e = upright_episode();
  e.time_up = 5;
  EXPECT_NEAR(style_episode_cost(e, targets, 10), kFallWeight / 2 + 4.0, 1e-12);
  // A far miss grows linearly, and an episode too short to measure pays a fixed far miss on
  // every target.
  e = upright_episode();
  e.speed = 2.2;  // ten tolerances off: 3 (2 * 10 - 3)
  EXPECT_NEAR(style_episode_cost(e, targets, 10), 51.0, 1e-9);
  e.time_up = kMeasuredAfter / 2;
  EXPECT_NEAR(style_episode_cost(e, targets, 10),
              kFallWeight * (1 - kMeasuredAfter / 20) + 2 * style_miss_cost(kUnmeasuredMiss), 1e-9);
}

TEST(StyleTuner, AMissCostsItsSquareNearTheTargetAndGrowsLinearlyFarFromIt) {
  EXPECT_DOUBLE_EQ(style_miss_cost(0), 0);
  EXPECT_DOUBLE_EQ(style_miss_cost(-2), 4);
  EXPECT_DOUBLE_EQ(style_miss_cost(kHuberKnee), kHuberKnee * kHuberKnee);  // continuous at the knee
  // The slope keeps its value at the knee (2 * knee per tolerance), so far candidates still rank.
  EXPECT_DOUBLE_EQ(style_miss_cost(12) - style_miss_cost(11), 2 * kHuberKnee);
  EXPECT_LT(style_miss_cost(20), style_miss_cost(21));
}

TEST(StyleTuner, MeasuresAreReadByName) {
  const GaitEpisodeResult e = upright_episode();
  EXPECT_EQ(style_measure(e, "speed"), 1.0);
  EXPECT_EQ(style_measure(e, "cadence"), 100);
  EXPECT_EQ(style_measure(e, "hand_spread"), 0.3);
  EXPECT_EQ(style_measure(e, "arm_swing"), 0.05);
  for (const char* name : kStyleMeasures) EXPECT_NO_THROW(style_measure(e, name)) << name;
  EXPECT_THROW(style_measure(e, "elegance"), std::invalid_argument);
}

class StyleFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("style_tuner_" + std::to_string(::getpid()) + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const nlohmann::json& j) {
    const std::string path = (dir_ / name).string();
    write_file_atomically(path, j.dump());
    return path;
  }
  std::string error_of(const nlohmann::json& style) {
    try {
      read_style_tuning(write("bad.json", style));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  }
  fs::path dir_;
};

const nlohmann::json kStyle = {
    {"style", "test"},
    {"parameters", {{"speed", 1.0}}},
    {"targets", {{"speed", {1.0, 0.2}}}},
    {"tune",
     {{"parameters", {{"speed", {0.5, 1.5}}, {"step_width", {0.05, 0.2}}}},
      {"generations", 2},
      {"population", 4},
      {"seed", 3},
      {"episodes", 1}}}};

TEST_F(StyleFileTest, ReadsTargetsBoundsAndTheStartingPointRelativeToTheFile) {
  nlohmann::json walk = {{"parameters", {{"speed", 0.8}, {"elbow", 1.0}}}};
  write("walk.json", walk);
  nlohmann::json style = kStyle;
  style["tune"]["start"] = "walk.json";
  const StyleTuning t = read_style_tuning(write("style.json", style));
  ASSERT_EQ(t.targets.size(), 1u);
  EXPECT_EQ(t.targets[0].measure, "speed");
  EXPECT_EQ(t.tuned.size(), 2u);
  EXPECT_EQ(t.options.population, 4);
  EXPECT_EQ(t.options.seed, 3u);
  EXPECT_EQ(t.episodes, 1);
  EXPECT_EQ(t.start.at("speed"), 1.0);  // this file's, set over the start file's 0.8
  EXPECT_EQ(t.start.at("elbow"), 1.0);  // the start file's
  EXPECT_EQ(t.start.at("step_width"), nlohmann::json(GaitParameters{}).at("step_width"));  // defaults fill in
}

TEST_F(StyleFileTest, MalformedFilesAreNamedWithTheirKey) {
  nlohmann::json s = kStyle;
  s["targets"]["elegance"] = {1, 1};
  EXPECT_NE(error_of(s).find("'elegance' is not a style measure"), std::string::npos) << error_of(s);
  s = kStyle;
  s["targets"]["speed"] = {1, 0};
  EXPECT_NE(error_of(s).find("tolerance > 0"), std::string::npos);
  s = kStyle;
  s["tune"]["parameters"]["wings"] = {0, 1};
  EXPECT_NE(error_of(s).find("'wings' is not a gait parameter"), std::string::npos);
  s = kStyle;
  s["tune"]["parameters"]["speed"] = {1};
  EXPECT_NE(error_of(s).find("pair of numbers"), std::string::npos);
  s = kStyle;
  s.erase("targets");
  EXPECT_NE(error_of(s).find("no 'targets'"), std::string::npos);
  EXPECT_NE(error_of(s).find("bad.json"), std::string::npos);
}

TEST_F(StyleFileTest, TuningWritesTheBestParametersIntoTheFileAndARerunResumesToTheSame) {
  nlohmann::json style = kStyle;
  style["description"] = "kept";
  const std::string path = write("style.json", style);
  const TuneResult first = tune_style(path, (dir_ / "run").string(), 2, "the command");
  const nlohmann::json written = read_json_file(path);
  EXPECT_EQ(written.at("description"), "kept");
  EXPECT_EQ(written.at("parameters"), first.parameters);
  EXPECT_EQ(written.at("tuned").at("command"), "the command");
  EXPECT_EQ(written.at("tuned").at("generations"), 2);
  // The cost is the style's: the episodes walked at the tuned parameters score it again
  const StyleTuning t = read_style_tuning(path);
  // (at most: a best candidate outside the bounds is scored at its repair plus the penalty).
  EXPECT_LE(style_cost(t, gait_parameters_from_json(first.parameters, path)), first.cost + 1e-9);
  const TuneResult again = tune_style(path, (dir_ / "run").string(), 1, "the command");
  EXPECT_EQ(again.resumed, "resumed at generation 2");
  EXPECT_EQ(again.parameters, first.parameters);
}

TEST(StyleTuner, EveryCommittedStyleFileReadsWithItsTargetsAndBounds) {
  int files = 0;
  for (const char* set : {"train", "eval"})
    for (const auto& entry : fs::directory_iterator(fs::path(VAEGAIL_SOURCE_DIR) / "configs/humanoid_styles" / set)) {
      const StyleTuning t = read_style_tuning(entry.path().string());
      EXPECT_FALSE(t.targets.empty()) << entry.path();
      EXPECT_GE(t.tuned.size(), 20u) << entry.path();
      const nlohmann::json style = read_json_file(entry.path().string());
      EXPECT_EQ(style.at("set"), set) << entry.path();
      EXPECT_FALSE(style.at("description").get<std::string>().empty()) << entry.path();
      ++files;
    }
  EXPECT_EQ(files, 11);  // the paper's six training and five evaluation styles
}

}  // namespace
}  // namespace vaegail
