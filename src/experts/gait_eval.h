// `vaegail experts eval --task humanoid --styles FILE...`: is a gait controller's style robust
// enough to demonstrate? Per style, N episodes from the reset's perturbed starts without pushes
// (falls, and the gait's measures over them) and the same N starts with random pushes on the
// pelvis (falls), the controller's speed in control steps/s, and optionally the held-mean replay
// figure (gait_episode.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "experts/gait_episode.h"

namespace vaegail {

struct GaitEvalOptions {
  int episodes = 20;          // per style, each run without and with pushes
  std::uint64_t seed = 12345;  // episode e resets with derive_seed(seed, e)
  GaitEpisodeOptions episode;  // steps and pushes (seed ignored; pushes: those of the pushed runs)
  bool replay = false;        // also measure held_mean_replay_steps on each start
  GaitEvalOptions() { episode.pushes = 1; }
};

struct GaitStyleEvaluation {
  std::string name;
  GaitParameters parameters;
  int episodes = 0;
  int falls = 0;         // of the episodes without pushes
  int pushed_falls = 0;  // of the episodes with pushes
  // Means over the episodes without pushes (GaitEpisodeResult's definitions).
  double time_up = 0, speed = 0, step_length = 0, cadence = 0, step_width = 0, pelvis_height = 0;
  double lateral_drift = 0;  // mean |drift| (m)
  double heading_error = 0, effort = 0;
  GaitSignature signature{};
  double control_steps_per_s = 0;  // every episode's control steps over the time they took
  // Bare mj_step of the same model in control steps/s, measured right after the style's episodes
  // so that both rates see the same load (0: not measured).
  double raw_control_steps_per_s = 0;
  // held_mean_replay_steps over the starts (0 when not measured).
  double replay_mean = 0;
  int replay_min = 0, replay_max = 0;
};

// `episode_done` is called after each episode (progress).
GaitStyleEvaluation evaluate_gait_style(const std::string& name, const GaitParameters& parameters,
                                        const GaitEvalOptions& options, const std::function<void()>& episode_done = {});

// The table `experts eval --styles` prints: one row per style, then the signatures, then each
// style's control steps/s against its raw physics figure where that was measured.
std::string format_gait_evaluations(const std::vector<GaitStyleEvaluation>& evaluations);

// One flat row of a style's numbers by column name (the CSV's and the JSON's), signature
// statistics prefixed "signature_".
std::vector<std::pair<std::string, double>> gait_evaluation_row(const GaitStyleEvaluation& evaluation);

}  // namespace vaegail
