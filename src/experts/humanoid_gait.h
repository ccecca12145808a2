// The humanoid's gait signature: per-episode statistics of the recorded features that tell its
// movement styles apart (docs/humanoid_controllers.md), and a nearest-centroid classifier on
// them (the test that the styles are distinct).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "data/demos.h"

namespace vaegail {

// The signature's statistics, in order; each over the states the actions reached (steps 1..T).
//   forward_speed  mean forward speed (m/s)
//   turn_rate      mean |heading change| per second (rad/s), the heading unwrapped
//   root_height    mean pelvis height (m)
//   head_forward   mean head x from the pelvis (m)
//   hand_height    mean of the two hands' z from the pelvis (m)
//   hand_spread    mean of the two hands' |y| (m)
//   foot_spread    mean of the two feet's |y| (m)
//   arm_swing      standard deviation of lhand_x (m): the fore-and-aft swing of the arm
inline constexpr std::array<const char*, 8> kGaitStatistics = {
    "forward_speed", "turn_rate", "root_height", "head_forward", "hand_height", "hand_spread", "foot_spread",
    "arm_swing"};
using GaitSignature = std::array<double, kGaitStatistics.size()>;

// feature_names: the humanoid's (HumanoidEnv::feature_names()); dt: its control step. Over the
// states after control step `from` (from+1..T; 0: the whole episode). Throws naming a missing
// feature, or for an episode without steps after `from`.
GaitSignature gait_signature(const Episode& episode, const std::vector<std::string>& feature_names, double dt,
                             int from = 0);

// Nearest centroid on statistics standardised by their spread over the fitted rows.
class NearestCentroid {
 public:
  void fit(const std::vector<GaitSignature>& rows, const std::vector<int>& labels);
  int predict(const GaitSignature& row) const;

 private:
  GaitSignature mean_{}, scale_{};
  std::map<int, GaitSignature> centroids_;  // standardised
};

// The styles of a demonstration file: its expert ids ("train/walk"; the gait controllers' styles)
// in order of appearance, and each episode's index into them.
struct StyleLabels {
  std::vector<std::string> names;
  std::vector<int> of_episode;
};
StyleLabels style_labels(const DemoSet& demos);

// Names the style of an episode's stretch after control step `from`: a NearestCentroid fitted on
// the signatures of the same stretch of the file's own demonstrations (those longer than `from`),
// so that a stretch is compared with the demonstrations' gait over the same time of the episode,
// not with their start from standing. Throws when no demonstration is longer than `from`.
class StyleClassifier {
 public:
  StyleClassifier(const DemoSet& demos, double dt, int from = 0);
  // The style of a signature of such a stretch (one of the file's expert ids).
  std::string name(const GaitSignature& signature) const;
  int from() const { return from_; }

 private:
  StyleLabels labels_;
  NearestCentroid classifier_;
  int from_ = 0;
};

// confusion[true label][predicted label] = count.
using Confusion = std::map<int, std::map<int, int>>;
double accuracy(const Confusion& confusion);

// Fits on the even-numbered episodes of each label (in file order) and names the odd ones: the
// issue's "fit on half, name the other half". labels[e] is episode e's style.
Confusion split_half_confusion(const std::vector<GaitSignature>& rows, const std::vector<int>& labels);

}  // namespace vaegail
