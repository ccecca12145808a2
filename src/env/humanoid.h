// The 62-DoF CMU humanoid task (models/humanoid_cmu.xml; the paper's section 4.3): a free root
// and 56 hinges, 56 torque motors, control step 0.03 s, 334-step episodes (10 s), every episode
// from the standing rest pose with each hinge's angle and velocity perturbed by up to +- 0.02
// (rad, rad/s; seeded). Context: `style`, one number, the label of a demonstration's style (the
// gait demonstrations give each episode its style's index within its set: six training styles,
// five evaluation ones). Any non-negative integer is a label; it changes neither the dynamics nor
// the reward, so an imitation runs in its demonstration's context whatever the label. set_context
// refuses a negative, fractional or non-finite label and a context of another size.
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
// Reward, the same for every style label: being upright and moving forward, less the effort,
//   upright * (0.2 + 0.8 * credit(forward_speed, 1.0, 0.5)) - 0.05 * mean(clip(a, -1, 1)^2)
//   upright = (1 + up_z) / 2
//   credit(x, target, s) = 1 / (1 + ((x - target) / s)^2)    1 on target, 1/2 at a miss of s
// about 1 a step walking upright at 1 m/s, 0.36 standing still, 0.18 lying still: being up pays
// at any speed, so that falling early never beats trying, as the walker's does. Simple on
// purpose: the imitation never uses it (diverse GAIL learns from its discriminator and logs this
// as env_return, a sanity figure of whether the imitations stay up and walk), and the styles are
// the gait controllers' (experts/, docs/humanoid_controllers.md); PPO on the task (`experts train
// --task humanoid`) gets a walking reward from it, no style.
#pragma once

#include <array>
#include <vector>

#include "env/mujoco_env.h"

namespace vaegail {

// Measures of a style in the current state: averaged over a gait controller's episode
// (experts/gait_episode.h), they are what its tuner scores a style's targets against.
enum StyleTerm { kForwardSpeed, kSwaySpeed, kTurnRate, kRootHeight, kHeadForward, kHandHeight, kHandSpread,
                 kFootSpread, kStyleTerms };
using StyleTerms = std::array<double, kStyleTerms>;

struct HumanoidOptions {
  bool terminate_on_fall = true;
  int episode_length = 334;
};

class HumanoidEnv : public MujocoEnv {
 public:
  static constexpr int kHinges = 56;
  static constexpr double kFallHeadHeight = 0.9;
  static constexpr double kFallRootHeight = 0.55;
  static constexpr double kAliveWeight = 0.2;  // what being upright pays at any speed
  static constexpr double kTargetSpeed = 1.0;  // m/s: the forward speed the reward pays in full
  static constexpr double kSpeedScale = 0.5;   // m/s: the miss of it at which its credit halves
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
  // The yaw rate of the root (rad/s, about world z).
  double yaw_rate() const;
  // The centre of mass's speed across the heading (m/s, positive towards the body's left).
  double lateral_speed() const;
  StyleTerms style_measures() const;
  void set_context(const std::vector<double>& context) override;
  // Observation 112..136: root height, up vector, root linear and angular velocity and the 15
  // end-effector coordinates; not the joint angles and velocities. The paper's discriminator sees
  // "a subset of features ... mostly features pertaining to end-effector positions" (appendix,
  // after Merel et al. 2017). Where the hands, feet and head are relative to the pelvis is what a
  // style looks like; how upright the body is and how fast it moves and turns say whether it
  // walks like the demonstration (the styles differ in speed and turn rate). The 112 joint
  // components pin down the exact pose: a discriminator given them tells the policy's steps
  // from the controller's by small joint details and saturates, leaving a reward that says
  // little about the style.
  std::vector<int> discriminator_observation() const override;
  // The reward (see above) for a forward speed, the pelvis's up_z and an action.
  static double upright_forward_reward(double forward_speed, double up_z, const float* action, int act_dim);

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
