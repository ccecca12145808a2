// CMA-ES, the covariance matrix adaptation evolution strategy (Hansen, "The CMA Evolution
// Strategy: A Tutorial", arXiv:1604.00772, 2016): a derivative-free minimiser for a few dozen
// continuous parameters whose cost is noisy and expensive, here a gait controller's score over
// simulated episodes (`vaegail experts tune`). Each generation samples lambda candidates from
// N(m, sigma^2 C), ranks them by cost, moves the mean to their weighted best half and adapts C
// (rank-one update along the evolution path p_c, rank-mu update from the ranked steps) and sigma
// (cumulative step-size adaptation along p_sigma). Every constant is the tutorial's default
// (its Table 1), with positive recombination weights only.
//
// Ask and tell: ask() gives the generation's candidates, the caller scores them (in any order,
// on any number of processes), tell() takes the costs in the candidates' order. The candidates
// of generation g are drawn from a stream seeded by (seed, g), so that the search is a function
// of the seed and the costs alone, and state() / from_state() resume it exactly (JSON, written
// by the tuner with its checkpoint).
//
// Unbounded: a caller with bounds searches a normalised space and repairs or penalises
// candidates outside it (the tuner does both).
#pragma once

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <vector>

namespace vaegail {

struct CmaEsOptions {
  int population = 0;    // lambda, candidates per generation; 0: the default 4 + floor(3 ln n)
  double sigma = 0.3;    // initial step size (the search space's units)
  std::uint64_t seed = 0;
};

class CmaEs {
 public:
  // Starts at `mean` with C = I. Throws std::invalid_argument for an empty mean, sigma <= 0 or
  // a population under 2.
  CmaEs(std::vector<double> mean, CmaEsOptions options);

  // The candidates of the current generation (the same on every call until tell()).
  const std::vector<std::vector<double>>& ask();
  // Ends the generation: costs[k] is the cost of ask()[k] (lower is better). Throws
  // std::invalid_argument unless there is one finite-or-infinite, non-NaN cost per candidate.
  void tell(const std::vector<double>& costs);

  int dimension() const { return static_cast<int>(mean_.size()); }
  int population() const { return lambda_; }
  int generation() const { return generation_; }
  const std::vector<double>& mean() const { return mean_; }
  double sigma() const { return sigma_; }
  // The best candidate told so far, and its cost (+inf before the first tell()).
  const std::vector<double>& best() const { return best_; }
  double best_cost() const { return best_cost_; }

  // Everything that determines the rest of the search.
  nlohmann::json state() const;
  // Throws std::invalid_argument naming the key when `state` is not one that state() wrote.
  static CmaEs from_state(const nlohmann::json& state);

 private:
  void set_strategy_constants();
  // B and D from C (C = B diag(D^2) B^T), after an update.
  void decompose();

  std::vector<double> mean_;
  CmaEsOptions options_;
  int lambda_ = 0, mu_ = 0;
  std::vector<double> weights_;
  double mu_eff_ = 0, c_sigma_ = 0, d_sigma_ = 0, c_c_ = 0, c_1_ = 0, c_mu_ = 0, chi_n_ = 0;

  double sigma_ = 0;
  int generation_ = 0;
  std::vector<double> p_sigma_, p_c_;
  std::vector<double> cov_;  // C, n x n row-major
  std::vector<double> basis_, scales_;  // B (columns: eigenvectors) and D (sqrt of eigenvalues)
  std::vector<std::vector<double>> candidates_, steps_;  // x_k and y_k = (x_k - m) / sigma
  std::vector<double> best_;
  double best_cost_;
};

}  // namespace vaegail
