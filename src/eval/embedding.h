// Embeddings of demonstrations as CSV (`vaegail vae embed`) and two tests of their structure
// (`vaegail vae knn`): do held-out demonstrations land next to training demonstrations of the
// same target speed (k-nearest-neighbour vote), and does one direction of z hold the target speed
// (linear read-out)?
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

namespace vaegail::eval {

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

// One classified expert: how many of its rows were classified right, whose rows were their
// nearest (k-NN: expert id -> how often among the k nearest of its rows), and the sum of its
// rows' read-outs (linear read-out).
struct ExpertVote {
  std::set<double> contexts;  // more than one for a context-conditioned expert
  int correct = 0, total = 0;
  std::map<std::string, int> neighbours;
  double readout_sum = 0;
};

struct TargetClassification {
  bool leave_one_expert_out = false;  // false: the held-out rows against the training rows
  bool linear = false;                // the linear read-out rather than the k-NN vote
  int k = 0;  // k-NN: the k asked for, or the fewest rows a query's pool held if that was fewer
  double ridge = 0;  // linear read-out of the held-out rows: the ridge it chose
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
TargetClassification knn_classify(const std::vector<EmbeddingRow>& rows, int k);
// The same vote for every training row against the training rows of the other experts (by
// expert_id): each training expert in turn plays the unseen one. With a few held-out experts
// the held-out vote has a few outcomes that matter; this one has one per training expert.
// Throws std::invalid_argument with fewer than two training experts.
TargetClassification knn_classify_leave_one_expert_out(const std::vector<EmbeddingRow>& rows, int k);

// The linear read-out: the target as an affine function of mu fit by ridge regression on the
// training rows, its ridge the one that classifies the training experts best when each is left
// out in turn; each held-out row gets the training target nearest its read-out. The k-NN vote
// weighs every direction of z alike, so an unseen gait next to a training gait of another speed
// is voted that speed even when one direction of z holds the speed; this read-out tells the two
// apart. Throws std::invalid_argument without held-out rows or with fewer than two training experts.
TargetClassification linear_classify(const std::vector<EmbeddingRow>& rows);
// The read-out refit without each training expert in turn (its ridge chosen over the others
// alone), which it then classifies.
TargetClassification linear_classify_leave_one_expert_out(const std::vector<EmbeddingRow>& rows);

// by_expert adds a line per classified expert: its score and, for the k-NN vote, the experts
// nearest to it (which names the training expert a wrongly voted held-out expert was taken
// for), for the read-out its rows' mean read-out.
std::string format_classification(const TargetClassification& result, bool by_expert = false);

}  // namespace vaegail::eval
