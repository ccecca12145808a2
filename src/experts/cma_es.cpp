#include "experts/cma_es.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <stdexcept>
#include <string>

#include "util/rng.h"

namespace vaegail {
namespace {

// Eigen-decomposition of a symmetric n x n matrix by cyclic Jacobi rotations: `a` is destroyed,
// `vectors` receives the eigenvectors as columns (row-major), the result the eigenvalues. Exact
// to rounding for the small, well-conditioned covariances of a CMA-ES (n of a few dozen), and
// the same bits on every machine, which keeps a resumed search identical.
std::vector<double> jacobi_eigen(std::vector<double> a, int n, std::vector<double>& vectors) {
  vectors.assign(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) vectors[i * n + i] = 1.0;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += a[p * n + q] * a[p * n + q];
    if (off < 1e-30) break;
    for (int p = 0; p < n; ++p) {
      for (int q = p + 1; q < n; ++q) {
        const double apq = a[p * n + q];
        if (std::abs(apq) < 1e-300) continue;
        // The rotation that zeroes a[p][q] (Golub & Van Loan, "symmetric Schur decomposition").
        const double theta = (a[q * n + q] - a[p * n + p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {  // columns p and q
          const double akp = a[k * n + p], akq = a[k * n + q];
          a[k * n + p] = c * akp - s * akq;
          a[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {  // rows p and q
          const double apk = a[p * n + k], aqk = a[q * n + k];
          a[p * n + k] = c * apk - s * aqk;
          a[q * n + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          const double vkp = vectors[k * n + p], vkq = vectors[k * n + q];
          vectors[k * n + p] = c * vkp - s * vkq;
          vectors[k * n + q] = s * vkp + c * vkq;
        }
      }
    }
  }
  std::vector<double> values(n);
  for (int i = 0; i < n; ++i) values[i] = a[i * n + i];
  return values;
}

double norm(const std::vector<double>& v) { return std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0)); }

template <typename T>
T required(const nlohmann::json& state, const char* key) {
  if (!state.contains(key)) throw std::invalid_argument(std::string("CMA-ES state: no '") + key + "'");
  return state.at(key).get<T>();
}

}  // namespace

CmaEs::CmaEs(std::vector<double> mean, CmaEsOptions options)
    : mean_(std::move(mean)), options_(options), sigma_(options.sigma), best_cost_(std::numeric_limits<double>::infinity()) {
  if (mean_.empty()) throw std::invalid_argument("CMA-ES: an empty starting point");
  if (!(options.sigma > 0)) throw std::invalid_argument("CMA-ES: sigma must be positive");
  const int n = dimension();
  lambda_ = options.population > 0 ? options.population : 4 + static_cast<int>(std::floor(3 * std::log(n)));
  if (lambda_ < 2) throw std::invalid_argument("CMA-ES: a population of at least 2");
  set_strategy_constants();
  p_sigma_.assign(n, 0.0);
  p_c_.assign(n, 0.0);
  cov_.assign(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) cov_[i * n + i] = 1.0;
  decompose();
}

void CmaEs::set_strategy_constants() {
  const double n = dimension();
  mu_ = lambda_ / 2;
  weights_.resize(mu_);
  for (int i = 0; i < mu_; ++i) weights_[i] = std::log((lambda_ + 1) / 2.0) - std::log(i + 1.0);
  const double sum = std::accumulate(weights_.begin(), weights_.end(), 0.0);
  for (double& w : weights_) w /= sum;
  mu_eff_ = 1 / std::inner_product(weights_.begin(), weights_.end(), weights_.begin(), 0.0);
  c_sigma_ = (mu_eff_ + 2) / (n + mu_eff_ + 5);
  d_sigma_ = 1 + 2 * std::max(0.0, std::sqrt((mu_eff_ - 1) / (n + 1)) - 1) + c_sigma_;
  c_c_ = (4 + mu_eff_ / n) / (n + 4 + 2 * mu_eff_ / n);
  c_1_ = 2 / ((n + 1.3) * (n + 1.3) + mu_eff_);
  c_mu_ = std::min(1 - c_1_, 2 * (mu_eff_ - 2 + 1 / mu_eff_) / ((n + 2) * (n + 2) + mu_eff_));
  chi_n_ = std::sqrt(n) * (1 - 1 / (4 * n) + 1 / (21 * n * n));  // E||N(0, I)||
}

void CmaEs::decompose() {
  const int n = dimension();
  scales_ = jacobi_eigen(cov_, n, basis_);
  for (double& d : scales_) d = std::sqrt(std::max(d, 1e-20));
}

const std::vector<std::vector<double>>& CmaEs::ask() {
  if (!candidates_.empty()) return candidates_;
  const int n = dimension();
  Rng rng(derive_seed(options_.seed, static_cast<std::uint64_t>(generation_)));
  candidates_.assign(lambda_, std::vector<double>(n));
  steps_.assign(lambda_, std::vector<double>(n));
  std::vector<double> z(n);
  for (int k = 0; k < lambda_; ++k) {
    for (double& zi : z) zi = rng.normal();
    for (int i = 0; i < n; ++i) {  // y = B D z
      double y = 0;
      for (int j = 0; j < n; ++j) y += basis_[i * n + j] * scales_[j] * z[j];
      steps_[k][i] = y;
      candidates_[k][i] = mean_[i] + sigma_ * y;
    }
  }
  return candidates_;
}

void CmaEs::tell(const std::vector<double>& costs) {
  if (candidates_.empty()) throw std::invalid_argument("CMA-ES: tell() without ask()");
  if (static_cast<int>(costs.size()) != lambda_)
    throw std::invalid_argument("CMA-ES: " + std::to_string(costs.size()) + " costs for " + std::to_string(lambda_) +
                                " candidates");
  for (double c : costs)
    if (std::isnan(c)) throw std::invalid_argument("CMA-ES: a NaN cost");
  const int n = dimension();
  std::vector<int> order(lambda_);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return costs[a] < costs[b]; });
  if (costs[order[0]] < best_cost_) {
    best_cost_ = costs[order[0]];
    best_ = candidates_[order[0]];
  }

