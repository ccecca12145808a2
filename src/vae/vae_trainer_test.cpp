#include "vae/vae_trainer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/csv_table.h"
#include "util/test_ranks.h"
#include "util/test_small_fs.h"
#include "vae/toy_trajectories.h"

namespace vaegail::vae {
namespace {

namespace fs = std::filesystem;

// Smaller than testing::tiny_vae_config, and a fast learning rate: many short runs below.
VaeConfig tiny_config() {
  VaeConfig c = testing::tiny_vae_config(3, 2);
  c.lstm_hidden = 8;
  c.action_hidden = {16};
  c.wavenet_channels = 4;
  c.batch_size = 3;
  c.learning_rate = 3e-3;
  return c;
}

TrajectoryDataset toy_dataset(int64_t M, uint64_t seed, bool ragged) {
  auto [states, actions] = testing::toy_trajectories(M, 7, 3, 2, seed);
  TrajectoryDataset d{states, actions, {}};
  if (ragged) {
    d.mask = torch::ones({M, 7}, torch::kBool);
    d.mask.index_put_({0, torch::indexing::Slice(4)}, false);
  }
  return d;
}

class VaeTrainerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    root_ = fs::temp_directory_path() /
            ("vae_trainer_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  TrainerOptions options(const std::string& name, int epochs) const {
    TrainerOptions o;
    o.run_dir = (root_ / name).string();
    o.epochs = epochs;
    o.seed = 42;
    o.progress = false;
    return o;
  }

