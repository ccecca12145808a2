#include "vae/bilstm.h"

#include <gtest/gtest.h>

namespace vaegail::vae {
namespace {

namespace rnn = torch::nn::utils::rnn;

constexpr int64_t kInput = 5, kHidden = 8, kSteps = 9;

class BiLstmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    torch::manual_seed(7);
  }

  // The stock module the BiLstm must equal, with the BiLstm's weights.
  torch::nn::LSTM stock_copy_of(BiLstm& ours) {
    torch::nn::LSTM stock(
        torch::nn::LSTMOptions(kInput, kHidden).num_layers(2).bidirectional(true).batch_first(true));
    torch::NoGradGuard no_grad;
    for (auto& p : stock->named_parameters()) p.value().copy_(ours->named_parameters()[p.key()]);
    return stock;
  }

  // torch::nn::LSTM on packed sequences, padded back with zeros: the reference semantics.
  static torch::Tensor stock_forward(torch::nn::LSTM& stock, const torch::Tensor& x,
                                     const torch::Tensor& lengths) {
    const auto packed = rnn::pack_padded_sequence(x, lengths, /*batch_first=*/true, /*enforce_sorted=*/false);
    const auto out = std::get<0>(stock->forward_with_packed_input(packed));
    return std::get<0>(rnn::pad_packed_sequence(out, /*batch_first=*/true, 0.0, x.size(1)));
  }

  const torch::Tensor lengths_ = torch::tensor({9, 4, 1, 7}, torch::kLong);
};

TEST_F(BiLstmTest, HasTheStockModulesParameterNamesShapesOrderAndInitialisation) {
  torch::manual_seed(3);
  torch::nn::LSTM stock(
      torch::nn::LSTMOptions(kInput, kHidden).num_layers(2).bidirectional(true).batch_first(true));
  torch::manual_seed(3);
  BiLstm ours(kInput, kHidden, 2);
  const auto a = stock->named_parameters(), b = ours->named_parameters();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].key(), b[k].key());
    EXPECT_TRUE(torch::equal(a[k].value(), b[k].value())) << a[k].key();
  }
}

TEST_F(BiLstmTest, ForwardEqualsTheStockLstmOnPackedRows) {
  BiLstm ours(kInput, kHidden, 2);
  auto stock = stock_copy_of(ours);
  const auto x = torch::randn({4, kSteps, kInput});
  const auto expected = stock_forward(stock, x, lengths_);
  const auto got = ours->forward(x, lengths_);
  ASSERT_EQ(got.sizes(), expected.sizes());
  EXPECT_LT((got - expected).abs().max().item<double>(), 1e-5);
  // All rows full: the stock module without packing.
  const auto full = torch::full({4}, kSteps, torch::kLong);
  EXPECT_LT((ours->forward(x, full) - std::get<0>(stock->forward(x))).abs().max().item<double>(), 1e-5);
}

TEST_F(BiLstmTest, GradientsEqualAutogradThroughTheStockLstm) {
  BiLstm ours(kInput, kHidden, 2);
  auto stock = stock_copy_of(ours);
  const auto x = torch::randn({4, kSteps, kInput});
  const auto weights = torch::randn({4, kSteps, 2 * kHidden});  // a loss that reads every output
  const auto x_ours = x.clone().requires_grad_(true), x_stock = x.clone().requires_grad_(true);
  (ours->forward(x_ours, lengths_) * weights).sum().backward();
  (stock_forward(stock, x_stock, lengths_) * weights).sum().backward();
  EXPECT_LT((x_ours.grad() - x_stock.grad()).abs().max().item<double>(), 1e-5);
  const auto expected = stock->named_parameters();
  for (const auto& p : ours->named_parameters()) {
    const auto& g = p.value().grad();
    ASSERT_TRUE(g.defined()) << p.key();
    EXPECT_GT(g.abs().max().item<double>(), 1e-3) << p.key();  // non-trivial, so equality means something
    EXPECT_LT((g - expected[p.key()].grad()).abs().max().item<double>(), 1e-5) << p.key();
  }
}

TEST_F(BiLstmTest, APaddedRowEqualsTheRowRunAloneAtItsLength) {
  BiLstm ours(kInput, kHidden, 2);
  const auto row = torch::randn({1, 4, kInput});
  // Row 0: 4 real steps, then padding of large values; row 1: full of other values.
  const auto padded = torch::cat(
      {torch::cat({row, torch::full({1, kSteps - 4, kInput}, 1e3)}, 1), torch::randn({1, kSteps, kInput})});
  const auto both = ours->forward(padded, torch::tensor({int64_t{4}, kSteps}));
  const auto alone = ours->forward(row, torch::tensor({int64_t{4}}));
  EXPECT_LT((both[0].narrow(0, 0, 4) - alone[0]).abs().max().item<double>(), 1e-6);
  EXPECT_EQ(both[0].narrow(0, 4, kSteps - 4).abs().max().item<double>(), 0.0);
  // And the padding does reach row 0's backward direction when the row is not cut at its length.
  const auto uncut = ours->forward(padded, torch::tensor({kSteps, kSteps}));
  EXPECT_GT((uncut[0][3] - both[0][3]).narrow(0, kHidden, kHidden).abs().max().item<double>(), 1e-3);
}

TEST_F(BiLstmTest, RecurrenceGradientsEqualFiniteDifferences) {
  // The hand-written backward through time alone against central differences on a tiny case
  // (float, so a loose tolerance; a wrong gate derivative is off by far more).
  const int64_t S = 3, B = 2, H = 2;
  const auto gates_in = torch::randn({S, B, 4 * H}).requires_grad_(true);
  const auto w_hh = torch::randn({4 * H, H}).requires_grad_(true);
  const auto weights = torch::randn({S, B, H});
  (lstm_recurrence(gates_in, w_hh) * weights).sum().backward();
  const auto loss = [&](const torch::Tensor& g, const torch::Tensor& w) {
    return (lstm_recurrence(g, w) * weights).sum().item<double>();
  };
  torch::NoGradGuard no_grad;
  const double eps = 1e-2;
  for (const auto* t : {&gates_in, &w_hh}) {
    const auto flat = t->detach().reshape(-1);
    for (int64_t k = 0; k < flat.numel(); ++k) {
      auto plus = flat.clone(), minus = flat.clone();
      plus[k] += eps;
      minus[k] -= eps;
      const bool is_gates = t == &gates_in;
      const double lp =
          is_gates ? loss(plus.view_as(*t), w_hh.detach()) : loss(gates_in.detach(), plus.view_as(*t));
      const double lm =
          is_gates ? loss(minus.view_as(*t), w_hh.detach()) : loss(gates_in.detach(), minus.view_as(*t));
      EXPECT_NEAR(t->grad().reshape(-1)[k].item<double>(), (lp - lm) / (2 * eps), 2e-3) << k;
    }
  }
}

}  // namespace
}  // namespace vaegail::vae
