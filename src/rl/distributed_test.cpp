#include "rl/distributed.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "rl/update_batch.h"
#include "util/world.h"

namespace vaegail {
namespace {

// The two halves of a run of 4 environments, as ranks 0 and 1 of two hold them.
const EnvSlice kFirstHalf{0, 2, 4}, kSecondHalf{2, 2, 4};

std::vector<int64_t> values(const torch::Tensor& t) {
  const auto c = t.to(torch::kLong).contiguous();
  return {c.data_ptr<int64_t>(), c.data_ptr<int64_t>() + c.numel()};
}

TEST(EnvSlice, OneProcessHoldsEveryEnvironment) {
  ASSERT_FALSE(World::get().distributed());
  const EnvSlice s = EnvSlice::of_world(6);
  EXPECT_EQ(s.first, 0);
  EXPECT_EQ(s.count, 6);
  EXPECT_EQ(s.total, 6);
  EXPECT_THROW(EnvSlice::of_world(0), std::invalid_argument);
}

TEST(EnvSlice, UnevenSharesAreContiguousInRankOrderAndDifferByAtMostOne) {
  const auto shares = [](int total, int ranks) {
    std::vector<std::pair<int, int>> out;
    for (int r = 0; r < ranks; ++r) {
      const EnvSlice s = EnvSlice::share(total, r, ranks);
      EXPECT_EQ(s.total, total);
      out.emplace_back(s.first, s.count);
    }
    return out;
  };
  EXPECT_EQ(shares(5, 2), (std::vector<std::pair<int, int>>{{0, 2}, {2, 3}}));
  EXPECT_EQ(shares(16, 2), (std::vector<std::pair<int, int>>{{0, 8}, {8, 8}}));
  EXPECT_EQ(shares(7, 3), (std::vector<std::pair<int, int>>{{0, 2}, {2, 2}, {4, 3}}));
  EXPECT_EQ(shares(1, 3), (std::vector<std::pair<int, int>>{{0, 0}, {0, 0}, {0, 1}}));
  EXPECT_EQ(shares(4, 1), (std::vector<std::pair<int, int>>{{0, 4}}));
  EXPECT_THROW(EnvSlice::share(4, 2, 2), std::invalid_argument);
}

TEST(RowSlice, ARolloutsRowsAreTimeMajorOverTheRunsEnvironments) {
  // Step t of the run's environment e is row t * 4 + e.
  EXPECT_EQ(values(RowSlice::of_rollout(3, kSecondHalf).global_rows), (std::vector<int64_t>{2, 3, 6, 7, 10, 11}));
  EXPECT_EQ(RowSlice::of_rollout(3, kSecondHalf).global_size, 12);
  EXPECT_EQ(values(RowSlice::of_rollout(2, EnvSlice::whole(3)).global_rows), (std::vector<int64_t>{0, 1, 2, 3, 4, 5}));
}

TEST(RowSlice, LocalRowsFindTheRanksShareOfAGlobalSubsetInItsOrder) {
  const RowSlice rows = RowSlice::of_rollout(3, kSecondHalf);  // global 2, 3, 6, 7, 10, 11
  EXPECT_EQ(values(rows.local_rows(torch::tensor({11, 0, 2, 5, 7}))), (std::vector<int64_t>{5, 0, 3}));
  const RowSlice whole = RowSlice::whole(5);
  EXPECT_EQ(values(whole.local_rows(torch::tensor({4, 1}))), (std::vector<int64_t>{4, 1}));
}

UpdateBatch batch_of(const RowSlice& rows) {
  const auto id = rows.global_rows.to(torch::kFloat32);
  return {id.unsqueeze(1), id.unsqueeze(1), id, id, id, rows};
}

TEST(UpdateBatch, TheRanksMinibatchesTogetherAreTheOneProcessMinibatches) {
  const auto whole = batch_of(RowSlice::of_rollout(5, EnvSlice::whole(4)));
  const auto first = batch_of(RowSlice::of_rollout(5, kFirstHalf)), second = batch_of(RowSlice::of_rollout(5, kSecondHalf));
  auto g0 = at::detail::createCPUGenerator(3), g1 = at::detail::createCPUGenerator(3),
       g2 = at::detail::createCPUGenerator(3);
  const auto all = whole.minibatches(3, g0), a = first.minibatches(3, g1), b = second.minibatches(3, g2);
  ASSERT_EQ(all.size(), 3u);
  for (size_t k = 0; k < all.size(); ++k) {
    // The same global rows (the inputs hold each row's global index), each on the rank that has it.
    auto mine = values(torch::cat({a[k].inputs, b[k].inputs}).reshape({-1}));
    auto expected = values(all[k].inputs.reshape({-1}));
    std::sort(mine.begin(), mine.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(mine, expected);
    EXPECT_EQ(a[k].global_size(), all[k].size());
    for (auto g : values(a[k].inputs.reshape({-1}))) EXPECT_LT(g % 4, 2) << "a row of the other rank's environments";
  }
}

TEST(UpdateBatch, TheFisherSubsampleIsEveryKthRowOfTheRun) {
  const auto whole = batch_of(RowSlice::whole(12));
  const auto [rows, count] = whole.every(5);
  EXPECT_EQ(values(rows), (std::vector<int64_t>{0, 5, 10}));
  EXPECT_EQ(count, 3);
  // Rank 1 of two holds environments 2, 3 of 4: global rows 2, 3, 6, 7, 10, 11 at local 0..5.
  const auto [second, total] = batch_of(RowSlice::of_rollout(3, kSecondHalf)).every(5);
  EXPECT_EQ(values(second), (std::vector<int64_t>{4}));  // global row 10
  EXPECT_EQ(total, 3);
}

TEST(Distributed, SumsAreTheIdentityInAWorldOfOne) {
  const auto t = torch::tensor({1.5, -2.0});
  EXPECT_TRUE(torch::equal(all_sum(t), t));
  EXPECT_EQ(all_sum(3.25), 3.25);
}

}  // namespace
}  // namespace vaegail
