#include "vae/policy_refit.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "util/run_lock.h"
#include "vae/toy_trajectories.h"

namespace vaegail::vae {
namespace {

namespace fs = std::filesystem;

constexpr int64_t kTrajectories = 6, kSteps = 12, kStateDim = 4, kActionDim = 2;

struct RefitFixture {
  TrajectoryVae vae{testing::tiny_vae_config(kStateDim, kActionDim)};
  TrajectoryDataset data;
  torch::Tensor mu;
};

RefitFixture make_fixture(uint64_t seed) {
  torch::manual_seed(seed);
  RefitFixture f;
  auto [states, actions] = testing::toy_trajectories(kTrajectories, kSteps, kStateDim, kActionDim, seed);
  f.vae->fit_normalization(states, actions);
  f.data = {states, actions, {}};
  f.mu = encode(f.vae, f.data).first;
  return f;
}

class PolicyRefitTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    root_ = fs::temp_directory_path() / ("policy_refit_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  PolicyRefitOptions options(const std::string& name, int epochs) const {
    PolicyRefitOptions o;
    o.out_dir = (root_ / name).string();
    o.epochs = epochs;
    o.batch = 16;
    o.learning_rate = 3e-3;
    o.seed = 7;
    o.progress = false;
    return o;
  }

  fs::path root_;
};

std::vector<torch::Tensor> copies(const std::vector<torch::Tensor>& parameters) {
  std::vector<torch::Tensor> out;
  for (const auto& p : parameters) out.push_back(p.detach().clone());
  return out;
}

bool all_equal(const std::vector<torch::Tensor>& a, const std::vector<torch::Tensor>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!torch::equal(a[i], b[i])) return false;
  return true;
}

TEST_F(PolicyRefitTest, RecordsAreTheRealStepsNormalisedWithTheirTrajectorysZ) {
  auto f = make_fixture(1);
  const auto all = step_records(f.vae, f.data, f.mu);
  ASSERT_EQ(all.size(), kTrajectories * kSteps);
  // Row t of trajectory 2: its normalised state and action, and trajectory 2's mu.
  const int64_t row = 2 * kSteps + 5;
  EXPECT_TRUE(torch::allclose(all.x[row], f.vae->normalize_states(f.data.states[2][5])));
  EXPECT_TRUE(torch::allclose(all.a[row], f.vae->normalize_actions(f.data.actions[2][5])));
  EXPECT_TRUE(torch::equal(all.z[row], f.mu[2]));
  // Padding (even NaN) is dropped: trajectory 0 keeps 4 steps.
  f.data.mask = torch::ones({kTrajectories, kSteps}, torch::kBool);
  f.data.mask.index_put_({0, torch::indexing::Slice(4)}, false);
  f.data.actions.index_put_({0, torch::indexing::Slice(4)}, NAN);
  const auto masked = step_records(f.vae, f.data, f.mu);
  ASSERT_EQ(masked.size(), kTrajectories * kSteps - (kSteps - 4));
  EXPECT_FALSE(masked.a.isnan().any().item<bool>());
  EXPECT_TRUE(torch::equal(masked.x[4], all.x[kSteps]));  // trajectory 1's first step follows trajectory 0's fourth
  EXPECT_THROW(step_records(f.vae, f.data, f.mu.narrow(0, 0, 3)), std::invalid_argument);
}

TEST_F(PolicyRefitTest, BorrowedLatentsComeFromSourceRowsOfTheSameLabel) {
  // Source row j has mu (j, j): the label of the row it came from is readable off the value.
  const auto source = torch::arange(6, torch::kFloat).unsqueeze(1).expand({6, 2}).contiguous();
  const std::vector<double> source_labels = {0, 1, 2, 0, 1, 2};
  const std::vector<double> target_labels = {2, 2, 0, 1, 0, 2, 1, 1};
  const auto z = latents_by_label(source, source_labels, target_labels, 5);
  ASSERT_EQ(z.size(0), 8);
  std::set<int> drawn;
  for (int i = 0; i < 8; ++i) {
    const int j = static_cast<int>(z[i][0].item<float>());
    EXPECT_EQ(source_labels[j], target_labels[i]);
    EXPECT_TRUE(torch::equal(z[i], source[j]));
    drawn.insert(j);
  }
  EXPECT_GT(drawn.size(), 3u);  // not always the first row of a label
  EXPECT_TRUE(torch::equal(latents_by_label(source, source_labels, target_labels, 5), z));  // seeded
  EXPECT_THROW(latents_by_label(source, source_labels, {3}, 5), std::invalid_argument);
  EXPECT_THROW(latents_by_label(source, {0, 1}, target_labels, 5), std::invalid_argument);
}

