#include "experts/gait_demos.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "env/humanoid.h"
#include "experts/gait_episode.h"
#include "util/atomic_file.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

TEST(GaitDemos, EpisodesCycleThroughTheStylesWithTheirLabelsAndTheFileLayout) {
  GaitParameters slow;
  slow.speed = 1.0;
  const std::vector<GaitDemonstrator> styles = {{"train/walk", GaitParameters{}}, {"train/slow", slow}};
  DemoHeader header;
  const auto episodes = record_gait_demos(styles, {.episodes = 3, .seed = 5, .threads = 2}, &header);
  HumanoidEnv env;
  ASSERT_EQ(episodes.size(), 3u);
  EXPECT_EQ(header.env_id, env.id());
  EXPECT_EQ(header.context_names, std::vector<std::string>{"style"});
  for (int i = 0; i < 3; ++i) {
    const Episode& e = episodes[i];
    EXPECT_EQ(e.context, std::vector<double>{static_cast<double>(i % 2)});
    EXPECT_EQ(e.expert_id, styles[i % 2].label);
    EXPECT_EQ(e.length(), env.episode_length());  // the walks stay up the whole episode
    EXPECT_TRUE(e.truncations.back());
    EXPECT_EQ(e.observations.size(), static_cast<size_t>(e.length() + 1) * env.obs_dim());
    EXPECT_EQ(e.actions.size(), static_cast<size_t>(e.length()) * env.act_dim());
    EXPECT_NO_THROW(validate_episode(e, header, "episode"));
  }
  // The record is the episode the runner walks: the same start gives the same states, and the
  // recorded actions are the means the controller applied.
  GaitEpisodeOptions options;
  options.seed = episodes[1].seed;
  std::vector<float> first_action, last_observation(env.obs_dim());
  run_gait_episode(env, slow, options, [&](const HumanoidEnv& at, const float* action, const StepOutcome*) {
    if (action && first_action.empty()) first_action.assign(action, action + at.act_dim());
    at.observe(last_observation.data());
  });
  EXPECT_EQ(first_action, std::vector<float>(episodes[1].actions.begin(), episodes[1].actions.begin() + env.act_dim()));
  EXPECT_EQ(last_observation, std::vector<float>(episodes[1].observations.end() - env.obs_dim(), episodes[1].observations.end()));
  // The thread count does not change a recording.
  const auto alone = record_gait_demos(styles, {.episodes = 3, .seed = 5, .threads = 1}, nullptr);
  EXPECT_EQ(alone[2].observations, episodes[2].observations);

  // A replay: the demonstrator made after the same reset walks through the recorded states,
  // where the recorded (mean) actions held for each control step leave them.
  const Episode& e = episodes[1];
  HumanoidEnv scripted, held;
  scripted.reset(e.seed);
  held.reset(e.seed);
  const auto demonstrator = make_gait_demonstrator(scripted.model(), slow);
  std::vector<float> mean(env.act_dim()), observed(env.obs_dim());
  float scripted_error = 0, held_error = 0;
  bool held_ended = false;
  for (int t = 0; t < e.length(); ++t) {
    scripted.step_controlled(*demonstrator, mean.data());
    const float* recorded = e.observations.data() + static_cast<size_t>(t + 1) * env.obs_dim();
    scripted.observe(observed.data());
    for (int k = 0; k < env.obs_dim(); ++k) scripted_error = std::max(scripted_error, std::abs(observed[k] - recorded[k]));
    if (held_ended) continue;
    const StepOutcome outcome = held.step(e.actions.data() + static_cast<size_t>(t) * env.act_dim());
    held_ended = outcome.terminated || outcome.truncated;
    held.observe(observed.data());
    held_error = std::max(held_error, std::abs(observed[112] - recorded[112]));  // the root height
  }
  EXPECT_EQ(scripted_error, 0.0f);
  EXPECT_GT(held_error, 0.05f);  // held, the mean actions drop or tip the body within the episode
}

TEST(GaitDemos, AStyleFileIsLabelledBySetAndStyleElseByFolderAndName) {
  const fs::path dir = fs::temp_directory_path() / ("gait_demos_" + std::to_string(::getpid())) / "eval";
  fs::create_directories(dir);
  write_file_atomically((dir / "a.json").string(), R"({"set": "train", "style": "walk", "parameters": {"speed": 1.1}})");
  write_file_atomically((dir / "b.json").string(), R"({"parameters": {}})");
  const GaitDemonstrator a = read_gait_demonstrator((dir / "a.json").string());
  EXPECT_EQ(a.label, "train/walk");
  EXPECT_EQ(a.parameters.speed, 1.1);
  EXPECT_EQ(read_gait_demonstrator((dir / "b.json").string()).label, "eval/b");
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace vaegail
