// The reaching task (models/arm.xml, the paper's Jaco experiment): 9 DoF (6 arm joints, 3
// fingers), 9 position servos, control step 0.05 s, 50-step episodes (2.5 s), every episode from the
// same home configuration (qpos = qvel = 0; the seed does not move it). Context: the target
// position (x, y, z) in metres, in the table-top workspace. Actions are joint-angle commands
// (rad) to position servos, bounded by the joint ranges.
//
// Observation layout (21 floats):
//   0..8    joint angles    arm_1..arm_6, finger_1..finger_3 (rad)
//   9..17   joint velocities, same order (rad/s)
//   18..20  grip position   the end effector (site "grip") in the world frame (m)
// The target is not observed: each expert reaches its own fixed target, and the VAE infers the
// goal from the demonstrated trajectory.
//
// Features: grip_x, grip_y, grip_z (m), target_distance (m, grip to target).
//
// Reward for the expert stage, at most 1:
//   0.5 * max(0, 1 - d / 1 m) + 0.5 * exp(-(d / 0.05)^2) - command_cost * mean_j (u_j - q_j)^2
//     - posture_cost * mean_j q_j^2
// The linear term pulls from anywhere in the workspace (no target is 1 m from the home grip),
// the sharp one pays for being on the target and staying there (every step counts). The last
// term charges each joint command u_j for its distance from the angle q_j the joint had when
// it was commanded: without it DDPG's actors swing their commands from step to step and settle
// by alternating around the target, so a demonstration's action is nearly noise given its state
// and a VAE cannot learn it. It pays nothing at rest (no bias on the reached pose beyond the
// servos' sag under gravity), and it depends only on the state and the action. The optional
// posture term (0 by default) charges the pose's distance from home: six arm joints place the
// grip in three dimensions, so without it each expert settles on its own arbitrary pose, and two
// experts with nearby targets can stand in poses far apart.
#pragma once

#include <array>

#include "env/mujoco_env.h"

namespace vaegail {

// Euclidean distance between two points of the workspace (m).
double point_distance(const std::array<double, 3>& a, const std::array<double, 3>& b);

struct ArmOptions {
  int episode_length = 50;
  double command_cost = 0.1;  // per rad^2 of mean squared command-minus-angle
  double posture_cost = 0.0;  // per rad^2 of mean squared joint angle
};

class ArmEnv : public MujocoEnv {
 public:
  static constexpr int kJoints = 9;
  // The workspace targets are drawn from (axis-aligned box on the table, in front of the base).
  static constexpr std::array<double, 3> kTargetLow = {0.25, -0.4, 0.05};
  static constexpr std::array<double, 3> kTargetHigh = {0.65, 0.4, 0.45};

  explicit ArmEnv(ArmOptions options = {});
  ArmEnv(std::shared_ptr<const MujocoModel> model, ArmOptions options);

  void observe(float* out) const override;
  void features(double* out) const override;
  std::unique_ptr<Env> clone() const override;

  std::array<double, 3> grip_position() const;
  double target_distance() const;
  // A target drawn uniformly from the workspace box.
  static std::vector<double> random_target(Rng& rng);
  static double task_reward(double target_distance);
  // mean_j (u_j - q_j)^2 of the last step's applied commands u against the angles q it began at.
  double command_jump() const;
  // posture_cost * mean_j q_j^2 of the current pose: what the reward charges for standing away from home.
  double posture_charge() const;
  StepOutcome step(const float* action) override;

 protected:
  void initialize_episode(Rng& rng) override;
  double reward(const float* action) const override;

 private:
  ArmOptions arm_options_;
  int grip_ = 0;
  std::array<double, kJoints> angles_at_command_{};
};

}  // namespace vaegail
