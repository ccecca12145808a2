// The 62-DoF CMU humanoid task (models/humanoid_cmu.xml; the paper's section 4.3): a free root
// and 56 hinges, 56 torque motors, control step 0.03 s, 334-step episodes (10 s), every episode
// from the standing rest pose with each hinge's angle and velocity perturbed by up to +- 0.02
// (rad, rad/s; seeded). Context: the movement style, an index (0, 1, ...) for style-conditioned
// experts; nothing reads it yet (the styles and their rewards come with the controllers).
//
// Observation layout (137 floats):
//   0..55     joint angles      the 56 hinges in model order, lfemurrz ... rthumbrx (rad)
//   56..111   joint velocities  same order (rad/s)
//   112       root_height       z of the root (pelvis) origin (m)
//   113..115  up_x, up_y, up_z  the world's up axis in the root frame (up_z: cosine of the tilt)
//   116..118  root_vel_x/y/z    linear velocity of the root origin in the root frame (m/s)
//   119..121  root_angvel_x/y/z angular velocity of the root in the root frame (rad/s)
//   122..136  end effectors     lhand, rhand, lfoot, rfoot, head: x, y, z of the body's origin
//                               (wrist, ankle, top of the neck) relative to the root origin, in
//                               the root frame (m)
// Where the body stands and which way it faces are left out: behaviour does not depend on them.
//
// Features (19): forward_speed (m/s, the centre of mass's velocity along the heading), heading
// (rad, the root's x axis projected on the floor, from world x towards world y), root_height (m),
// fallen, then the observation's 15 end-effector coordinates lhand_x ... head_z, the
// discriminator's subset in the paper ("mostly features pertaining to end-effector positions").
// fallen is 1 when the head is below 0.9 m, the root below 0.55 m, or a geom other than the
// feet and toes touches the floor (contacts as found at the last physics step).
//
// Reward for the expert stage, a neutral placeholder until the styles bring their own:
//   stand * upright * (0.2 + 0.8 * move) - 0.05 * mean(clip(a)^2)
//   stand   = clip((root_height - 0.55) / 0.35, 0, 1)        full credit from 0.9 m
//   upright = (1 + up_z) / 2
//   move    = 1 / (1 + ((forward_speed - target_speed) / 0.5)^2)
// move is sharp at the target yet its tails still pull from a standstill (0.15 at rest for the
// default 1.2 m/s); being up pays on its own, as the walker's does, so that falling early never
// beats trying.
#pragma once

#include <array>

#include "env/mujoco_env.h"

namespace vaegail {

struct HumanoidOptions {
  bool terminate_on_fall = true;
  int episode_length = 334;
  double target_speed = 1.2;  // m/s, an adult's usual walking speed
};

class HumanoidEnv : public MujocoEnv {
 public:
  static constexpr int kHinges = 56;
  static constexpr double kFallHeadHeight = 0.9;
  static constexpr double kFallRootHeight = 0.55;
  static constexpr double kAliveWeight = 0.2;
  // The bodies whose positions the observation and the features carry, in their order.
  static constexpr std::array<const char*, 5> kEndEffectors = {"lhand", "rhand", "lfoot", "rfoot", "head"};

  explicit HumanoidEnv(HumanoidOptions options = {});
  HumanoidEnv(std::shared_ptr<const MujocoModel> model, HumanoidOptions options);

  void observe(float* out) const override;
  void features(double* out) const override;
  std::unique_ptr<Env> clone() const override;

  double root_height() const;
  double heading() const;
  double forward_speed() const;
  // The world's up axis in the root frame.
  std::array<double, 3> up_in_root() const;
  // Position of end effector `k` (kEndEffectors order) relative to the root, in the root frame.
  std::array<double, 3> end_effector(int k) const;
  bool fallen() const;
  // Whether a geom other than the feet and toes touches the floor.
  bool off_feet_contact() const;
  // The reward for a given state and action, for tests and documentation.
  static double task_reward(double forward_speed, double target_speed, double root_height, double up_z,
                            const float* action, int act_dim);

 protected:
  double reward(const float* action) const override;
  bool has_terminated() const override;

 private:
  // Express a world-frame vector in the root frame.
  std::array<double, 3> to_root_frame(const double* world) const;

  HumanoidOptions humanoid_options_;
  int root_ = 0, head_ = 0, floor_ = 0;
  std::array<int, kEndEffectors.size()> end_effectors_{};
  std::array<int, 4> feet_{};  // lfoot, ltoes, rfoot, rtoes: the bodies that may touch the floor
};

}  // namespace vaegail
