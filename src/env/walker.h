// The planar walker task (models/walker.xml): 9 DoF, 6 motors, control step 0.025 s,
// 400-step episodes (10 s). Context: the target speed in m/s (the paper's -1, 0, 1, 3).
//
// Observation layout (18 floats):
//   0      torso_height       z of the torso centre (m)
//   1, 2   torso_pitch_sin/cos orientation of the torso in the sagittal plane
//   3..8   joint angles        right_hip, right_knee, right_ankle, left_hip, left_knee, left_ankle (rad)
//   9..11  root velocities     rootx (m/s), rootz (m/s), rooty (pitch rate, rad/s)
//   12..17 joint velocities    same order as the angles (rad/s)
// The horizontal position is left out: behaviour does not depend on where the walker is.
//
// Features: com_speed (forward velocity of the centre of mass, m/s), torso_height (m),
// fallen (1 when the torso centre is below 0.7 m or pitched more than ~57 degrees).
//
// Reward for the expert stage, in [-0.05, 1]:
//   stand * upright * (0.2 + 0.8 * move) - 0.05 * mean(clip(a)^2)
//   stand   = clip((torso_height - 0.8) / 0.4, 0, 1)        full credit from 1.2 m
//   upright = (1 + cos pitch) / 2
//   move    = 0.6 * max(0, 1 - dv / max(1, |target|)) + 0.4 * exp(-2 dv^2), dv = |com_speed - target|
// The broad (linear) term keeps a gradient towards any target; the narrow one rewards precision
// (experts must average within 0.3 m/s). The control cost favours smooth, economical gaits.
// WalkerOptions::posture_cost adds - posture_cost * mean_j q_j^2 over the six joint angles (0 by
// default: the published experts' reward has no such term).
#pragma once

#include "env/mujoco_env.h"

namespace vaegail {

struct WalkerOptions {
  bool terminate_on_fall = true;
  int episode_length = 400;
  // Per rad^2 of mean squared joint angle: charging the distance from the straight-legged pose
  // narrows the gaits that experts of one speed settle on (the walker's counterpart of the arm's).
  double posture_cost = 0.0;
};

class WalkerEnv : public MujocoEnv {
 public:
  static constexpr double kFallHeight = 0.7;
  static constexpr double kFallCosPitch = 0.54;

  explicit WalkerEnv(WalkerOptions options = {});
  WalkerEnv(std::shared_ptr<const MujocoModel> model, WalkerOptions options);

  void observe(float* out) const override;
  void features(double* out) const override;
  std::unique_ptr<Env> clone() const override;

  double torso_height() const;
  double torso_pitch() const;
  double com_speed() const;
  bool fallen() const;
  // posture_cost * mean_j q_j^2 of the current pose: what the reward charges for bending the legs.
  double posture_charge() const;
  static constexpr double kAliveWeight = 0.2;
  // The reward for a given forward speed, posture and action, for tests and documentation.
  static double task_reward(double com_speed, double target_speed, double torso_height,
                            double pitch, const float* action, int act_dim);

 protected:
  void initialize_episode(Rng& rng) override;
  double reward(const float* action) const override;
  bool has_terminated() const override;

 private:
  WalkerOptions walker_options_;
  int torso_ = 0;
};

}  // namespace vaegail
