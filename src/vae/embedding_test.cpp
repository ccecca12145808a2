#include "vae/embedding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace vaegail::vae {
namespace {

EmbeddingRow row(int episode, double context, bool held_out, std::vector<double> mu) {
  EmbeddingRow r;
  r.episode = episode;
  r.expert_id = "e" + std::to_string(episode % 4);
  r.context = context;
  r.achieved_speed = context + 0.1;
  r.held_out = held_out;
  r.sigma.assign(mu.size(), 0.5);
  r.mu = std::move(mu);
  return r;
}

TEST(EmbeddingTest, CsvHasExactlyTheDocumentedColumns) {
  const std::string csv = embedding_csv({row(0, -1, false, {0.5, -2}), row(7, 3, true, {1, 0.25})});
  const std::string expected =
      "episode,expert_id,context,achieved_speed,held_out,mu_0,mu_1,sigma_0,sigma_1\n"
      "0,e0,-1,-0.9,0,0.5,-2,0.5,0.5\n"
      "7,e3,3,3.1,1,1,0.25,0.5,0.5\n";
  EXPECT_EQ(csv, expected);
}

TEST(EmbeddingTest, CsvRoundTrips) {
  const std::vector<EmbeddingRow> rows{row(0, -1, false, {0.123456789, -2}), row(1, 0, true, {1e-7, 3})};
  const auto back = parse_embedding_csv(embedding_csv(rows), "x.csv");
  ASSERT_EQ(back.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].episode, rows[i].episode);
    EXPECT_EQ(back[i].expert_id, rows[i].expert_id);
    EXPECT_EQ(back[i].held_out, rows[i].held_out);
    for (size_t j = 0; j < 2; ++j) EXPECT_NEAR(back[i].mu[j], rows[i].mu[j], 1e-8 * (1 + std::abs(rows[i].mu[j])));
  }
}