TEST_F(PolicyRefitTest, FitIsTheDecodersNllAndTheRawRmseOfItsMean) {
  auto f = make_fixture(2);
  // Demonstrated actions = the decoder's own mean + 0.3 in raw units: the RMSE is 0.3.
  const auto z_steps = f.mu.unsqueeze(1).expand({kTrajectories, kSteps, f.mu.size(1)});
  {
    torch::NoGradGuard no_grad;
    f.data.actions = f.vae->action_mean(f.data.states.narrow(1, 0, kSteps), z_steps) + 0.3;
  }
  const auto records = step_records(f.vae, f.data, f.mu);
  const auto fit = policy_fit(f.vae, records, 7);  // batches that do not divide the rows
  EXPECT_NEAR(fit.rmse, 0.3, 1e-5);
  torch::NoGradGuard no_grad;
  const double nll = -f.vae->action_decoder()->log_prob(records.x, records.z, records.a).mean().item<double>();
  EXPECT_NEAR(fit.nll, nll, 1e-4 * std::abs(nll));
}

TEST_F(PolicyRefitTest, TrainsOnlyTheActionDecoderAndLowersItsError) {
  auto f = make_fixture(3);
  const auto records = step_records(f.vae, f.data, f.mu);
  const auto encoder = copies(f.vae->encoder()->parameters());
  const auto state_decoder = copies(f.vae->state_decoder()->parameters());
  const auto action_decoder = copies(f.vae->action_decoder()->parameters());
  const auto r = refit_policy(f.vae, records, {}, options("run", 40));
  EXPECT_EQ(r.epochs_run, 40);
  EXPECT_LT(r.train.rmse, 0.5 * r.before_train.rmse);
  EXPECT_LT(r.train.nll, r.before_train.nll - 1.0);
  EXPECT_TRUE(std::isnan(r.val.nll));
  EXPECT_TRUE(all_equal(copies(f.vae->encoder()->parameters()), encoder));
  EXPECT_TRUE(all_equal(copies(f.vae->state_decoder()->parameters()), state_decoder));
  EXPECT_FALSE(all_equal(copies(f.vae->action_decoder()->parameters()), action_decoder));
  // The weights file is the whole refitted VAE, loadable as any VAE run.
  auto loaded = load_trained_vae((root_ / "run" / "weights.pt").string());
  torch::NoGradGuard no_grad;
  const auto z_steps = f.mu.unsqueeze(1).expand({kTrajectories, kSteps, f.mu.size(1)});
  const auto x = f.data.states.narrow(1, 0, kSteps);
  EXPECT_TRUE(torch::allclose(loaded->action_mean(x, z_steps), f.vae->action_mean(x, z_steps)));
}

TEST_F(PolicyRefitTest, AResumedRefitEndsWhereAnUninterruptedOneDoes) {
  auto whole = make_fixture(4);
  const auto records = step_records(whole.vae, whole.data, whole.mu);
  refit_policy(whole.vae, records, records, options("whole", 6));
  // A run killed during its last epoch: the checkpoint of epoch 5 (the one latest.pt replaced)
  // is its newest, and metrics.csv already holds the row of epoch 6.
  fs::copy(root_ / "whole", root_ / "cut", fs::copy_options::recursive);
  fs::rename(root_ / "cut" / "checkpoints" / "previous.pt", root_ / "cut" / "checkpoints" / "latest.pt");
  auto resumed = make_fixture(4);
  const auto r = refit_policy(resumed.vae, records, records, options("cut", 6));
  EXPECT_EQ(r.epochs_run, 1);
  EXPECT_TRUE(all_equal(copies(resumed.vae->action_decoder()->parameters()),
                        copies(whole.vae->action_decoder()->parameters())));
  std::ifstream metrics(root_ / "cut" / "metrics.csv");
  int lines = 0;
  for (std::string line; std::getline(metrics, line);) ++lines;
  EXPECT_EQ(lines, 7);  // the header and epochs 1-6, epoch 6 once
  // A second writer on the same directory is refused while the first holds it.
  {
    const RunLock held = lock_run_directory((root_ / "cut").string());
    EXPECT_THROW(refit_policy(resumed.vae, records, records, options("cut", 6)), std::runtime_error);
  }
  // A finished run trains nothing further.
  EXPECT_EQ(refit_policy(resumed.vae, records, records, options("cut", 6)).epochs_run, 0);
}

}  // namespace
}  // namespace vaegail::vae
