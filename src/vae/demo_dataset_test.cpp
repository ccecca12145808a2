#include "vae/demo_dataset.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace vaegail::vae {
namespace {

// A header with 3 observation, 2 action components and one feature, com_speed.
DemoHeader small_header() {
  DemoHeader h;
  h.env_id = "toy";
  h.control_timestep = 0.1;
  h.observation_names = {"o0", "o1", "o2"};
  h.action_names = {"a0", "a1"};
  h.feature_names = {"com_speed"};
  h.context_names = {"target_speed"};
  return h;
}

// Episode whose observation (t, j) is 100 * id + 10 * t + j and whose speed feature is t.
Episode episode(int id, int T, double held_out = -1) {
  Episode e;
  for (int t = 0; t <= T; ++t) {
    for (int j = 0; j < 3; ++j) e.observations.push_back(100.f * id + 10.f * t + j);
    e.features.push_back(t);
  }
  e.actions.assign(2 * T, static_cast<float>(id));
  e.rewards.assign(T, 0.0);
  e.terminations.assign(T, 0);
  e.truncations.assign(T, 0);
  e.expert_id = "expert" + std::to_string(id % 3);
  e.context = {static_cast<double>(id % 2)};
  e.seed = 1000 + id;
  if (held_out >= 0) e.attributes["held_out"] = held_out;
  return e;
}

DemoSet demo_set(std::vector<Episode> episodes) {
  return DemoSet{"toy.h5", small_header(), std::move(episodes)};
}

VaeConfig config_for_toy() { return VaeConfig::walker(3, 2); }

TEST(DemoDatasetTest, PadsUnequalLengthsAndMasksThePadding) {
  const auto set = demo_set({episode(0, 3), episode(1, 5)});
  const auto d = to_trajectory_dataset(set, {0, 1}, config_for_toy());
  EXPECT_EQ(d.states.sizes(), torch::IntArrayRef({2, 6, 3}));
  EXPECT_EQ(d.actions.sizes(), torch::IntArrayRef({2, 5, 2}));
  ASSERT_TRUE(d.mask.defined());
  EXPECT_TRUE(torch::equal(d.mask, torch::tensor({{1, 1, 1, 0, 0}, {1, 1, 1, 1, 1}}).to(torch::kBool)));
  EXPECT_EQ(d.states[0][3][2].item<float>(), 32.f);   // last real state of episode 0
  EXPECT_EQ(d.states[1][5][1].item<float>(), 151.f);
  EXPECT_EQ(d.states[0][4].abs().sum().item<float>(), 0.f);  // padding
  EXPECT_EQ(d.actions[1][4][0].item<float>(), 1.f);
  d.validate(config_for_toy());
}

TEST(DemoDatasetTest, EqualLengthsNeedNoMask) {
  const auto set = demo_set({episode(0, 4), episode(1, 4), episode(2, 4)});
  const auto d = to_trajectory_dataset(set, {2, 0}, config_for_toy());
  EXPECT_FALSE(d.mask.defined());
  EXPECT_EQ(d.states[0][0][0].item<float>(), 200.f);  // rows follow the requested order
}

TEST(DemoDatasetTest, HeldOutExpertsAreTheValidationSet) {
  const auto set = demo_set({episode(0, 2, 0), episode(1, 2, 1), episode(2, 2, 0), episode(3, 2, 1), episode(4, 2)});
  const auto split = split_demos(set, 7);
  EXPECT_EQ(split.train, (std::vector<int64_t>{0, 2, 4}));
  EXPECT_EQ(split.val, (std::vector<int64_t>{1, 3}));
}

TEST(DemoDatasetTest, WithoutHeldOutExpertsASeededTenthValidates) {
  std::vector<Episode> episodes;
  for (int i = 0; i < 30; ++i) episodes.push_back(episode(i, 2));
  const auto set = demo_set(episodes);
  const auto a = split_demos(set, 1), b = split_demos(set, 1), c = split_demos(set, 2);
  EXPECT_EQ(a.val.size(), 3u);
  EXPECT_EQ(a.train.size(), 27u);
  EXPECT_EQ(a.val, b.val);
  EXPECT_NE(a.val, c.val);
  std::vector<int64_t> all = a.train;
  all.insert(all.end(), a.val.begin(), a.val.end());
  std::sort(all.begin(), all.end());
  for (int i = 0; i < 30; ++i) EXPECT_EQ(all[i], i);
  EXPECT_EQ(split_demos(demo_set({episode(0, 2), episode(1, 2)}), 3).val.size(), 1u);
}

TEST(DemoDatasetTest, DimensionMismatchIsAOneLineError) {
  const auto set = demo_set({episode(0, 2)});
  try {
    make_demo_training_data(set, VaeConfig::walker(), 0);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("toy.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("3/2"), std::string::npos) << what;
    EXPECT_NE(what.find("18/6"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(DemoDatasetTest, LoadsAFileIntoTrainingAndValidationTensors) {
  const auto path = (std::filesystem::temp_directory_path() /
                     ("demo_dataset_test_" + std::to_string(::getpid()) + ".h5")).string();
  {
    DemoWriter writer(path, small_header());
    writer.append(episode(0, 3, 0));
    writer.append(episode(1, 4, 1));
    writer.append(episode(2, 5, 0));
    writer.commit();
  }
  const auto d = make_demo_training_data(read_demos(path), config_for_toy(), 0);
  std::filesystem::remove(path);
  EXPECT_EQ(d.split.train, (std::vector<int64_t>{0, 2}));
  EXPECT_EQ(d.train.states.sizes(), torch::IntArrayRef({2, 6, 3}));
  EXPECT_EQ(d.val.states.sizes(), torch::IntArrayRef({1, 5, 3}));
  EXPECT_EQ(d.val.states[0][4][0].item<float>(), 140.f);
  EXPECT_TRUE(d.train.mask.defined());
  EXPECT_FALSE(d.val.mask.defined());
}

TEST(DemoDatasetTest, AchievedSpeedPrefersTheRecordedAttribute) {
  auto with_attribute = episode(0, 4);
  with_attribute.attributes["mean_com_speed"] = 1.25;
  const auto set = demo_set({with_attribute, episode(1, 4)});
  EXPECT_EQ(achieved_speed(set, 0), 1.25);
  EXPECT_DOUBLE_EQ(achieved_speed(set, 1), (1 + 2 + 3 + 4) / 4.0);  // the feature over t = 1..T
}

TEST(DemoDatasetTest, AFileWithoutASpeedHasNoneToReport) {
  auto set = demo_set({episode(0, 4)});
  set.header.feature_names = {"grip_x"};
  EXPECT_THROW(achieved_speed(set, 0), DataError);
  EXPECT_TRUE(std::isnan(achieved_speed_or_nan(set, 0)));
  EXPECT_DOUBLE_EQ(achieved_speed_or_nan(demo_set({episode(0, 4)}), 0), 2.5);
}

}  // namespace
}  // namespace vaegail::vae
