// One humanoid episode walked by the gait controller, and what it measured: the function the
// tuner scores and `experts eval --styles` aggregates. The controller acts at every physics step
// through MujocoEnv::step_controlled; random pushes on the pelvis (xfrc_applied) test it.
#pragma once

#include <cstdint>
#include <functional>

#include "env/humanoid.h"
#include "experts/gait_parameters.h"
#include "experts/humanoid_gait.h"

namespace vaegail {

struct GaitEpisodeOptions {
  std::uint64_t seed = 0;      // the environment's reset seed; the pushes are drawn from it too
  int steps = 0;               // control steps; 0: the environment's episode length (334 = 10 s)
  int pushes = 0;              // pushes on the pelvis, each at a uniform time in [push_earliest, push_latest]
                               //   s and a uniform horizontal direction
  double push_force = 200.0;   // N
  double push_duration = 0.1;  // s
  double push_earliest = 2.0, push_latest = 8.0;  // s
  // Std of Gaussian noise added to every motor's ctrl (in the action box's units), one draw per
  // control step held over it, from the seed's own stream: the execution noise of DART (Laskey et
  // al. 2017), which takes the demonstrator off its own path so that its demonstrations show how
  // it comes back. The label leaves pushes out. 0: none.
  double action_noise = 0;
  // DAgger (Ross et al. 2011): at each control step, with probability learner_share (drawn from
  // the seed's own stream), `learner` acts instead: its action from the step's first observation,
  // held over the step as a policy's is, while the controller still runs beneath it so that its
  // state machine follows the walk. Each step then records the clean label as under action_noise:
  // the controller's answer to the states a learner visits. Empty or 0: the controller acts.
  std::function<void(const float* observation, float* action)> learner;
  double learner_share = 0;
};

// Means are over the control steps after the first second (the start's transient left out)
// unless said otherwise; step statistics over the footholds after the first second.
struct GaitEpisodeResult {
  int control_steps = 0;           // control steps taken
  double time_up = 0;              // s: until the fall, or the whole episode
  bool fallen = false;             // HumanoidEnv::fallen() ended it
  double distance = 0;             // m: the COM's displacement along `heading` (the wander's centre)
  double lateral_drift = 0;        // m: its displacement across `heading`, + to the left
  double speed = 0;                // m/s: mean forward COM speed (HumanoidEnv::forward_speed)
  double heading_error = 0;        // rad: mean |root heading - commanded heading|
  double final_heading_error = 0;  // rad: the same at the last step
  int steps = 0;                   // foot swaps, the whole episode
  double step_length = 0;          // m: mean distance between successive footholds along the heading
  double step_width = 0;           // m: mean |distance| across it
  double cadence = 0;              // steps per minute
  double pelvis_height = 0;        // m: mean root height
  StyleTerms style{};              // mean HumanoidEnv::style_measures()
  GaitSignature signature{};       // gait_signature of the episode's features (all steps)
  double effort = 0;               // mean over steps and motors of the recorded action squared
  double wall_seconds = 0;         // s spent simulating and controlling
};

// Called once after the reset (mean_action and outcome null), then after each control step with
// the step's mean action (float[56]) and outcome: what a recorder of the episode needs. Under
// action_noise or a learner the action is the clean label instead: the mean ctrl the controller, noise-free,
// would apply over the step from the state the step started in (MujocoEnv::lookahead_controlled).
using GaitStepObserver =
    std::function<void(const HumanoidEnv& env, const float* mean_action, const StepOutcome* outcome)>;

// Resets `env` with options.seed and walks it with `parameters` until it falls or the steps run
// out (the environment's own time limit and termination are not used: it may run longer).
GaitEpisodeResult run_gait_episode(HumanoidEnv& env, const GaitParameters& parameters, const GaitEpisodeOptions& options,
                                   const GaitStepObserver& observer = {});

// The held-mean replay figure: the episode of `options` (no pushes) is recorded, then its mean
// actions are replayed from the same start through step(), each held for its control step.
// Returns the control steps until the root is more than `tolerance` m from where the controller
// took it (a fall counts as leaving), or the recorded episode's length if it never is.
int held_mean_replay_steps(HumanoidEnv& env, const GaitParameters& parameters, const GaitEpisodeOptions& options,
                           double tolerance = 0.1);

}  // namespace vaegail
