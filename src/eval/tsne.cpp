#include "eval/tsne.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <string>

#include "util/rng.h"

namespace vaegail::eval {
namespace {

double student_t(double dx, double dy) { return 1.0 / (1.0 + dx * dx + dy * dy); }

// Sum over pairs i < j of the unnormalised similarity; Q's normaliser is twice this.
double student_t_sum(const std::vector<double>& y, int n) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double xi = y[2 * i], yi = y[2 * i + 1];
    for (int j = i + 1; j < n; ++j) sum += student_t(xi - y[2 * j], yi - y[2 * j + 1]);
  }
  return sum;
}

// Row i of the conditional distribution for one beta, written into `row`; returns its entropy.
// Distances are taken relative to the row's smallest so exp() cannot underflow to all zeros.
double fill_row(const double* distances, int n, int i, double nearest, double beta, double* row) {
  double z = 0, weighted = 0;
  for (int j = 0; j < n; ++j) {
    if (j == i) {
      row[j] = 0;
      continue;
    }
    const double shifted = distances[j] - nearest;
    row[j] = std::exp(-beta * shifted);
    z += row[j];
    weighted += row[j] * shifted;
  }
  for (int j = 0; j < n; ++j) row[j] /= z;
  return std::log(z) + beta * weighted / z;
}

void check_perplexity(double perplexity, int n) {
  const std::string text = fmt::format("{:g}", perplexity);
  if (!(perplexity >= 1))
    throw std::invalid_argument(std::string("t-SNE: perplexity must be >= 1, got ") + text);
  if (!(n - 1 > perplexity))
    throw std::invalid_argument(std::string("t-SNE: perplexity ") + text +
                                " needs more than " +
                                std::to_string(static_cast<int>(std::floor(perplexity)) + 1) +
                                " points, got " + std::to_string(n) + "; choose a smaller perplexity");
}

}  // namespace

std::vector<double> squared_distances(const std::vector<double>& data, int n, int d) {
  std::vector<double> out(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      double s = 0;
      for (int k = 0; k < d; ++k) {
        const double diff = data[static_cast<size_t>(i) * d + k] - data[static_cast<size_t>(j) * d + k];
        s += diff * diff;
      }
      out[static_cast<size_t>(i) * n + j] = out[static_cast<size_t>(j) * n + i] = s;
    }
  return out;
}

std::vector<double> conditional_probabilities(const std::vector<double>& sq_distances, int n,
                                              double perplexity) {
  check_perplexity(perplexity, n);
  const double target = std::log(perplexity);
  std::vector<double> p(static_cast<size_t>(n) * n);
  for (int i = 0; i < n; ++i) {
    const double* distances = &sq_distances[static_cast<size_t>(i) * n];
    double* row = &p[static_cast<size_t>(i) * n];
    double nearest = std::numeric_limits<double>::infinity();
    for (int j = 0; j < n; ++j)
      if (j != i) nearest = std::min(nearest, distances[j]);
    // Entropy falls as beta rises: bisect, doubling the upper end until it brackets the target.
    double beta = 1, low = 0, high = std::numeric_limits<double>::infinity();
    for (int step = 0; step < 200; ++step) {
      const double entropy = fill_row(distances, n, i, nearest, beta, row);
      if (std::abs(entropy - target) < 1e-10) break;
      if (entropy > target) {
        low = beta;
        beta = std::isinf(high) ? beta * 2 : (beta + high) / 2;
      } else {
        high = beta;
        beta = (beta + low) / 2;
      }
    }
  }
  return p;
}

std::vector<double> joint_probabilities(const std::vector<double>& conditional, int n) {
  std::vector<double> p(conditional.size());
  const double scale = 1.0 / (2.0 * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      p[static_cast<size_t>(i) * n + j] =
          (conditional[static_cast<size_t>(i) * n + j] + conditional[static_cast<size_t>(j) * n + i]) * scale;
  return p;
}

double kl_divergence(const std::vector<double>& p, const std::vector<double>& y, int n) {
  const double z = 2 * student_t_sum(y, n);
  double kl = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double pij = p[static_cast<size_t>(i) * n + j];
      if (i == j || pij <= 0) continue;
      const double q = student_t(y[2 * i] - y[2 * j], y[2 * i + 1] - y[2 * j + 1]) / z;
      kl += pij * std::log(pij / q);
    }
  return kl;
}