TEST(EmbeddingTest, MalformedCsvNamesTheLine) {
  const std::string good = embedding_csv({row(0, -1, false, {0.5})});
  EXPECT_THROW(parse_embedding_csv("a,b\n", "x.csv"), std::invalid_argument);
  try {
    parse_embedding_csv(good + "1,e1,0,0,0,zz,1\n", "x.csv");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv: line 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_embedding_csv(good + "1,e1,0\n", "x.csv"), std::invalid_argument);
  try {
    parse_embedding_csv(good + "1,e1,nan,nan,0,0.5,nan\n", "x.csv");  // nan labels pass, a nan sigma not
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv: line 3: sigma_0 is not finite"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_embedding_csv(good + "1,e1,nan,nan,0,0.5,1\n", "x.csv").size(), 2u);
}

// Four targets, each a Gaussian blob in 3-d; held-out rows drawn from the same blobs.
std::vector<EmbeddingRow> synthetic(double spread, uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> noise(0.0, spread);
  const double targets[] = {-1, 0, 1, 3};
  std::vector<EmbeddingRow> rows;
  int episode = 0;
  for (int i = 0; i < 40; ++i)
    for (int t = 0; t < 4; ++t) {
      std::vector<double> mu{4.0 * t + noise(gen), (t % 2 ? 3.0 : -3.0) + noise(gen), noise(gen)};
      rows.push_back(row(episode++, targets[t], i >= 30, mu));
    }
  return rows;
}

TEST(EmbeddingTest, KnnRecoversSeparatedTargets) {
  const auto result = knn_classify(synthetic(0.3, 1), 5);
  EXPECT_EQ(result.total, 40);
  EXPECT_EQ(result.correct, 40);
  ASSERT_EQ(result.per_target.size(), 4u);
  EXPECT_EQ(result.per_target.at(3.0), (std::pair<int, int>{10, 10}));
  EXPECT_NE(format_knn(result).find("40 / 40 = 100.0%"), std::string::npos) << format_knn(result);
}

TEST(EmbeddingTest, KnnIsNearChanceOnOverlappingTargets) {
  const auto result = knn_classify(synthetic(100.0, 2), 5);
  EXPECT_LT(result.accuracy(), 0.6);
}

TEST(EmbeddingTest, KnnVotesAndBreaksTiesByTheNearest) {
  // Query at 0: neighbours 0.1 (target 1), 0.2 (target 2), 0.3 (target 2), 0.4 (target 1).
  std::vector<EmbeddingRow> rows{row(0, 1, false, {0.1}), row(1, 2, false, {0.2}), row(2, 2, false, {0.3}),
                                 row(3, 1, false, {0.4}), row(4, 1, true, {0.0})};
  EXPECT_EQ(knn_classify(rows, 1).correct, 1);  // nearest: target 1
  EXPECT_EQ(knn_classify(rows, 3).correct, 0);  // 2 votes for target 2
  EXPECT_EQ(knn_classify(rows, 4).correct, 1);  // 2 : 2, the nearest tied target wins
  rows.pop_back();
  EXPECT_THROW(knn_classify(rows, 3), std::invalid_argument);  // nothing held out
}

TEST(EmbeddingTest, LeaveOneExpertOutVotesWithoutTheExpertsOwnRows) {
  // Expert a (target 1) sits next to expert b (target 2) and far from c and d (target 1):
  // with its own rows in the pool a would be right; without them its nearest are b's.
  auto at = [](const std::string& expert, double context, double x) {
    EmbeddingRow r = row(0, context, false, {x});
    r.expert_id = expert;
    return r;
  };
  const std::vector<EmbeddingRow> rows{at("a", 1, 0.0),  at("a", 1, 0.1),  at("b", 2, 0.2),
                                       at("b", 2, 0.3),  at("c", 1, 10.0), at("d", 1, 10.1)};
  const auto result = knn_classify_leave_one_expert_out(rows, 1);
  EXPECT_EQ(result.total, 6);
  EXPECT_EQ(result.correct, 2);  // a's two rows go to b, b's to a; c and d find each other
  EXPECT_EQ(result.experts, 4);
  EXPECT_EQ(result.experts_majority_correct, 2);
  EXPECT_EQ(result.per_target.at(2.0), (std::pair<int, int>{0, 2}));
  EXPECT_NE(format_knn(result).find("each expert left out"), std::string::npos);
  EXPECT_EQ(result.per_expert.at("a").neighbours, (std::map<std::string, int>{{"b", 2}}));
  EXPECT_NE(format_knn(result, true).find("  expert a (target 1): 0 / 2; nearest: b 2\n"), std::string::npos)
      << format_knn(result, true);
  EXPECT_EQ(format_knn(result).find("  expert a"), std::string::npos);
  EXPECT_THROW(knn_classify_leave_one_expert_out({at("a", 1, 0), at("a", 1, 1)}, 1), std::invalid_argument);
}

TEST(EmbeddingTest, KnnReportsTheSmallestPoolsK) {
  // Left out, b's rows vote among a's single row (k 1), a's row among b's three (k 3).
  auto at = [](const std::string& expert, double x) {
    EmbeddingRow r = row(0, 1, false, {x});
    r.expert_id = expert;
    return r;
  };
  EXPECT_EQ(knn_classify_leave_one_expert_out({at("b", 0), at("b", 1), at("b", 2), at("a", 3)}, 3).k, 1);
  EXPECT_EQ(knn_classify(synthetic(0.3, 1), 5).k, 5);
}

TEST(EmbeddingTest, KnnCountsExpertsWithAMajorityCorrect) {
  const auto result = knn_classify(synthetic(0.3, 1), 5);
  EXPECT_EQ(result.experts, 4);  // row() names experts e0..e3
  EXPECT_EQ(result.experts_majority_correct, 4);
}

}  // namespace
}  // namespace vaegail::vae
