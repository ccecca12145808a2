// Ranks (util/world.h, rl/distributed.h): K ranks of a run train what one process with all its
// environments trains, and a run resumes under another rank count. The test binary runs itself
// under mpirun (the RankShare case below is the ranks' program; util/test_ranks.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "env/walker.h"
#include "gail/diverse_gail.h"
#include "gail/test_support.h"
#include "util/test_ranks.h"
#include "util/world.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRunDirVariable = "VAEGAIL_TEST_RANKS_RUN_DIR";
constexpr const char* kIterationsVariable = "VAEGAIL_TEST_RANKS_ITERATIONS";
constexpr int kEnvs = 4;

class DistributedGailTest : public ::testing::Test {
 protected:
  void SetUp() override {
    WalkerOptions w;
    w.episode_length = 8;
    env = std::make_unique<WalkerEnv>(w);
    demos = random_walker_demos(*env, 6);
    torch::manual_seed(2);
    vae = vae::TrajectoryVae(tiny_vae_config(env->obs_dim(), env->act_dim()));
    options.num_envs = kEnvs;
    options.policy_hidden = options.critic_hidden = {16};
    options.discriminator_hidden = {8};
    options.discriminator_minibatches = 2;  // shuffled minibatches: drawn over the run's rows
    options.seed = 9;
    dir = fs::temp_directory_path() / ("gail_ranks_test_" + std::to_string(::getpid()));
  }
  void TearDown() override {
    if (World::get().is_root() && std::getenv(kRunDirVariable) == nullptr) fs::remove_all(dir);
  }

  GailTrainer trainer(const fs::path& run_dir, int iterations) {
    GailOptions o = options;
    o.iterations = iterations;
    return GailTrainer(demos, vae, *env, o, run_dir.string());
  }

  // This test binary's RankShare case on `ranks` ranks, training run_dir to `iterations`.
  void train_on_ranks(int ranks, const fs::path& run_dir, int iterations) {
    fs::create_directories(dir);
    const std::string failure =
        run_case_on_ranks(ranks, "DistributedGailTest.RankShare",
                          {{kRunDirVariable, run_dir.string()}, {kIterationsVariable, std::to_string(iterations)}},
                          dir / "mpirun.log");
    ASSERT_TRUE(failure.empty()) << failure;
  }

  std::unique_ptr<WalkerEnv> env;
  DemoSet demos;
  vae::TrajectoryVae vae{nullptr};
  GailOptions options;
  fs::path dir;
};

// A copy of every parameter and buffer of the run's agent and discriminator, by name.
std::map<std::string, torch::Tensor> snapshot_of(GailTrainer& t) {
  std::map<std::string, torch::Tensor> out;
  for (const auto& item : t.agent().named_parameters()) out["agent." + item.key()] = item.value().clone();
  for (const auto& item : t.agent().named_buffers()) out["agent." + item.key()] = item.value().clone();
  for (const auto& item : t.discriminator().named_parameters()) out["disc." + item.key()] = item.value().clone();
  return out;
}

void expect_close(const std::map<std::string, torch::Tensor>& a, const std::map<std::string, torch::Tensor>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, value] : a) {
    const auto& other = b.at(name);
    EXPECT_TRUE(torch::allclose(value.to(torch::kFloat64), other.to(torch::kFloat64), 1e-4, 1e-5))
        << name << ": largest difference " << (value - other).abs().max().item<double>();
  }
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The ranks' program: trains the run directory the parent names, then exits.
TEST_F(DistributedGailTest, RankShare) {
  const char* run_dir = std::getenv(kRunDirVariable);
  if (run_dir == nullptr) GTEST_SKIP() << "the ranks' program of the tests below, run by them under mpirun";
  auto t = trainer(run_dir, std::atoi(std::getenv(kIterationsVariable)));
  t.train();
}

TEST_F(DistributedGailTest, TwoRanksTrainWhatOneProcessWithAllTheEnvironmentsTrains) {
  if (!have_mpirun()) GTEST_SKIP() << "built without MPI or no mpirun";
  train_on_ranks(2, dir / "ranks", 1);
  auto one = trainer(dir / "one", 1);
  one.train();
  auto ranks = trainer(dir / "ranks", 1);  // loads the 2-rank run's checkpoint
  ASSERT_EQ(ranks.iteration(), 1);
  // The 2-rank run moved the networks as far as the one-process run did, to float rounding.
  auto initial = trainer(dir / "initial", 0);
  const auto start = snapshot_of(initial), a = snapshot_of(one), b = snapshot_of(ranks);
  expect_close(a, b);
  int agent_moved = 0, disc_moved = 0;
  for (const auto& [name, value] : a)
    if (!torch::equal(value, start.at(name))) ++(name.rfind("agent.", 0) == 0 ? agent_moved : disc_moved);
  EXPECT_GT(agent_moved, 0) << "the iteration left the agent as it was: the comparison would prove nothing";
  EXPECT_GT(disc_moved, 0) << "the iteration left the discriminator as it was";
  // Rank 0 alone wrote the one metrics row, with the run's step and episode counts.
  const auto rows_one = lines_of(dir / "one" / "metrics.csv"), rows_ranks = lines_of(dir / "ranks" / "metrics.csv");
  ASSERT_EQ(rows_ranks.size(), 2u);
  const auto counts = [](const std::string& row) { return row.substr(0, row.find(',', row.find(',', row.find(',') + 1) + 1)); };
  EXPECT_EQ(counts(rows_ranks[1]), counts(rows_one[1]));
}

TEST_F(DistributedGailTest, ARunResumesUnderAnotherRankCount) {
  if (!have_mpirun()) GTEST_SKIP() << "built without MPI or no mpirun";
  trainer(dir / "resumed", 1).train();    // one process
  train_on_ranks(2, dir / "resumed", 2);  // the second iteration on two ranks
  auto whole = trainer(dir / "whole", 2);
  whole.train();
  auto resumed = trainer(dir / "resumed", 2);
  ASSERT_EQ(resumed.iteration(), 2);
  expect_close(snapshot_of(whole), snapshot_of(resumed));
  EXPECT_EQ(lines_of(dir / "resumed" / "metrics.csv").size(), 3u);
}

}  // namespace
}  // namespace vaegail
