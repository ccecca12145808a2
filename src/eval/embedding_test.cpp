#include "eval/embedding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace vaegail::eval {
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
  EXPECT_NE(format_classification(result).find("40 / 40 = 100.0%"), std::string::npos) << format_classification(result);
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
  EXPECT_NE(format_classification(result).find("each expert left out"), std::string::npos);
  EXPECT_EQ(result.per_expert.at("a").neighbours, (std::map<std::string, int>{{"b", 2}}));
  EXPECT_NE(format_classification(result, true).find("  expert a (target 1): 0 / 2; nearest: b 2\n"), std::string::npos)
      << format_classification(result, true);
  EXPECT_EQ(format_classification(result).find("  expert a"), std::string::npos);
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

// Target t's experts sit at mu_0 = scale t, each with its own style in mu_1 (spread 2 apart),
// and mu_2 is a collapsed dimension (0 on every row). Two experts per target but 3. The held-out
// expert (target 1) shares its style with expert a (target -1): the vote follows the style, the
// read-out the speed.
std::vector<EmbeddingRow> speed_along_one_direction(double scale) {
  std::vector<EmbeddingRow> rows;
  auto add = [&](const std::string& expert, double target, double style, bool held_out) {
    for (int i = 0; i < 5; ++i) {
      EmbeddingRow r = row(static_cast<int>(rows.size()), target, held_out, {scale * target, style + 0.01 * i, 0.0});
      r.expert_id = expert;
      rows.push_back(r);
    }
  };
  add("a", -1, 0, false);
  add("b", 0, 2, false);
  add("c", 1, 4, false);
  add("d", 3, 6, false);
  add("e", 0, 8, false);
  add("f", -1, 10, false);
  add("g", 1, 12, false);
  add("unseen", 1, 0, true);
  return rows;
}

double mean_readout(const TargetClassification& result, const std::string& expert) {
  const auto& e = result.per_expert.at(expert);
  return e.readout_sum / e.total;
}

TEST(EmbeddingTest, LinearReadoutFindsTheTargetAlongOneDirection) {
  const auto rows = speed_along_one_direction(0.2);
  EXPECT_EQ(knn_classify(rows, 5).correct, 0);  // all five neighbours are a's
  const auto result = linear_classify(rows);
  EXPECT_TRUE(result.linear);
  EXPECT_EQ(result.correct, 5);
  // The targets are exactly 5 mu_0: the unseen rows' 0.2 reads as 1, less the ridge's shrinkage.
  EXPECT_NEAR(mean_readout(result, "unseen"), 1.0, 0.1);
  const std::string text = format_classification(result, true);
  EXPECT_NE(text.find("linear read-out (ridge "), std::string::npos) << text;
  EXPECT_NE(text.find("on held-out embeddings: 5 / 5 = 100.0%\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  expert unseen (target 1): 5 / 5; mean read-out +"), std::string::npos) << text;
}

TEST(EmbeddingTest, LinearReadoutRidgeIsTheLargestThatReadsLeftOutExpertsBest) {
  // Targets 500 mu_0: a ridge of 1e-3 or more shrinks the weight until -1 and 1 read as 0.
  auto small = linear_classify(speed_along_one_direction(0.002));
  EXPECT_LE(small.ridge, 1e-4);
  EXPECT_EQ(small.correct, 5);
  // Targets mu_0 / 2: every ridge up to 10 reads the left-out experts alike, and ties go up.
  EXPECT_GE(linear_classify(speed_along_one_direction(2.0)).ridge, 10.0);
}

TEST(EmbeddingTest, LinearReadoutLeftOutIsRefitWithoutTheExpert) {
  auto rows = speed_along_one_direction(0.2);
  rows.resize(rows.size() - 5);  // the held-out expert plays no part
  // Left out, each expert is read by the line through the others. The nearest target is one of
  // the other experts', so d (target 3, the only one) cannot be right.
  const auto result = linear_classify_leave_one_expert_out(rows);
  EXPECT_TRUE(result.leave_one_expert_out);
  EXPECT_EQ(result.total, 35);
  EXPECT_EQ(result.correct, 30);
  EXPECT_EQ(result.per_target.at(3.0), (std::pair<int, int>{0, 5}));
  EXPECT_GT(mean_readout(result, "d"), 2.0);  // read as fast, snapped to the others' fastest, 1
  // An expert off the others' line is read by their line, not by its own rows.
  for (auto& r : rows)
    if (r.expert_id == "b") r.mu[0] = 0.2;
  EXPECT_NEAR(mean_readout(linear_classify_leave_one_expert_out(rows), "b"), 1.0, 0.1);
  EXPECT_THROW(linear_classify(rows), std::invalid_argument);  // nothing held out
}

}  // namespace
}  // namespace vaegail::eval
