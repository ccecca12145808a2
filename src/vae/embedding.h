// Embeddings of demonstrations as CSV (`vaegail vae embed`) and the k-nearest-neighbour test
// of their structure (`vaegail vae knn`): do held-out demonstrations land next to training
// demonstrations of the same target speed?
//
// CSV columns, exactly:
//   episode,expert_id,context,achieved_speed,held_out,mu_0..mu_{d-1},sigma_0..sigma_{d-1}
// episode = index in the demonstration file, context = its first context value (the walker's
// target speed), achieved_speed = mean forward speed, held_out = 0/1, (mu, sigma) = q(z | x).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace vaegail::vae {

struct EmbeddingRow {
  int episode = 0;
  std::string expert_id;
  double context = 0;
  double achieved_speed = 0;
  bool held_out = false;
  std::vector<double> mu, sigma;
};

// Header and one line per row; all rows must have the same latent size.
std::string embedding_csv(const std::vector<EmbeddingRow>& rows);
// Throws std::invalid_argument "where: line N: problem" on a malformed file.
std::vector<EmbeddingRow> parse_embedding_csv(const std::string& text, const std::string& where);

// One classified expert: how many of its rows were voted right, and whose rows were their
// nearest (expert id -> how often among the k nearest of its rows).
struct ExpertVote {
  std::set<double> contexts;  // more than one for a context-conditioned expert
  int correct = 0, total = 0;
  std::map<std::string, int> neighbours;
};

struct KnnResult {
  bool leave_one_expert_out = false;  // false: the held-out rows against the training rows
  int k = 0;  // the k asked for, or the fewest rows a query's pool held if that was fewer
  int total = 0, correct = 0;
  std::map<double, std::pair<int, int>> per_target;  // context -> (correct, total)
  // Experts whose rows were classified, and those with more than half of them correct.
  int experts = 0, experts_majority_correct = 0;
  std::map<std::string, ExpertVote> per_expert;
  double accuracy() const { return total ? static_cast<double>(correct) / total : 0.0; }
};

// Each held-out row gets the context most common among its k nearest training rows
// (Euclidean on mu); a tied vote goes to the tied context with the nearest member.
// Throws std::invalid_argument without training or held-out rows.
KnnResult knn_classify(const std::vector<EmbeddingRow>& rows, int k);
// The same vote for every training row against the training rows of the other experts (by
// expert_id): each training expert in turn plays the unseen one. With a few held-out experts
// the held-out vote has a few outcomes that matter; this one has one per training expert.
// Throws std::invalid_argument with fewer than two training experts.
KnnResult knn_classify_leave_one_expert_out(const std::vector<EmbeddingRow>& rows, int k);
// by_expert adds a line per classified expert: its score and the experts nearest to it,
// which names the training expert a wrongly voted held-out expert was taken for.
std::string format_knn(const KnnResult& result, bool by_expert = false);

}  // namespace vaegail::vae
