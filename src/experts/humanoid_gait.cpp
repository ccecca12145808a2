#include "experts/humanoid_gait.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vaegail {

namespace {
int column(const std::vector<std::string>& names, const std::string& name) {
  const auto at = std::find(names.begin(), names.end(), name);
  if (at == names.end()) throw std::invalid_argument("gait signature: the episode has no feature '" + name + "'");
  return static_cast<int>(at - names.begin());
}

// The angle from a to b, wrapped into (-pi, pi]: heading is atan2's, so it jumps at +-pi.
double turn(double a, double b) { return std::remainder(b - a, 2 * M_PI); }
}  // namespace

GaitSignature gait_signature(const Episode& episode, const std::vector<std::string>& names, double dt, int from) {
  const int n = static_cast<int>(names.size()), steps = episode.length() - from;
  if (from < 0 || steps < 1)
    throw std::invalid_argument("gait signature: an episode without steps after control step " + std::to_string(from));
  const int speed = column(names, "forward_speed"), heading = column(names, "heading"),
            root = column(names, "root_height"), head_x = column(names, "head_x"), lhand_x = column(names, "lhand_x"),
            lhand_y = column(names, "lhand_y"), lhand_z = column(names, "lhand_z"), rhand_y = column(names, "rhand_y"),
            rhand_z = column(names, "rhand_z"), lfoot_y = column(names, "lfoot_y"), rfoot_y = column(names, "rfoot_y");
  auto at = [&](int t, int f) { return episode.features[static_cast<size_t>(t) * n + f]; };
  GaitSignature sum{};
  double swing_sq = 0;
  for (int t = from + 1; t <= episode.length(); ++t) {
    sum[0] += at(t, speed);
    sum[1] += std::abs(turn(at(t - 1, heading), at(t, heading))) / dt;
    sum[2] += at(t, root);
    sum[3] += at(t, head_x);
    sum[4] += 0.5 * (at(t, lhand_z) + at(t, rhand_z));
    sum[5] += 0.5 * (std::abs(at(t, lhand_y)) + std::abs(at(t, rhand_y)));
    sum[6] += 0.5 * (std::abs(at(t, lfoot_y)) + std::abs(at(t, rfoot_y)));
    sum[7] += at(t, lhand_x);
    swing_sq += at(t, lhand_x) * at(t, lhand_x);
  }
  GaitSignature mean;
  for (size_t k = 0; k < mean.size(); ++k) mean[k] = sum[k] / steps;
  mean[7] = std::sqrt(std::max(0.0, swing_sq / steps - mean[7] * mean[7]));
  return mean;
}

void NearestCentroid::fit(const std::vector<GaitSignature>& rows, const std::vector<int>& labels) {
  if (rows.empty() || rows.size() != labels.size())
    throw std::invalid_argument("nearest centroid: needs as many labels as rows, and at least one");
  for (size_t k = 0; k < mean_.size(); ++k) {
    double s = 0, sq = 0;
    for (const auto& r : rows) {
      s += r[k];
      sq += r[k] * r[k];
    }
    mean_[k] = s / rows.size();
    const double sd = std::sqrt(std::max(0.0, sq / rows.size() - mean_[k] * mean_[k]));
    scale_[k] = sd > 1e-12 ? sd : 1.0;  // a constant statistic tells nothing apart: leave it unscaled
  }
  std::map<int, int> counts;
  centroids_.clear();
  for (size_t i = 0; i < rows.size(); ++i) {
    auto& c = centroids_[labels[i]];
    for (size_t k = 0; k < c.size(); ++k) c[k] += (rows[i][k] - mean_[k]) / scale_[k];
    ++counts[labels[i]];
  }
  for (auto& [label, c] : centroids_)
    for (double& x : c) x /= counts[label];
}

int NearestCentroid::predict(const GaitSignature& row) const {
  if (centroids_.empty()) throw std::logic_error("nearest centroid: predict before fit");
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const auto& [label, c] : centroids_) {
    double d = 0;
    for (size_t k = 0; k < c.size(); ++k) d += std::pow((row[k] - mean_[k]) / scale_[k] - c[k], 2);
    if (d < best_distance) {
      best_distance = d;
      best = label;
    }
  }
  return best;
}

StyleLabels style_labels(const DemoSet& demos) {
  StyleLabels labels;
  for (const auto& e : demos.episodes) {
    const auto known = std::find(labels.names.begin(), labels.names.end(), e.expert_id);
    labels.of_episode.push_back(static_cast<int>(known - labels.names.begin()));
    if (known == labels.names.end()) labels.names.push_back(e.expert_id);
  }
  return labels;
}

StyleClassifier::StyleClassifier(const DemoSet& demos, double dt, int from) : labels_(style_labels(demos)), from_(from) {
  std::vector<GaitSignature> rows;
  std::vector<int> labels;
  for (size_t i = 0; i < demos.episodes.size(); ++i) {
    if (demos.episodes[i].length() <= from) continue;
    rows.push_back(gait_signature(demos.episodes[i], demos.header.feature_names, dt, from));
    labels.push_back(labels_.of_episode[i]);
  }
  if (rows.empty())
    throw std::invalid_argument(demos.path + ": no demonstration runs past control step " + std::to_string(from) +
                                " to name styles by");
  classifier_.fit(rows, labels);
}

std::string StyleClassifier::name(const GaitSignature& signature) const {
  return labels_.names.at(classifier_.predict(signature));
}

double accuracy(const Confusion& confusion) {
  int right = 0, all = 0;
  for (const auto& [truth, row] : confusion)
    for (const auto& [predicted, count] : row) {
      all += count;
      if (predicted == truth) right += count;
    }
  return all ? static_cast<double>(right) / all : 0.0;
}

Confusion split_half_confusion(const std::vector<GaitSignature>& rows, const std::vector<int>& labels) {
  std::map<int, int> seen;
  std::vector<bool> fitted(rows.size());
  std::vector<GaitSignature> fit_rows;
  std::vector<int> fit_labels;
  for (size_t i = 0; i < rows.size(); ++i) {
    fitted[i] = seen[labels[i]]++ % 2 == 0;
    if (!fitted[i]) continue;
    fit_rows.push_back(rows[i]);
    fit_labels.push_back(labels[i]);
  }
  NearestCentroid classifier;
  classifier.fit(fit_rows, fit_labels);
  Confusion confusion;
  for (size_t i = 0; i < rows.size(); ++i)
    if (!fitted[i]) ++confusion[labels[i]][classifier.predict(rows[i])];
  return confusion;
}

}  // namespace vaegail
