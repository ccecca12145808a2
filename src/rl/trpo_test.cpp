#include "rl/trpo.h"

#include <gtest/gtest.h>

#include "rl/gaussian_policy.h"
#include "rl/test_support.h"

namespace vaegail {
namespace {

std::shared_ptr<GaussianPolicy> tiny_policy(torch::Dtype dtype = torch::kFloat32) {
  GaussianPolicyOptions o;
  o.input_dim = 3;
  o.act_dim = 2;
  o.hidden = {4};
  o.output_gain = 1.0;
  o.init_log_std = -0.5;
  auto policy = std::make_shared<GaussianPolicy>(o);
  policy->to(dtype);
  return policy;
}

// The explicit Fisher matrix of a diagonal Gaussian policy: the mean over samples of JᵀMJ,
// J the Jacobian of (mean, log σ) with respect to the parameters and M = diag(1/σ², 2), the
// Fisher metric of a Gaussian in those coordinates.
torch::Tensor explicit_fisher(GaussianPolicy& policy, const torch::Tensor& inputs) {
  const auto params = policy.trainable_parameters();
  int64_t n = 0;
  for (const auto& p : params) n += p.numel();
  auto fisher = torch::zeros({n, n}, torch::kFloat64);
  for (int64_t b = 0; b < inputs.size(0); ++b) {
    const auto d = policy.distribution(inputs.slice(0, b, b + 1));
    const auto outputs = torch::cat({d.mean[0], d.log_std[0]});
    const auto sigma = torch::exp(d.log_std[0]).detach();
    const auto metric = torch::cat({sigma.pow(-2), torch::full_like(sigma, 2.0)});
    std::vector<torch::Tensor> rows;
    for (int64_t k = 0; k < outputs.size(0); ++k) {
      auto grads = torch::autograd::grad({outputs[k]}, params, {}, true, false, true);
      std::vector<torch::Tensor> flat;
      for (size_t i = 0; i < grads.size(); ++i)
        flat.push_back(grads[i].defined() ? grads[i].reshape({-1}) : torch::zeros({params[i].numel()}));
      rows.push_back(torch::cat(flat).to(torch::kFloat64));
    }
    const auto jacobian = torch::stack(rows);
    fisher += jacobian.t().mm(metric.unsqueeze(1).to(torch::kFloat64) * jacobian);
  }
  return fisher / static_cast<double>(inputs.size(0));
}

TEST(Trpo, FisherVectorProductEqualsTheExplicitFisherTimesV) {
  torch::manual_seed(0);
  auto policy = tiny_policy(torch::kFloat64);
  const auto inputs = torch::randn({6, 3}, torch::kFloat64);
  const auto fisher = explicit_fisher(*policy, inputs);
  const double damping = 0.1;
  const auto fvp = fisher_vector_product(*policy, inputs, torch::Tensor(), damping);
  for (int trial = 0; trial < 3; ++trial) {
    const auto v = torch::randn({fisher.size(0)}, torch::kFloat64);
    const auto expected = fisher.mv(v) + damping * v;
    EXPECT_TRUE(torch::allclose(fvp(v), expected, 1e-9, 1e-10)) << (fvp(v) - expected).abs().max();
  }
}

TEST(Trpo, ConjugateGradientSolvesASmallSpdSystem) {
  torch::manual_seed(1);
  const auto q = torch::randn({6, 6}, torch::kFloat64);
  const auto a = q.t().mm(q) + 0.5 * torch::eye(6, torch::kFloat64);
  const auto b = torch::randn({6}, torch::kFloat64);
  const auto x = conjugate_gradient([&](const torch::Tensor& v) { return a.mv(v); }, b, 6, 1e-30);
  EXPECT_TRUE(torch::allclose(a.mv(x), b, 1e-8, 1e-8)) << a.mv(x) - b;
  // Fewer iterations: an approximation, but already a descent direction.
  const auto x2 = conjugate_gradient([&](const torch::Tensor& v) { return a.mv(v); }, b, 2);
  EXPECT_GT(x2.dot(b).item<double>(), 0.0);
}

UpdateBatch random_batch(GaussianPolicy& policy, int64_t size, std::uint64_t seed) {
  torch::manual_seed(seed);
  auto gen = at::detail::createCPUGenerator(seed);
  torch::NoGradGuard no_grad;
  const auto inputs = torch::randn({size, 3});
  const auto dist = policy.distribution(inputs);
  const auto actions = dist.sample(gen);
  const auto advantages = torch::randn({size});
  return {inputs, actions, dist.log_prob(actions), (advantages - advantages.mean()) / advantages.std(),
          torch::randn({size})};
}

TEST(Trpo, AStepNeverExceedsTheKlBoundAndImprovesTheSurrogate) {
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    // With little damping the quadratic model's full step overshoots the bound on most seeds, so
    // the line search's KL test is exercised, not only the step-length formula.
    for (auto [max_kl, damping] : {std::pair{0.01, 0.1}, {1e-4, 0.1}, {0.01, 1e-3}, {0.1, 1e-3}, {0.5, 1e-2}}) {
      auto policy = tiny_policy();
      CriticOptions critic_options;
      critic_options.input_dim = 3;
      critic_options.hidden = {4};
      TrpoOptions options;
      options.max_kl = max_kl;
      options.cg_damping = damping;
      Trpo trpo(policy, std::make_shared<Critic>(critic_options), options);
      const UpdateBatch batch = random_batch(*policy, 128, seed);
      DiagGaussian before;
      {
        torch::NoGradGuard no_grad;
        before = policy->distribution(batch.inputs);
      }
      const TrpoStats stats = trpo.update(batch);
      torch::NoGradGuard no_grad;
      const double kl = kl_divergence(before, policy->distribution(batch.inputs)).mean().item<double>();
      ASSERT_TRUE(stats.accepted) << "seed " << seed << ", max_kl " << max_kl << ", damping " << damping;
      EXPECT_LE(kl, max_kl) << "seed " << seed << ", max_kl " << max_kl << ", damping " << damping;
      EXPECT_NEAR(kl, stats.kl, 1e-6);
      EXPECT_GT(kl, 0.0);
      EXPECT_GT(stats.surrogate_improvement, 0.0);
      EXPECT_LT(stats.value_loss_after, stats.value_loss_before);
    }
  }
}

TEST(Trpo, SolvesThePointMassTask) { expect_solves_point_mass<Trpo>(TrpoOptions{}); }

}  // namespace
}  // namespace vaegail
