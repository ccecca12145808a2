#include "gail/diverse_gail.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "env/humanoid.h"
#include "env/walker.h"
#include "gail/test_support.h"
#include "util/atomic_file.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

constexpr int kEpisodeLength = 8;

class DiverseGailTest : public ::testing::Test {
 protected:
  void SetUp() override {
    WalkerOptions w;
    w.episode_length = kEpisodeLength;
    env = std::make_unique<WalkerEnv>(w);
    demos = random_walker_demos(*env, 6);
    torch::manual_seed(2);
    vae = vae::TrajectoryVae(tiny_vae_config(env->obs_dim(), env->act_dim()));
    options.iterations = 3;
    options.num_envs = 2;
    options.policy_hidden = options.critic_hidden = {16};
    options.discriminator_hidden = {8};
    options.seed = 9;
    dir = fs::temp_directory_path() / ("gail_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  GailTrainer trainer(const std::string& name, GailOptions o) {
    return GailTrainer(demos, vae, *env, o, (dir / name).string());
  }

  std::unique_ptr<WalkerEnv> env;
  DemoSet demos;
  vae::TrajectoryVae vae{nullptr};
  GailOptions options;
  fs::path dir;
};

// Every parameter and buffer of the agent and the discriminator, by name.
std::map<std::string, torch::Tensor> state_of(GailTrainer& t) {
  std::map<std::string, torch::Tensor> out;
  for (const auto& item : t.agent().named_parameters()) out["agent." + item.key()] = item.value();
  for (const auto& item : t.agent().named_buffers()) out["agent." + item.key()] = item.value();
  for (const auto& item : t.discriminator().named_parameters()) out["disc." + item.key()] = item.value();
  for (const auto& item : t.discriminator().named_buffers()) out["disc." + item.key()] = item.value();
  return out;
}

// metrics.csv without its last column (wall-clock seconds).
std::string metrics_without_seconds(const std::string& path) {
  std::istringstream in(read_file(path));
  std::string line, out;
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

TEST_F(DiverseGailTest, ResumedRunEqualsTheUninterruptedOne) {
  for (const GailMode mode : {GailMode::Diverse, GailMode::Plain}) {
    SCOPED_TRACE(to_string(mode));
    options.mode = mode;
    auto whole = trainer(to_string(mode) + "_whole", options);
    EXPECT_EQ(whole.train(), 3);

    GailOptions first = options;
    first.iterations = 1;
    EXPECT_EQ(trainer(to_string(mode) + "_resumed", first).train(), 1);
    auto resumed = trainer(to_string(mode) + "_resumed", options);  // a new process, as after a kill
    EXPECT_EQ(resumed.iteration(), 1);
    EXPECT_EQ(resumed.train(), 2);

    const auto a = state_of(whole), b = state_of(resumed);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [name, value] : a) EXPECT_TRUE(torch::equal(value, b.at(name))) << name;
    EXPECT_EQ(metrics_without_seconds(whole.metrics_path()), metrics_without_seconds(resumed.metrics_path()));
  }
}

// A full file system mid-run: the iteration ends in one line naming the file it could not write,
// no temporary file is left and the checkpoint before is kept; the same run started again once
// there is room resumes from it and learns what the uninterrupted run learns.
TEST_F(DiverseGailTest, AFullDiskStopsTheRunInOneLineAndTheRerunEqualsTheUninterruptedOne) {
  SmallFileSystem small(4 * 1024 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  auto whole = trainer("whole", options);
  whole.train();
  const std::string run = small.path("run");
  {
    GailTrainer stopped(demos, vae, *env, options, run);
    stopped.iterate();
    const std::string checkpoint = read_file(stopped.checkpoint_path());
    small.fill_leaving(0);
    const std::string error = error_of([&] { stopped.iterate(); });
    EXPECT_TRUE(names_full_disk(error, stopped.checkpoint_path()) || names_full_disk(error, stopped.metrics_path()))
        << error;
    EXPECT_EQ(temporary_files_under(run), std::vector<std::string>{});
    EXPECT_TRUE(read_file(stopped.checkpoint_path()) == checkpoint);
  }
  small.make_room();
  auto resumed = GailTrainer(demos, vae, *env, options, run);
  EXPECT_EQ(resumed.iteration(), 1);
  EXPECT_EQ(resumed.train(), 2);
  const auto a = state_of(whole), b = state_of(resumed);
  for (const auto& [name, value] : a) EXPECT_TRUE(torch::equal(value, b.at(name))) << name;
  EXPECT_EQ(metrics_without_seconds(whole.metrics_path()), metrics_without_seconds(resumed.metrics_path()));
}

// One run directory, one writer: a second trainer on it is refused in one line naming the holder.
TEST_F(DiverseGailTest, ASecondTrainerOnTheRunDirectoryIsRefused) {
  const auto first = trainer("held", options);
  EXPECT_EQ(error_of([&] { trainer("held", options); }),
            (dir / "held").string() + ": in use by process " + std::to_string(::getpid()) + " (another vaegail run)");
}

// Both players learn: the policy takes a TRPO step inside the trust region every iteration, and the
// discriminator's steps make it tell policy samples from demonstrations better. The control is the same
// run with a discriminator that does not learn: iteration 2 rolls out the same policy in both runs (its
// TRPO step was scored by the same, initial D), so row 2, taken before D's update, compares the trained
// D with the untrained one on the same samples.
TEST_F(DiverseGailTest, WritesOneMetricsRowPerIterationAndLearns) {
  auto t = trainer("metrics", options);
  std::vector<GailMetrics> rows;
  t.train([&](const GailMetrics& m) { rows.push_back(m); });
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows.back().steps, 3 * 2 * kEpisodeLength);
  for (const auto& row : rows) {
    EXPECT_GT(row.kl, 0.0) << "iteration " << row.iteration << ": no policy step kept";
    EXPECT_LE(row.kl, options.max_kl) << "iteration " << row.iteration;
  }

  GailOptions frozen_discriminator = options;
  frozen_discriminator.iterations = 2;
  frozen_discriminator.discriminator_learning_rate = 0;
  std::vector<GailMetrics> control;
  trainer("control", frozen_discriminator).train([&](const GailMetrics& m) { control.push_back(m); });
  ASSERT_EQ(control.size(), 2u);
  EXPECT_EQ(rows[0].discriminator_loss, control[0].discriminator_loss);  // same start, same samples
  EXPECT_EQ(rows[1].env_return, control[1].env_return);                  // same rollout
  EXPECT_LT(rows[1].discriminator_loss, control[1].discriminator_loss);
  EXPECT_LT(rows[1].gail_reward, control[1].gail_reward);  // -log(1 - D) on policy samples: D saw through more
  for (const auto& row : rows) EXPECT_TRUE(std::isfinite(row.task.at("speed_error")));  // the walker's
  std::istringstream csv(read_file(t.metrics_path()));
  std::string line, header;
  int lines = 0;
  for (; std::getline(csv, line); ++lines)
    if (lines == 0) header = line;
  EXPECT_EQ(lines, 4);
  // The committed runs' columns, so that they resume.
  const std::string committed = read_file(std::string(VAEGAIL_SOURCE_DIR) + "/checkpoints/walker/diverse_gail/metrics.csv");
  EXPECT_EQ(header, committed.substr(0, committed.find('\n')));
  EXPECT_EQ(t.agent().condition_dim(), vae->config().latent_dim);
  EXPECT_EQ(t.discriminator().latent_dim(), vae->config().latent_dim);
}

TEST_F(DiverseGailTest, PlainModeHasNoLatentAnywhere) {
  options.mode = GailMode::Plain;
  auto t = GailTrainer(demos, vae::TrajectoryVae(nullptr), *env, options, (dir / "plain").string());
  EXPECT_EQ(t.agent().condition_dim(), 0);
  EXPECT_EQ(t.discriminator().latent_dim(), 0);
  EXPECT_EQ(t.train(), 3);
}

TEST_F(DiverseGailTest, ALoadedRunsMeanPolicyActsAsTheTrainedOneAndReadsZ) {
  auto t = trainer("run", options);
  t.train();
  const auto loaded = agent_mean_policy(load_gail_agent((dir / "run").string(), env->obs_dim(), env->act_dim(),
                                                        vae, torch::kCPU));
  torch::NoGradGuard no_grad;
  const auto obs = torch::randn({3, env->obs_dim()});
  const auto z = torch::randn({3, vae->config().latent_dim});
  const auto trained = t.agent().policy().distribution(t.agent().input(obs, z)).mean;
  EXPECT_TRUE(torch::allclose(loaded(obs, z), trained));
  EXPECT_FALSE(torch::allclose(loaded(obs, z), loaded(obs, z + 1)));
}

TEST_F(DiverseGailTest, RefusesOtherSettingsInAnExistingRun) {
  trainer("run", options);
  GailOptions other = options;
  other.discriminator_steps = 3;
  EXPECT_THROW(trainer("run", other), std::invalid_argument);
  other = options;
  other.iterations = 10;  // extending a run is fine
  EXPECT_NO_THROW(trainer("run", other));
}

TEST_F(DiverseGailTest, RefusesAVaeOfOtherDimensions) {
  vae = vae::TrajectoryVae(tiny_vae_config(env->obs_dim() + 1, env->act_dim()));
  EXPECT_THROW(trainer("dims", options), std::invalid_argument);
}

TEST(GailPreset, TheHumanoidsIsTablesTwoAndThreeWithTheBodysDiscriminatorSubset) {
  const HumanoidEnv humanoid;
  const GailOptions o = gail_preset("humanoid", humanoid);
  EXPECT_EQ(o.policy_hidden, (std::vector<int>{300, 200, 100}));
  EXPECT_EQ(o.critic_hidden, (std::vector<int>{300, 200, 100}));
  EXPECT_EQ(o.discriminator_hidden, (std::vector<int>{300, 200}));
  EXPECT_NEAR(std::exp(o.init_log_std), 0.1, 1e-12);
  EXPECT_EQ(o.discriminator_learning_rate, 1e-4);
  EXPECT_EQ(o.discriminator_steps, 10);
  EXPECT_EQ(o.iterations, 100000);
  EXPECT_EQ(o.discriminator_state_indices, humanoid.discriminator_observation());
  const auto& names = humanoid.observation_spec().names;
  EXPECT_EQ(names.at(o.discriminator_state_indices.front()), "root_height");
  EXPECT_EQ(names.at(o.discriminator_state_indices.back()), "head_z");
  EXPECT_EQ(default_gail_preset(humanoid), "humanoid");
}

TEST(GailPreset, TheWalkersIsTheOptionsDefaultsOnTheWholeObservation) {
  const WalkerEnv walker;
  EXPECT_EQ(nlohmann::json(gail_preset("walker", walker)), nlohmann::json(GailOptions()));
  EXPECT_EQ(default_gail_preset(walker), "walker");
  try {
    gail_preset("ant", walker);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "GAIL: unknown preset 'ant' (walker, humanoid)");
  }
}

}  // namespace
}  // namespace vaegail
