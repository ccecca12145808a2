// Exact t-SNE (van der Maaten & Hinton 2008): maps N points in d dimensions to the plane so
// that neighbours stay neighbours. Used on VAE embeddings of demonstrations (the paper's
// Figure 4, left). Cost is O(N^2) per iteration: meant for up to a few thousand points.
//
// Arrays are row-major doubles: data [N, d], similarity matrices [N, N], embeddings [N, 2].
#pragma once

#include <cstdint>
#include <vector>

namespace vaegail::eval {

struct TsneOptions {
  double perplexity = 30;  // effective number of neighbours; needs N - 1 > perplexity >= 1
  int iterations = 1000;
  double learning_rate = 200;
  double early_exaggeration = 12;   // P is multiplied by this for the first iterations...
  int exaggeration_iterations = 250;  // ...this many, which also run with momentum 0.5, not 0.8
  std::uint64_t seed = 0;             // of the initial layout
};

struct TsneResult {
  std::vector<double> embedding;  // [N, 2], centred on the origin
  double kl_divergence = 0;       // KL(P || Q) of the final layout
};

// Throws std::invalid_argument on a size mismatch, non-finite data or an impossible perplexity.
TsneResult tsne(const std::vector<double>& data, int n, int d, const TsneOptions& options = {});

// The stages, exposed for tests.
std::vector<double> squared_distances(const std::vector<double>& data, int n, int d);
// Row i holds p_{j|i} proportional to exp(-beta_i * D_ij), p_{i|i} = 0, with beta_i found by
// bisection so that the row's entropy (in nats) is log(perplexity).
std::vector<double> conditional_probabilities(const std::vector<double>& sq_distances, int n,
                                              double perplexity);
// (P_{j|i} + P_{i|j}) / 2N: symmetric, summing to one.
std::vector<double> joint_probabilities(const std::vector<double>& conditional, int n);
// KL(P || Q) with q_ij proportional to 1 / (1 + |y_i - y_j|^2), and its gradient with respect
// to y (the sum over j of 4 (exaggeration * p_ij - q_ij) (y_i - y_j) / (1 + |y_i - y_j|^2)).
double kl_divergence(const std::vector<double>& p, const std::vector<double>& y, int n);
std::vector<double> kl_gradient(const std::vector<double>& p, const std::vector<double>& y, int n,
                                double exaggeration = 1.0);

}  // namespace vaegail::eval