std::vector<double> kl_gradient(const std::vector<double>& p, const std::vector<double>& y, int n,
                                double exaggeration) {
  const double inverse_z = 1.0 / (2 * student_t_sum(y, n));
  std::vector<double> gradient(static_cast<size_t>(n) * 2, 0.0);
  // Each pair once: its force acts on i and, opposite, on j (P and the kernel are symmetric).
  for (int i = 0; i < n; ++i) {
    const double xi = y[2 * i], yi = y[2 * i + 1];
    const double* p_row = &p[static_cast<size_t>(i) * n];
    double gx = 0, gy = 0;
    for (int j = i + 1; j < n; ++j) {
      const double dx = xi - y[2 * j], dy = yi - y[2 * j + 1];
      const double w = student_t(dx, dy);
      const double force = 4 * (exaggeration * p_row[j] - w * inverse_z) * w;
      gx += force * dx;
      gy += force * dy;
      gradient[2 * j] -= force * dx;
      gradient[2 * j + 1] -= force * dy;
    }
    gradient[2 * i] += gx;
    gradient[2 * i + 1] += gy;
  }
  return gradient;
}

TsneResult tsne(const std::vector<double>& data, int n, int d, const TsneOptions& options) {
  if (n < 2 || d < 1 || data.size() != static_cast<size_t>(n) * d)
    throw std::invalid_argument("t-SNE: data holds " + std::to_string(data.size()) +
                                " values, expected N x d = " + std::to_string(n) + " x " +
                                std::to_string(d) + " with N >= 2, d >= 1");
  for (size_t k = 0; k < data.size(); ++k)
    if (!std::isfinite(data[k]))
      throw std::invalid_argument("t-SNE: point " + std::to_string(k / d) + " has a non-finite value");
  check_perplexity(options.perplexity, n);
  if (options.iterations < 0 || !(options.learning_rate > 0))
    throw std::invalid_argument("t-SNE: iterations must be >= 0 and learning rate > 0");

  const auto p = joint_probabilities(
      conditional_probabilities(squared_distances(data, n, d), n, options.perplexity), n);
  Rng rng(options.seed);
  std::vector<double> y(static_cast<size_t>(n) * 2);
  for (double& v : y) v = 1e-4 * rng.normal();
  std::vector<double> update(y.size(), 0.0), gains(y.size(), 1.0);
  for (int it = 0; it < options.iterations; ++it) {
    const bool early = it < options.exaggeration_iterations;
    const double momentum = early ? 0.5 : 0.8;
    const auto gradient = kl_gradient(p, y, n, early ? options.early_exaggeration : 1.0);
    // Per-coordinate step sizes grow while the gradient keeps pointing the way the point is
    // moving and shrink when it turns (the "gains" of the reference implementation).
    for (size_t k = 0; k < y.size(); ++k) {
      const bool turned = (gradient[k] > 0) != (update[k] > 0);
      gains[k] = std::max(0.01, turned ? gains[k] + 0.2 : gains[k] * 0.8);
      update[k] = momentum * update[k] - options.learning_rate * gains[k] * gradient[k];
      y[k] += update[k];
    }
    // KL is invariant to translation; keeping the centre at the origin stops drift.
    double cx = 0, cy = 0;
    for (int i = 0; i < n; ++i) cx += y[2 * i], cy += y[2 * i + 1];
    for (int i = 0; i < n; ++i) y[2 * i] -= cx / n, y[2 * i + 1] -= cy / n;
  }
  TsneResult result;
  result.kl_divergence = kl_divergence(p, y, n);
  result.embedding = std::move(y);
  return result;
}

}  // namespace vaegail::eval
