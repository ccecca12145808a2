// Transitions between behaviours (the paper's last experiment, end of section 4.3): for a pair
// of demonstrations (A, B), start from A's initial state conditioned on z_A, blend the
// conditioning linearly to z_B over 20 control steps at mid-episode, run to the episode's end,
// and ask whether the body stayed up and whether what it does after the blend is B's behaviour.
// "Behaviour" is the task's to say (BehaviourJudge): the walker's is its speed; the humanoid's
// its style (experts/humanoid_gait.h's classifier).
#pragma once

#include <torch/torch.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "eval/walker_eval.h"
#include "vae/imitation.h"

namespace vaegail::eval {

// When and how fast the conditioning moves from z_A to z_B. At control step t (actions taken so
// far) the policy sees z_A + alpha(t) (z_B - z_A), with
//   alpha(t) = 0                          t < start
//            = (t - start + 1) / width    start <= t < start + width
//            = 1                          t >= start + width
// so `width` steps each move the conditioning by 1 / width and the last of them reaches z_B.
// Written as z_A plus a step, not (1 - alpha) z_A + alpha z_B, so that z_A == z_B gives z_A bit
// for bit (no transition at all); once alpha is 1 the policy gets z_B itself, not z_A + (z_B - z_A).
struct BlendSchedule {
  int start = 0, width = 20;
  double alpha(int step) const;
  int end() const { return start + width; }  // the first step conditioned on z_B alone
};

// The paper's schedule: starting half-way through an episode of `episode_length` control steps.
BlendSchedule mid_episode_blend(int episode_length, int width = 20);

// z [n, Z] float CPU for rows [n] (long) of pairs whose rollouts have taken steps [n] (long):
// z_from[rows] + alpha(steps) * (z_to[rows] - z_from[rows]), and z_to[rows] where alpha is 1;
// z_from, z_to [P, Z].
torch::Tensor blended_latents(const torch::Tensor& z_from, const torch::Tensor& z_to, const torch::Tensor& rows,
                              const torch::Tensor& steps, const BlendSchedule& blend);

// What a demonstration, or a stretch of a rollout, does.
struct Behaviour {
  std::string label;             // discrete: the walker's target speed ("-1"), the humanoid's style
  double speed = std::nan("");   // mean forward speed (m/s)
};

// A task's notion of behaviour: the hook a body plugs into for `eval transitions`.
struct BehaviourJudge {
  std::string noun;  // what the label is, for tables: "speed", "style"
  std::string rule;  // what `matches` asks, for tables: "the speed is within 0.25 m/s of B's demonstration's"
  std::string speed_feature;  // the feature a behaviour's speed is the mean of: com_speed, forward_speed
  // The demonstration's own behaviour; pairs "of different behaviours" differ in label.
  std::function<Behaviour(const DemoSet& demos, int64_t episode)> of_demonstration;
  // A rollout's over the states reached by its actions from `from_step` on (steps from_step+1..T).
  std::function<Behaviour(const Episode& rollout, int from_step)> of_rollout;
  // Whether a rollout's behaviour is the demonstration's.
  std::function<bool(const Behaviour& rollout, const Behaviour& demonstration)> matches;
};

// The walker's: the label is the demonstration's target speed (its context), the speed the mean
// of the `com_speed` feature; a rollout matches when its speed is within `tolerance` m/s of the
// demonstration's achieved speed (issue 36: 0.25 m/s).
BehaviourJudge walker_speed_judge(const std::vector<std::string>& feature_names, double tolerance = 0.25);

// The humanoid's: the label is the demonstration's style (its expert id, "train/walk"); a
// rollout's is the style that experts/humanoid_gait.h's nearest-centroid classifier names from the
// gait signature of its stretch, the classifier fitted on the same stretch of every demonstration
// of `demos` (their own gait over the same seconds of the episode, not their start from
// standing); a rollout matches when it is named the demonstration's style. The speed is the
// signature's mean forward speed. `feature_names`: the environment's (the rollouts'); dt its
// control step.
BehaviourJudge humanoid_style_judge(const DemoSet& demos, const std::vector<std::string>& feature_names, double dt);

// The judge for the demonstrations' task (by the environment's id): the walker's or the
// humanoid's; throws one line naming the task when it has none.
BehaviourJudge behaviour_judge(const Env& env, const DemoSet& demos, double speed_tolerance = 0.25);

struct TransitionPair {
  int64_t from = 0, to = 0;  // episode indices in the demonstration file
  bool operator==(const TransitionPair& o) const { return from == o.from && to == o.to; }
};

// Every ordered pair (A, B) of distinct episodes of the list, A-major.
std::vector<TransitionPair> all_ordered_pairs(const std::vector<int64_t>& episodes);

// `count` distinct ordered pairs drawn uniformly (util/rng.h, `seed`) among the ordered pairs of
// the episodes whose labels differ, in the order drawn; all of them, shuffled, when fewer.
// labels[i] is episodes[i]'s behaviour label.
std::vector<TransitionPair> sample_pairs(const std::vector<int64_t>& episodes, const std::vector<std::string>& labels,
                                         int count, std::uint64_t seed);

// The pairs plus one (B, B) per distinct B among them, after them: the same measurement without
// a transition, what each policy does when it imitates B from the start.
std::vector<TransitionPair> with_references(std::vector<TransitionPair> pairs);

struct TransitionOptions {
  int blend_width = 20;  // control steps of the blend (the paper: 20)
  // Control steps after the blend's end before the behaviour is measured: the gait has to
  // settle into the new speed (the walker: 40 steps, 1 s, about a stride).
  int settle = 40;
  vae::ImitationOptions rollout;
};

// Each pair rolled out from A's initial state under the blend of `blend` (z_from, z_to [P, Z]).
std::vector<vae::ImitationOutcome> roll_out_transitions(const Env& prototype, const DemoSet& demos,
                                                        const std::vector<TransitionPair>& pairs,
                                                        const torch::Tensor& z_from, const torch::Tensor& z_to,
                                                        const vae::LatentPolicy& policy, const BlendSchedule& blend,
                                                        const vae::ImitationOptions& options = {},
                                                        Progress* progress = nullptr);

struct TransitionRow {
  std::string policy, from_expert, to_expert;
  TransitionPair pair;
  Behaviour from, to;        // the demonstrations'
  bool fell = false;
  int fall_step = -1;        // -1: stayed up to the end
  bool up_at_blend = false;  // had not fallen when the blend began (a transition was tried)
  Behaviour after;           // the rollout's after the blend and the settling (NaN speed: it ended first)
  bool matched = false;      // stayed up to the end and `after` matches `to`
  bool reference() const { return pair.from == pair.to; }
  bool different() const { return from.label != to.label; }
};

// Every policy runs every pair; the mid-episode blend of the prototype's episode length.
// z_from, z_to [pairs.size(), Z]: the embeddings of each pair's A and B.
std::vector<TransitionRow> run_transitions(const Env& prototype, const DemoSet& demos,
                                           const std::vector<TransitionPair>& pairs, const torch::Tensor& z_from,
                                           const torch::Tensor& z_to, const std::vector<NamedPolicy>& policies,
                                           const BehaviourJudge& judge, const TransitionOptions& options = {},
                                           Progress* progress = nullptr);

// One row per pair and policy: policy, from_episode, to_episode, from_expert, to_expert,
// from_behaviour, to_behaviour, from_speed, to_speed, fell, fall_step, speed_after,
// behaviour_after, matched.
std::string transitions_csv(const std::vector<TransitionRow>& rows);

struct TransitionSummary {
  std::string policy, pairs;  // pairs: "different", "same" or "none" (the (B, B) references)
  std::string from_label, to_label;  // set in the summaries by labels
  int n = 0;
  double up_at_blend = 0, stayed_up = 0, matched = 0;  // fractions of n
  // Transitions to a B that the policy matches without a transition (its (B, B) reference
  // matched), and how many of them matched B: the transition's own success, apart from how
  // well the policy imitates B at all. 0 for the references themselves.
  int b_alone = 0, matched_b_alone = 0;
};

// Per policy, one summary per kind of pair present (different behaviours, same behaviour, no
// transition), in that order; with `by_labels`, per policy and (from, to) label of the pairs of
// different behaviours.
std::vector<TransitionSummary> summarize_transitions(const std::vector<TransitionRow>& rows, bool by_labels = false);
// A Markdown table of the summaries (pairs, up when the blend began, stayed up to the end,
// matched B, matched B where B alone is matched); `noun` names the behaviour ("speed").
std::string transition_table(const std::vector<TransitionSummary>& summaries, const std::string& noun);

}  // namespace vaegail::eval
