#include "eval/arm_eval.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <stdexcept>

#include "env/arm.h"
#include "vae/demo_dataset.h"

namespace vaegail::eval {

namespace {

void write_point(std::ostringstream& out, const Point3& p) { out << ',' << p[0] << ',' << p[1] << ',' << p[2]; }

const char* kPathsHeader = "path,group,label,style,x,y\n";

// One path's rows in scripts/plot/paths.py's CSV: the grip seen from above.
void write_top_view(std::ostringstream& out, size_t id, const std::string& group, const std::string& label,
                    bool dashed, const std::vector<Point3>& path) {
  for (const auto& p : path)
    out << id << ',' << group << ',' << label << ',' << (dashed ? "dashed" : "solid") << ',' << p[0] << ',' << p[1]
        << '\n';
}

}  // namespace

std::vector<Point3> grip_path(const Episode& episode, const std::vector<std::string>& names) {
  int column[3];
  const char* wanted[3] = {"grip_x", "grip_y", "grip_z"};
  for (int k = 0; k < 3; ++k) {
    const auto it = std::find(names.begin(), names.end(), wanted[k]);
    if (it == names.end()) throw std::invalid_argument(std::string("grip_path: no feature '") + wanted[k] + "'");
    column[k] = static_cast<int>(it - names.begin());
  }
  const size_t n = names.size();
  std::vector<Point3> path;
  for (size_t r = 0; (r + 1) * n <= episode.features.size(); ++r)
    path.push_back({episode.features[r * n + column[0]], episode.features[r * n + column[1]],
                    episode.features[r * n + column[2]]});
  return path;
}

double ReachRow::final_distance() const { return point_distance(demo_path.back(), imitation_path.back()); }

std::vector<ReachRow> imitate_reaches(const Env& prototype, const DemoSet& demos, const std::vector<int64_t>& episodes,
                                      const torch::Tensor& z, const vae::LatentPolicy& policy,
                                      const vae::ImitationOptions& options, Progress* progress) {
  vae::ImitationOptions o = options;
  o.speed_feature.clear();
  const auto outcomes = vae::roll_out_latent_policy(prototype, vae::rollout_starts(demos, episodes), z, policy, o,
                                                    progress);
  std::vector<ReachRow> rows;
  for (size_t i = 0; i < episodes.size(); ++i) {
    const Episode& demo = demos.episodes.at(episodes[i]);
    ReachRow r;
    r.expert_id = demo.expert_id;
    r.episode = episodes[i];
    r.held_out = vae::is_held_out(demo);
    r.demo_path = grip_path(demo, demos.header.feature_names);
    r.imitation_path = grip_path(outcomes[i].episode, prototype.feature_names());
    rows.push_back(std::move(r));
  }
  return rows;
}

DistanceSummary summarize_distances(std::vector<double> d) {
  DistanceSummary s;
  s.n = static_cast<int>(d.size());
  if (d.empty()) return s;
  std::sort(d.begin(), d.end());
  for (double x : d) s.mean += x / d.size();
  s.median = vae::median(d);
  const double rank = 0.9 * (d.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(lo + 1, d.size() - 1);
  s.p90 = d[lo] + (rank - lo) * (d[hi] - d[lo]);
  return s;
}

std::pair<double, double> segment_coordinates(const Point3& a, const Point3& b, const Point3& p) {
  Point3 ab, ap;
  double ab2 = 0, along = 0;
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[k] - a[k];
    ap[k] = p[k] - a[k];
    ab2 += ab[k] * ab[k];
  }
  if (ab2 <= 0) throw std::invalid_argument("segment_coordinates: the two end points coincide");
  for (int k = 0; k < 3; ++k) along += ap[k] * ab[k];
  along /= ab2;
  Point3 foot;
  for (int k = 0; k < 3; ++k) foot[k] = a[k] + along * ab[k];
  return {along, point_distance(foot, p)};
}

double InterpolationPair::segment_length() const { return point_distance(demo_end_a, demo_end_b); }

bool InterpolationPair::monotone(double tolerance) const {
  for (size_t k = 1; k < along.size(); ++k)
    if (along[k] < along[k - 1] - tolerance) return false;
  return true;
}

std::vector<std::pair<int, int>> monotone_by_segment_length(const std::vector<InterpolationPair>& pairs,
                                                            double tolerance, const std::vector<double>& edges) {
  if (!std::is_sorted(edges.begin(), edges.end()))
    throw std::invalid_argument("monotone_by_segment_length: edges must ascend");
  std::vector<std::pair<int, int>> bins(edges.size() + 1);
  for (const auto& p : pairs) {
    auto& bin = bins[std::upper_bound(edges.begin(), edges.end(), p.segment_length()) - edges.begin()];
    bin.first += p.monotone(tolerance);
    bin.second += 1;
  }
  return bins;
}

std::vector<InterpolationPair> interpolate_reaches(const Env& prototype, const DemoSet& demos,
                                                   const std::vector<std::pair<int64_t, int64_t>>& pairs,
                                                   const torch::Tensor& z_a, const torch::Tensor& z_b,
                                                   const std::vector<double>& alphas,
                                                   const vae::LatentPolicy& policy,
                                                   const vae::ImitationOptions& options) {
  const int64_t P = static_cast<int64_t>(pairs.size()), A = static_cast<int64_t>(alphas.size());
  if (z_a.size(0) != P || z_b.size(0) != P) throw std::invalid_argument("interpolate_reaches: one z_a, z_b per pair");
  // Every (pair, alpha) in one batch of rollouts, each from pair's first demonstration's start.
  std::vector<int64_t> starts;
  std::vector<torch::Tensor> z;
  for (int64_t p = 0; p < P; ++p)
    for (double alpha : alphas) {
      starts.push_back(pairs[p].first);
      z.push_back((1.0 - alpha) * z_a[p] + alpha * z_b[p]);
    }
  const auto rows = imitate_reaches(prototype, demos, starts, torch::stack(z), policy, options);
  std::vector<InterpolationPair> out;
  for (int64_t p = 0; p < P; ++p) {
    InterpolationPair r;
    r.episode_a = pairs[p].first;
    r.episode_b = pairs[p].second;
    r.demo_end_a = grip_path(demos.episodes.at(r.episode_a), demos.header.feature_names).back();
    r.demo_end_b = grip_path(demos.episodes.at(r.episode_b), demos.header.feature_names).back();
    r.alphas = alphas;
    for (int64_t k = 0; k < A; ++k) {
      const auto& path = rows[p * A + k].imitation_path;
      r.paths.push_back(path);
      r.ends.push_back(path.back());
      const auto [along, off] = segment_coordinates(r.demo_end_a, r.demo_end_b, path.back());
      r.along.push_back(along);
      r.off_line.push_back(off);
    }
    out.push_back(std::move(r));
  }
  return out;
}

std::string reach_rows_csv(const std::vector<ReachRow>& rows) {
  std::ostringstream out;
  out << "expert_id,episode,held_out,demo_end_x,demo_end_y,demo_end_z,imitation_end_x,imitation_end_y,"
         "imitation_end_z,final_distance\n";
  for (const auto& r : rows) {
    out << r.expert_id << ',' << r.episode << ',' << (r.held_out ? 1 : 0);
    write_point(out, r.demo_path.back());
    write_point(out, r.imitation_path.back());
    out << ',' << r.final_distance() << '\n';
  }
  return out.str();
}

std::string interpolation_csv(const std::vector<InterpolationPair>& pairs) {
  std::ostringstream out;
  out << "pair,episode_a,episode_b,alpha,end_x,end_y,end_z,along,off_line,segment_length\n";
  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto& r = pairs[p];
    for (size_t k = 0; k < r.alphas.size(); ++k) {
      out << p << ',' << r.episode_a << ',' << r.episode_b << ',' << r.alphas[k];
      write_point(out, r.ends[k]);
      out << ',' << r.along[k] << ',' << r.off_line[k] << ',' << r.segment_length() << '\n';
    }
  }
  return out.str();
}

std::string reach_paths_csv(const std::vector<ReachRow>& rows) {
  std::ostringstream out;
  out << kPathsHeader;
  for (size_t i = 0; i < rows.size(); ++i) {
    write_top_view(out, 2 * i, std::to_string(i), i ? "" : "demonstration", false, rows[i].demo_path);
    write_top_view(out, 2 * i + 1, std::to_string(i), i ? "" : "imitation (dashed)", true, rows[i].imitation_path);
  }
  return out.str();
}

std::string interpolation_paths_csv(const InterpolationPair& pair, const DemoSet& demos) {
  std::ostringstream out;
  out << kPathsHeader;
  write_top_view(out, 0, "0", "demonstration a", false, grip_path(demos.episodes.at(pair.episode_a),
                                                                  demos.header.feature_names));
  write_top_view(out, 1, "1", "demonstration b", false, grip_path(demos.episodes.at(pair.episode_b),
                                                                  demos.header.feature_names));
  for (size_t k = 0; k < pair.alphas.size(); ++k) {
    const std::string alpha = fmt::format("{:.2f}", pair.alphas[k]);
    write_top_view(out, k + 2, alpha, "alpha " + alpha, true, pair.paths[k]);
  }
  return out.str();
}

}  // namespace vaegail::eval