  fs::path root_;
};

int count_lines(const fs::path& p) {
  std::ifstream in(p);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST_F(VaeTrainerTest, WritesMetricsConfigAndCheckpoint) {
  VaeTrainer trainer(tiny_config(), options("run", 2), toy_dataset(7, 1, true), toy_dataset(4, 2, false));
  const auto metrics = trainer.train();
  ASSERT_EQ(metrics.size(), 2u);
  EXPECT_EQ(metrics[1].epoch, 2);
  EXPECT_TRUE(std::isfinite(metrics[1].val.total));
  EXPECT_NEAR(metrics[1].train.total,
              metrics[1].train.action_nll + metrics[1].train.state_nll + metrics[1].train.kl, 1e-3);
  const fs::path dir = root_ / "run";
  EXPECT_EQ(count_lines(dir / "metrics.csv"), 3);  // header + 2 epochs
  std::ifstream csv(dir / "metrics.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "epoch,train_loss,train_action_nll,train_state_nll,train_kl,val_loss,val_action_nll,"
            "val_state_nll,val_kl,seconds");
  EXPECT_EQ(VaeConfig::load((dir / "config.json").string()), tiny_config());
  EXPECT_TRUE(fs::exists(dir / "checkpoints" / "latest.pt"));
  for (const auto& entry : fs::directory_iterator(dir / "checkpoints"))
    EXPECT_EQ(entry.path().filename(), "latest.pt") << "left behind: " << entry.path();
}

TEST_F(VaeTrainerTest, KeepEpochsLeavesEachEpochsCheckpointLoadableAndDistinct) {
  auto o = options("run", 2);
  o.keep_epochs = true;
  VaeTrainer trainer(tiny_config(), o, toy_dataset(7, 1, true), {});
  trainer.train();
  const auto x = trainer.model()->normalize_states(toy_dataset(1, 5, false).states);
  const auto encode_with = [&](const std::string& path) {
    return load_trained_vae(path)->encoder()->forward(x);
  };
  const auto first = encode_with(trainer.epoch_checkpoint_path(1));
  const auto second = encode_with(trainer.epoch_checkpoint_path(2));
  const auto latest = encode_with(trainer.checkpoint_path());
  EXPECT_TRUE(torch::equal(second.mean, latest.mean));
  EXPECT_FALSE(torch::allclose(first.mean, second.mean));
}

TEST_F(VaeTrainerTest, TrainingReducesTheLoss) {
  VaeTrainer trainer(tiny_config(), options("run", 15), toy_dataset(9, 3, false), {});
  const auto metrics = trainer.train();
  EXPECT_LT(metrics.back().train.total, metrics.front().train.total - 5.0);
  EXPECT_TRUE(std::isnan(metrics.back().val.total));
}

TEST_F(VaeTrainerTest, TheOptimiserTakesTheConfiguredLearningRateAndWeightDecay) {
  auto c = tiny_config();
  c.weight_decay = 1e-3;
  VaeTrainer trainer(c, options("run", 1), toy_dataset(3, 1, false), {});
  const auto& adam = static_cast<const torch::optim::AdamOptions&>(
      trainer.optimizer().param_groups().front().options());
  EXPECT_DOUBLE_EQ(adam.weight_decay(), 1e-3);
  EXPECT_DOUBLE_EQ(adam.lr(), c.learning_rate);
}

TEST(ScheduledLearningRateTest, ConstantWithoutDecayCosineToZeroWithIt) {
  auto c = tiny_config();
  EXPECT_DOUBLE_EQ(scheduled_learning_rate(c, 1), c.learning_rate);
  EXPECT_DOUBLE_EQ(scheduled_learning_rate(c, 1000), c.learning_rate);
  c.lr_decay_epochs = 4;  // epochs 1..4 at cos(0), cos(pi/4), cos(pi/2), cos(3 pi/4)
  EXPECT_DOUBLE_EQ(scheduled_learning_rate(c, 1), c.learning_rate);
  EXPECT_NEAR(scheduled_learning_rate(c, 2), c.learning_rate * (1 + std::sqrt(0.5)) / 2, 1e-15);
  EXPECT_NEAR(scheduled_learning_rate(c, 3), c.learning_rate / 2, 1e-15);
  EXPECT_NEAR(scheduled_learning_rate(c, 4), c.learning_rate * (1 - std::sqrt(0.5)) / 2, 1e-15);
  EXPECT_THROW(scheduled_learning_rate(c, 5), std::invalid_argument);
  EXPECT_THROW(scheduled_learning_rate(c, 0), std::invalid_argument);
}

TEST_F(VaeTrainerTest, EachEpochRunsAtItsScheduledRateAndResumeKeepsTheSchedule) {
  auto c = tiny_config();
  c.lr_decay_epochs = 3;
  const auto rate = [](VaeTrainer& t) {
    return static_cast<const torch::optim::AdamOptions&>(t.optimizer().param_groups().front().options()).lr();
  };
  const auto train = toy_dataset(6, 4, false);
  {
    VaeTrainer first(c, options("run", 2), train, {});
    first.train_epoch();
    EXPECT_DOUBLE_EQ(rate(first), scheduled_learning_rate(c, 1));
    first.train_epoch();
    EXPECT_DOUBLE_EQ(rate(first), scheduled_learning_rate(c, 2));
  }
  VaeTrainer resumed(c, options("run", 3), train, {});
  EXPECT_DOUBLE_EQ(resumed.batch_learning_rate(3, 0), scheduled_learning_rate(c, 3));  // Adam's moments kept: no ramp
  resumed.train();
  EXPECT_DOUBLE_EQ(rate(resumed), scheduled_learning_rate(c, 3));
  EXPECT_THROW(VaeTrainer(c, options("run", 4), train, {}), std::invalid_argument);
}

TEST_F(VaeTrainerTest, ResumeReproducesTheUninterruptedRun) {
  const auto train = toy_dataset(8, 4, true), val = toy_dataset(3, 5, false);
  VaeTrainer straight(tiny_config(), options("straight", 3), train, val);
  const auto full = straight.train();
  {
    VaeTrainer first(tiny_config(), options("resumed", 1), train, val);
    first.train();
  }
  // As if killed after writing epoch 2's row but before its checkpoint.
  std::ofstream((root_ / "resumed" / "metrics.csv").string(), std::ios::app) << "2,1,1,1,1,1,1,1,1,1\n";
  VaeTrainer resumed(tiny_config(), options("resumed", 3), train, val);
  EXPECT_EQ(resumed.epoch(), 1);
  const auto rest = resumed.train();
  ASSERT_EQ(rest.size(), 2u);
  EXPECT_EQ(rest.back().train.total, full.back().train.total);
  EXPECT_EQ(rest.back().val.total, full.back().val.total);
  const auto a = straight.model()->named_parameters(), b = resumed.model()->named_parameters();
  for (const auto& p : a) EXPECT_TRUE(torch::equal(p.value(), b[p.key()])) << p.key();
  // One row per epoch, equal to the uninterrupted run's but for the last column (seconds).
  const auto without_seconds = [](const std::string& csv) {
    std::istringstream in(csv);
    std::string out;
    for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  EXPECT_EQ(without_seconds(read_file((root_ / "resumed" / "metrics.csv").string())),
            without_seconds(read_file((root_ / "straight" / "metrics.csv").string())));
  EXPECT_EQ(count_lines(root_ / "resumed" / "metrics.csv"), 4);
}

// What a repository keeps of a long run: weights.pt beside metrics.csv, no checkpoint. The same
// command resumes at its epoch with its parameters; an exported weights file (no epoch) is refused.
TEST_F(VaeTrainerTest, ARunKeptAsItsWeightsAloneResumesAtItsEpoch) {
  const auto train = toy_dataset(8, 4, true);
  std::vector<torch::Tensor> trained;
  {
    VaeTrainer first(tiny_config(), options("run", 2), train, {});
    first.train();
    for (const auto& p : first.model()->parameters()) trained.push_back(p.detach().clone());
  }
  fs::remove_all(root_ / "run" / "checkpoints");
  {
    VaeTrainer resumed(tiny_config(), options("run", 3), train, {});
    EXPECT_EQ(resumed.epoch(), 2);
    // Adam starts afresh: the rate ramps up over the resumed epoch's three minibatches, then follows its schedule.
    const double rate = scheduled_learning_rate(tiny_config(), 3);
    EXPECT_DOUBLE_EQ(resumed.batch_learning_rate(3, 0), rate / 3);
    EXPECT_DOUBLE_EQ(resumed.batch_learning_rate(3, 1), rate * 2 / 3);
    EXPECT_DOUBLE_EQ(resumed.batch_learning_rate(3, 2), rate);
    EXPECT_DOUBLE_EQ(resumed.batch_learning_rate(4, 0), scheduled_learning_rate(tiny_config(), 4));
    const auto parameters = resumed.model()->parameters();
    ASSERT_EQ(parameters.size(), trained.size());
    for (size_t k = 0; k < trained.size(); ++k) EXPECT_TRUE(torch::equal(parameters[k], trained[k])) << k;
    EXPECT_EQ(resumed.train().size(), 1u);
    EXPECT_EQ(count_lines(root_ / "run" / "metrics.csv"), 4);
    save_vae_weights(resumed.model(), resumed.weights_path());  // as `vaegail export` writes it
  }
  fs::remove_all(root_ / "run" / "checkpoints");
  EXPECT_NE(error_of([&] { VaeTrainer(tiny_config(), options("run", 4), train, {}); }).find("no epoch"), std::string::npos);
  auto other = tiny_config();
  other.latent_dim = 3;
  EXPECT_NE(error_of([&] { VaeTrainer(other, options("run", 4), train, {}); }).find("different VaeConfig"), std::string::npos);
}

// A checkpoint on a full file system: refused in one line, the one before kept; a new trainer (the
// rerun command) resumes from it once there is room.
TEST_F(VaeTrainerTest, ACheckpointOnAFullDiskIsRefusedAndTheRunResumesFromTheOneBefore) {
  SmallFileSystem small(1024 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  TrainerOptions o = options("run", 2);
  o.run_dir = small.path("run");
  const auto train = toy_dataset(4, 6, false);
  {
    VaeTrainer trainer(tiny_config(), o, train, {});
    trainer.train_epoch();
    expect_refused_on_a_full_disk_then_saved(small, trainer.checkpoint_path(),
                                             [&] { trainer.save_checkpoint(trainer.checkpoint_path()); });
    expect_refused_on_a_full_disk_then_saved(small, trainer.weights_path(), [&] {
      save_vae_weights(trainer.model(), trainer.weights_path(), trainer.epoch());
    });
  }
  VaeTrainer resumed(tiny_config(), o, train, {});
  EXPECT_EQ(resumed.epoch(), 1);
  EXPECT_EQ(resumed.train().size(), 1u);
}

// One run directory, one trainer: a second is refused while the first holds it.
TEST_F(VaeTrainerTest, ASecondTrainerOnTheRunDirectoryIsRefused) {
  const VaeTrainer first(tiny_config(), options("run", 1), toy_dataset(4, 6, false), {});
  EXPECT_EQ(error_of([&] { VaeTrainer(tiny_config(), options("run", 1), toy_dataset(4, 6, false), {}); }),
            options("run", 1).run_dir + ": in use by process " + std::to_string(::getpid()) + " (another vaegail run)");
}

TEST_F(VaeTrainerTest, ResumeRefusesAnotherConfig) {
  { VaeTrainer(tiny_config(), options("run", 1), toy_dataset(4, 6, false), {}).train(); }
  auto other = tiny_config();
  other.latent_dim = 3;
  EXPECT_THROW(VaeTrainer(other, options("run", 2), toy_dataset(4, 6, false), {}),
               std::invalid_argument);
}

TEST_F(VaeTrainerTest, EncodeAndLoadTrainedModel) {
  const auto data = toy_dataset(5, 7, true);
  VaeTrainer trainer(tiny_config(), options("run", 1), data, {});
  trainer.train();
  const auto [mu, sigma] = encode(trainer.model(), data, 2);
  EXPECT_EQ(mu.sizes(), torch::IntArrayRef({5, 2}));
  EXPECT_EQ(sigma.sizes(), mu.sizes());
  auto loaded = load_trained_vae(trainer.checkpoint_path());
  const auto [mu2, sigma2] = encode(loaded, data);
  EXPECT_TRUE(torch::allclose(mu, mu2, 1e-6, 1e-6));
  EXPECT_TRUE(torch::allclose(sigma, sigma2, 1e-6, 1e-6));
}

// ---- Ranks: `mpirun -np K vaegail vae train` (the test binary runs itself under mpirun; the
// RankShare case is the ranks' program, told the run directory and epochs by the variables).
constexpr const char* kVaeRanksRunDir = "VAEGAIL_TEST_VAE_RANKS_RUN_DIR";
constexpr const char* kVaeRanksEpochs = "VAEGAIL_TEST_VAE_RANKS_EPOCHS";

class VaeTrainerRanksTest : public VaeTrainerTest {
 protected:
  // 7 ragged training trajectories in batches of 3, 3, 1: on 2 ranks uneven shares (1 + 2) and a
  // rank without rows; 5 validation trajectories in evaluation batches of 4 and 1; z of 3 and
  // noise on the encoder's input, both drawn per batch.
  static VaeTrainer trainer(const fs::path& run_dir, int epochs) {
    VaeConfig c = tiny_config();
    c.latent_dim = 3;
    c.encoder_input_noise = 0.3;
    TrainerOptions o;
    o.run_dir = run_dir.string();
    o.epochs = epochs;
    o.seed = 42;
    o.progress = false;
    o.eval_batch_size = 4;
    return VaeTrainer(c, o, toy_dataset(7, 1, true), toy_dataset(5, 2, true));
  }

  void train_on_ranks(int ranks, const fs::path& run_dir, int epochs) {
    fs::create_directories(root_);
    const std::string failure =
        run_case_on_ranks(ranks, "VaeTrainerRanksTest.RankShare",
                          {{kVaeRanksRunDir, run_dir.string()}, {kVaeRanksEpochs, std::to_string(epochs)}},
                          root_ / "mpirun.log");
    ASSERT_TRUE(failure.empty()) << failure;
  }
};

std::map<std::string, torch::Tensor> parameters_of(VaeTrainer& t) {
  std::map<std::string, torch::Tensor> out;
  for (const auto& p : t.model()->named_parameters()) out[p.key()] = p.value().detach().clone();
  return out;
}

void expect_close(const std::map<std::string, torch::Tensor>& a, const std::map<std::string, torch::Tensor>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, value] : a)
    EXPECT_TRUE(torch::allclose(value, b.at(name), 1e-5, 1e-5))
        << name << ": largest difference " << (value - b.at(name)).abs().max().item<double>();
}

// metrics.csv's loss columns (not seconds) agree to float rounding, row by row.
void expect_same_losses(const fs::path& a, const fs::path& b) {
  const auto x = CsvTable::read(a.string()), y = CsvTable::read(b.string());
  ASSERT_EQ(x.rows(), y.rows());
  for (const auto& column : x.columns()) {
    if (column == "seconds") continue;
    const auto u = x.numbers(column), v = y.numbers(column);
    for (size_t i = 0; i < u.size(); ++i)
      EXPECT_NEAR(u[i], v[i], 1e-5 * std::max(1.0, std::abs(u[i]))) << column << " of epoch " << i + 1;
  }
}

TEST_F(VaeTrainerRanksTest, RankShare) {
  const char* run_dir = std::getenv(kVaeRanksRunDir);
  if (run_dir == nullptr) GTEST_SKIP() << "the ranks' program of the tests below, run by them under mpirun";
  trainer(run_dir, std::atoi(std::getenv(kVaeRanksEpochs))).train();
}

TEST_F(VaeTrainerRanksTest, TwoRanksTrainWhatOneProcessTrains) {
  if (!have_mpirun()) GTEST_SKIP() << "built without MPI or no mpirun";
  train_on_ranks(2, root_ / "ranks", 2);
  auto one = trainer(root_ / "one", 2);
  one.train();
  auto ranks = trainer(root_ / "ranks", 2);  // loads the 2-rank run's checkpoint
  ASSERT_EQ(ranks.epoch(), 2);
  const auto a = parameters_of(one), b = parameters_of(ranks);
  expect_close(a, b);
  // 6 Adam steps moved every parameter: the comparison is not of two initialisations.
  auto initial = trainer(root_ / "initial", 0);
  const auto start = parameters_of(initial);
  for (const auto& [name, value] : a) EXPECT_FALSE(torch::equal(value, start.at(name))) << name << " never moved";
  // Rank 0 alone wrote one row per epoch, with the run's training and validation losses.
  EXPECT_EQ(count_lines(root_ / "ranks" / "metrics.csv"), 3);
  expect_same_losses(root_ / "one" / "metrics.csv", root_ / "ranks" / "metrics.csv");
}

TEST_F(VaeTrainerRanksTest, ARunResumesUnderAnotherRankCount) {
  if (!have_mpirun()) GTEST_SKIP() << "built without MPI or no mpirun";
  trainer(root_ / "resumed", 1).train();    // one process
  train_on_ranks(2, root_ / "resumed", 2);  // the second epoch on two ranks
  auto whole = trainer(root_ / "whole", 2);
  whole.train();
  auto resumed = trainer(root_ / "resumed", 2);
  ASSERT_EQ(resumed.epoch(), 2);
  expect_close(parameters_of(whole), parameters_of(resumed));
  expect_same_losses(root_ / "whole" / "metrics.csv", root_ / "resumed" / "metrics.csv");
}

TEST_F(VaeTrainerTest, RejectsMalformedData) {
  auto bad = toy_dataset(4, 8, false);
  bad.actions = bad.actions.narrow(1, 0, 5);
  EXPECT_THROW(VaeTrainer(tiny_config(), options("run", 1), bad, {}), std::invalid_argument);
  auto holes = toy_dataset(4, 8, false);
  holes.mask = torch::ones({4, 7}, torch::kBool);
  holes.mask.index_put_({1, 2}, false);
  EXPECT_THROW(VaeTrainer(tiny_config(), options("run", 1), holes, {}), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail::vae
