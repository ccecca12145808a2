#include "experts/parameter_tuner.h"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "util/atomic_file.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

class ParameterTunerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("parameter_tuner_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

// A bowl in two named parameters with its minimum at a = 0.3, b = -2 (inside the bounds); "fixed"
// is not tuned and must come back as it was.
const nlohmann::json kStart = {{"a", 0.9}, {"b", 1.0}, {"fixed", 7}, {"label", "x"}};
const std::vector<TunedParameter> kTuned = {{"a", 0.0, 1.0}, {"b", -4.0, 4.0}};
double bowl(const nlohmann::json& p, int) {
  const double a = p.at("a").get<double>() - 0.3, b = p.at("b").get<double>() + 2.0;
  return a * a + 0.1 * b * b;
}

TEST_F(ParameterTunerTest, FindsTheMinimumOfABowlByName) {
  const TuneResult r = tune_parameters(kStart, kTuned, {.generations = 80, .seed = 1}, bowl, path("state.json"),
                                       path("metrics.csv"));
  EXPECT_NEAR(r.parameters.at("a").get<double>(), 0.3, 1e-3);
  EXPECT_NEAR(r.parameters.at("b").get<double>(), -2.0, 1e-2);
  EXPECT_EQ(r.parameters.at("fixed"), 7);
  EXPECT_EQ(r.parameters.at("label"), "x");
  EXPECT_EQ(r.generations, 80);
  EXPECT_TRUE(r.resumed.empty());
  const std::string csv = read_file(path("metrics.csv"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 81);  // header + one row per generation
}

TEST_F(ParameterTunerTest, AMinimumOutsideTheBoundsEndsOnTheBound) {
  // The bowl's b = -2 lies below [-1, 4]: the repaired candidates never leave the range.
  const std::vector<TunedParameter> tight = {{"a", 0.0, 1.0}, {"b", -1.0, 4.0}};
  std::atomic<bool> left_bounds{false};
  const auto watched = [&](const nlohmann::json& p, int k) {
    if (p.at("b").get<double>() < -1.0 || p.at("a").get<double>() > 1.0) left_bounds = true;
    return bowl(p, k);
  };
  const TuneResult r =
      tune_parameters(kStart, tight, {.generations = 60, .seed = 2}, watched, path("s.json"), path("m.csv"));
  EXPECT_NEAR(r.parameters.at("b").get<double>(), -1.0, 1e-3);
  EXPECT_NEAR(r.parameters.at("a").get<double>(), 0.3, 1e-2);
  EXPECT_FALSE(left_bounds);
}

TEST_F(ParameterTunerTest, AResumedSearchEndsWhereTheUninterruptedOneEnds) {
  const TuneOptions options{.generations = 30, .seed = 3, .jobs = 2};
  const TuneResult whole = tune_parameters(kStart, kTuned, options, bowl, path("whole.json"), path("whole.csv"));
  TuneOptions first = options;
  first.generations = 12;
  tune_parameters(kStart, kTuned, first, bowl, path("part.json"), path("part.csv"));
  // A state identical to the 12-generation one, but options.generations is not part of the
  // search's identity: the same command with more generations carries on.
  // The start a resumed search is given does not count: the state's does (a tuner writes its
  // result over the style file it started from, and the same command must still resume).
  nlohmann::json moved = kStart;
  moved["a"] = 0.1;
  const TuneResult resumed = tune_parameters(moved, kTuned, options, bowl, path("part.json"), path("part.csv"));
  EXPECT_EQ(resumed.resumed, "resumed at generation 12");
  EXPECT_EQ(resumed.parameters, whole.parameters);
  EXPECT_EQ(resumed.cost, whole.cost);
  // The metrics agree but for the seconds column.
  const auto strip_seconds = [](std::string csv) {
    std::string out;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  EXPECT_EQ(strip_seconds(read_file(path("part.csv"))), strip_seconds(read_file(path("whole.csv"))));
}

TEST_F(ParameterTunerTest, AStateOfAnotherSearchIsRefusedNamingTheFile) {
  tune_parameters(kStart, kTuned, {.generations = 2, .seed = 4}, bowl, path("s.json"), path("m.csv"));
  try {
    tune_parameters(kStart, kTuned, {.generations = 4, .seed = 5}, bowl, path("s.json"), path("m.csv"));
    FAIL() << "a state of another seed resumed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path("s.json")), std::string::npos) << e.what();
  }
}

TEST_F(ParameterTunerTest, BadParameterNamesAndRangesAreNamed) {
  const auto message = [&](const std::vector<TunedParameter>& tuned) {
    try {
      normalise(kStart, tuned);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"missing", 0, 1}}).find("'missing'"), std::string::npos);
  EXPECT_NE(message({{"label", 0, 1}}).find("not a number"), std::string::npos);
  EXPECT_NE(message({{"a", 1, 1}}).find("empty range"), std::string::npos);
}

TEST(ParameterTuner, NormaliseAndDenormaliseAreInverseInsideTheBounds) {
  const auto u = normalise(kStart, kTuned);
  EXPECT_DOUBLE_EQ(u[0], 0.9);
  EXPECT_DOUBLE_EQ(u[1], 5.0 / 8.0);
  double outside = -1;
  EXPECT_EQ(denormalise(kStart, kTuned, u, &outside), kStart);
  EXPECT_EQ(outside, 0.0);
  denormalise(kStart, kTuned, {1.5, -0.5}, &outside);
  EXPECT_DOUBLE_EQ(outside, 0.5);
}

}  // namespace
}  // namespace vaegail
