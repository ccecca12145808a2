// The paper's arm measurements (section 4.1, Figures 2 and 3).
//
// Reaching imitation: encode a demonstration, roll the VAE policy out from the same home pose,
// and compare where the end effector ends up with where the demonstration's ended up.
//
// Latent interpolation: for two demonstrations with embeddings z_a, z_b, roll out the policy at
// z = (1 - α) z_a + α z_b for α in {0, 0.25, 0.5, 0.75, 1}. With the demonstrations' end
// points d_a, d_b, each reached end point e_α has a coordinate along the segment,
//   s_α = (e_α - d_a) · (d_b - d_a) / |d_b - d_a|²   (0 at d_a, 1 at d_b),
// and a distance from the straight line through d_a and d_b. A pair moves monotonically when
// s_α does not decrease from one α to the next (beyond `monotone_tolerance`, in units of s).
#pragma once

#include <torch/torch.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "vae/imitation.h"

namespace vaegail::eval {

using Point3 = std::array<double, 3>;

// The end effector's path (features grip_x, grip_y, grip_z) over an episode's T+1 states.
std::vector<Point3> grip_path(const Episode& episode, const std::vector<std::string>& feature_names);

struct ReachRow {
  std::string expert_id;
  int64_t episode = 0;
  bool held_out = false;
  std::vector<Point3> demo_path, imitation_path;
  double final_distance() const;  // |imitation end - demonstration end| (m)
};

// The policy imitates each episode from its start; z [episodes.size(), Z].
std::vector<ReachRow> imitate_reaches(const Env& prototype, const DemoSet& demos, const std::vector<int64_t>& episodes,
                                      const torch::Tensor& z, const vae::LatentPolicy& policy,
                                      const vae::ImitationOptions& options = {}, Progress* progress = nullptr);

struct DistanceSummary {
  int n = 0;
  double mean = 0, median = 0, p90 = 0;
};
// p90 by linear interpolation between order statistics.
DistanceSummary summarize_distances(std::vector<double> distances);

struct InterpolationPair {
  int64_t episode_a = 0, episode_b = 0;
  Point3 demo_end_a{}, demo_end_b{};
  std::vector<double> alphas;
  std::vector<Point3> ends;                 // e_α, one per alpha
  std::vector<std::vector<Point3>> paths;   // the rollouts, one per alpha
  std::vector<double> along;                // s_α
  std::vector<double> off_line;             // distance of e_α from the line (m)
  bool monotone(double tolerance) const;
  double segment_length() const;  // |d_b - d_a| (m)
};

// Monotone pairs among those whose segment is at least `edges[i-1]` and shorter than `edges[i]`
// (m, ascending; the first bin starts at 0, the last has no end): (monotone, total) per bin.
// A short segment is the hard case: its α steps are a few centimetres, the size of the
// imitation error itself.
std::vector<std::pair<int, int>> monotone_by_segment_length(const std::vector<InterpolationPair>& pairs,
                                                            double tolerance, const std::vector<double>& edges);

// s and the distance from the line through a and b, for point p (a != b).
std::pair<double, double> segment_coordinates(const Point3& a, const Point3& b, const Point3& p);

// A policy whose latent is the joint command itself and holds it: with z a demonstration's final
// command, interpolating z blends poses in joint space (the reference `eval arm --joint-blend`).
const vae::LatentPolicy kHoldZAsCommand = [](const torch::Tensor&, const torch::Tensor& z) { return z.clone(); };

// Every pair (episodes[i], episodes[j]) listed in `pairs`, rolled out at every alpha.
std::vector<InterpolationPair> interpolate_reaches(const Env& prototype, const DemoSet& demos,
                                                   const std::vector<std::pair<int64_t, int64_t>>& pairs,
                                                   const torch::Tensor& z_a, const torch::Tensor& z_b,
                                                   const std::vector<double>& alphas,
                                                   const vae::LatentPolicy& policy,
                                                   const vae::ImitationOptions& options = {});

// CSVs: one row per reach (expert, episode, held_out, demo end, imitation end, distance) and
// one per (pair, alpha).
std::string reach_rows_csv(const std::vector<ReachRow>& rows);
std::string interpolation_csv(const std::vector<InterpolationPair>& pairs);

// The figures' data, for scripts/plot/paths.py (columns path, group, label, style, x, y; the grip
// seen from above). Figure 2: demonstration (solid) and imitation (dashed) paths, the two of a
// row in one group (colour). Figure 3's counterpart: a pair's demonstrations (solid, groups 0 and
// 1) and its rollouts for every alpha (dashed, group α), for the viridis colour map.
std::string reach_paths_csv(const std::vector<ReachRow>& rows);
std::string interpolation_paths_csv(const InterpolationPair& pair, const DemoSet& demos);

}  // namespace vaegail::eval