  // The weighted mean step of the best mu, and the mean's move.
  std::vector<double> y_w(n, 0.0);
  for (int r = 0; r < mu_; ++r)
    for (int i = 0; i < n; ++i) y_w[i] += weights_[r] * steps_[order[r]][i];
  for (int i = 0; i < n; ++i) mean_[i] += sigma_ * y_w[i];

  // p_sigma along C^{-1/2} y_w = B D^-1 B^T y_w: the step in the isotropic frame.
  std::vector<double> bt_y(n, 0.0), c_inv_half_y(n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) bt_y[j] += basis_[i * n + j] * y_w[i];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) c_inv_half_y[i] += basis_[i * n + j] * bt_y[j] / scales_[j];
  const double sigma_gain = std::sqrt(c_sigma_ * (2 - c_sigma_) * mu_eff_);
  for (int i = 0; i < n; ++i) p_sigma_[i] = (1 - c_sigma_) * p_sigma_[i] + sigma_gain * c_inv_half_y[i];

  // h_sigma stalls p_c while p_sigma is long (a large step just taken), as the tutorial does.
  const double p_sigma_norm = norm(p_sigma_);
  const double decay = 1 - std::pow(1 - c_sigma_, 2.0 * (generation_ + 1));
  const bool h_sigma = p_sigma_norm / std::sqrt(decay) < (1.4 + 2 / (n + 1.0)) * chi_n_;
  const double c_gain = std::sqrt(c_c_ * (2 - c_c_) * mu_eff_);
  for (int i = 0; i < n; ++i) p_c_[i] = (1 - c_c_) * p_c_[i] + (h_sigma ? c_gain * y_w[i] : 0.0);

  // C: decay, rank-one along p_c, rank-mu from the ranked steps.
  const double delta = h_sigma ? 0.0 : c_c_ * (2 - c_c_);
  const double keep = 1 + c_1_ * delta - c_1_ - c_mu_;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j <= i; ++j) {
      double rank_mu = 0;
      for (int r = 0; r < mu_; ++r) rank_mu += weights_[r] * steps_[order[r]][i] * steps_[order[r]][j];
      const double c = keep * cov_[i * n + j] + c_1_ * p_c_[i] * p_c_[j] + c_mu_ * rank_mu;
      cov_[i * n + j] = cov_[j * n + i] = c;
    }
  }
  sigma_ *= std::exp(c_sigma_ / d_sigma_ * (p_sigma_norm / chi_n_ - 1));
  decompose();
  ++generation_;
  candidates_.clear();
  steps_.clear();
}

nlohmann::json CmaEs::state() const {
  return {{"mean", mean_},       {"sigma", sigma_},         {"generation", generation_}, {"population", lambda_},
          {"seed", options_.seed}, {"p_sigma", p_sigma_},   {"p_c", p_c_},               {"covariance", cov_},
          {"best", best_},       {"best_cost", std::isinf(best_cost_) ? nlohmann::json(nullptr) : nlohmann::json(best_cost_)},
          {"initial_sigma", options_.sigma}};
}

CmaEs CmaEs::from_state(const nlohmann::json& state) {
  CmaEsOptions options;
  options.population = required<int>(state, "population");
  options.seed = required<std::uint64_t>(state, "seed");
  options.sigma = required<double>(state, "initial_sigma");
  CmaEs es(required<std::vector<double>>(state, "mean"), options);
  const size_t n = es.mean_.size();
  es.sigma_ = required<double>(state, "sigma");
  es.generation_ = required<int>(state, "generation");
  es.p_sigma_ = required<std::vector<double>>(state, "p_sigma");
  es.p_c_ = required<std::vector<double>>(state, "p_c");
  es.cov_ = required<std::vector<double>>(state, "covariance");
  es.best_ = required<std::vector<double>>(state, "best");
  if (state.contains("best_cost") && !state.at("best_cost").is_null()) es.best_cost_ = state.at("best_cost").get<double>();
  if (es.p_sigma_.size() != n || es.p_c_.size() != n || es.cov_.size() != n * n)
    throw std::invalid_argument("CMA-ES state: the vectors' sizes do not match the mean's " + std::to_string(n));
  es.decompose();
  return es;
}

}  // namespace vaegail
