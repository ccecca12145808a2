#include "gail/behavior_cloning.h"

#include <gtest/gtest.h>

#include "gail/test_support.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

TEST(BehaviorCloning, RecoversALinearGaussianPolicy) {
  torch::manual_seed(11);
  const auto W = torch::tensor({{0.5f, -1.0f, 0.2f}, {1.5f, 0.3f, -0.7f}}), b = torch::tensor({0.1f, -0.4f});
  const double noise = 0.05;
  // Observations far from zero mean and unit scale: the normaliser has to matter.
  const auto sample_x = [](int64_t n) { return torch::randn({n, 3}) * torch::tensor({2.f, 0.5f, 1.f}) + 3.0; };
  const auto x = sample_x(4000);
  const auto a = torch::matmul(x, W.t()) + b + noise * torch::randn({4000, 2});
  BcOptions o;
  o.hidden = {};  // a linear mean can represent the truth exactly
  o.epochs = 100;
  o.batch_size = 100;
  o.learning_rate = 3e-2;
  BehaviorCloning bc(x, a, o);
  const double start = bc.nll(x, a);
  for (int e = 0; e < o.epochs; ++e) bc.train_epoch();
  EXPECT_EQ(bc.epoch(), o.epochs);

  const auto x_test = sample_x(500);
  torch::NoGradGuard no_grad;
  const auto dist = bc.agent().policy().distribution(bc.agent().input(x_test, torch::zeros({500, 0})));
  EXPECT_LT((dist.mean - (torch::matmul(x_test, W.t()) + b)).abs().max().item<double>(), 0.05);
  EXPECT_NEAR(dist.log_std.exp().mean().item<double>(), noise, 0.005);
  // The Gaussian's own negative log-likelihood per 2-d action is log(2πe)·1 + 2·log(0.05) ≈ -3.15.
  EXPECT_LT(bc.nll(x, a), -2.9);
  EXPECT_LT(bc.nll(x, a), start);
}

// A checkpoint on a full file system: refused in one line, the one before kept and loadable.
TEST(BehaviorCloning, ACheckpointOnAFullDiskIsRefusedAndTheOneBeforeStillLoads) {
  SmallFileSystem small(512 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  BcOptions o;
  o.hidden = {16};
  BehaviorCloning bc(torch::randn({50, 3}), torch::randn({50, 2}), o);
  bc.train_epoch();
  const std::string path = small.path("latest.pt");
  expect_refused_on_a_full_disk_then_saved(small, path, [&] { bc.save_checkpoint(path); });
  BehaviorCloning loaded(torch::randn({50, 3}), torch::randn({50, 2}), o);
  loaded.load_checkpoint(path);
  EXPECT_EQ(loaded.epoch(), 1);
}

}  // namespace
}  // namespace vaegail
