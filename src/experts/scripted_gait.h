// A scripted controller for any MJCF body whose actuators are motors on hinge joints: each
// actuated joint tracks a periodic target by PD control, and a style sets the targets. It makes
// demonstrations of diverse behaviours on a body that has no expert (`vaegail env rollout
// --policy gait --styles K`, docs/own_body.md), the style index being the episode's context.
//
// Style k, at time t since the episode's reset, for the joint of actuator j:
//   target_j = offset_j + amplitude_j * sin(2 pi frequency t + phase_j)               (rad)
//   u_j      = kp (target_j - q_j) - kd qdot_j                                       (control units)
//   u_j     += pitch_kp (pitch - lean) + pitch_kd pitch_rate      balance joints only
//   ctrl_j   = u_j clipped to the actuator's ctrlrange ([-1, 1] when it has none)
// pitch is the angle of the root's pitch hinge (a hinge about y on the first body with joints,
// the hopper's `rooty`); the balance joints are the actuated hinges about y of that body's
// children (the hopper's hip). A hip torque turns the torso the other way while the foot is on
// the ground, so pitch_kp > 0 pushes a torso that leans past `lean` back. A body without such
// a root gets no balance term.
//
// Where styles come from (gait_styles()):
//   * the MJCF's <custom> entries, in model order, when it has any:
//       <numeric name="vaegail_gait_style_NAME"
//                data="FREQUENCY KP KD PITCH_KP PITCH_KD LEAN  AMPLITUDE_0 OFFSET_0 PHASE_0  AMPLITUDE_1 ..."/>
//     (one amplitude, offset, phase triple per actuator, in actuator order);
//   * otherwise K styles drawn from a seed within the ranges of GaitKnobs, with GaitStyle's
//     default gains and no balance term.
// The controller is a pure function of the style, the time and the state: the same seed of the
// episode's reset gives the same episode, bit for bit.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "data/record.h"
#include "env/mujoco_env.h"

namespace vaegail {

struct GaitStyle {
  std::string name;
  double frequency = 1.0;                        // Hz, shared by every joint
  double kp = 4.0, kd = 0.1;                     // control units per rad, per rad/s
  double pitch_kp = 0, pitch_kd = 0, lean = 0;   // balance feedback (control per rad, per rad/s; rad)
  std::vector<double> amplitude, offset, phase;  // per actuator, in actuator order (rad)
};

// The ranges that styles are drawn from when the MJCF defines none.
struct GaitKnobs {
  double min_frequency = 1.0, max_frequency = 3.0;  // Hz
  // Drawn amplitudes and offsets, as fractions of a joint's half range (1 rad when unlimited);
  // offsets are around the range's centre.
  double min_amplitude = 0.2, max_amplitude = 0.6, max_offset = 0.3;
};

class ScriptedGait {
 public:
  // Throws naming the model and the actuator when an actuator is not a motor (fixed gain, no
  // bias) on a hinge joint, and when a style's per-actuator vectors do not have one entry each.
  ScriptedGait(const mjModel* model, const std::string& model_name, std::vector<GaitStyle> styles);

  // ctrl[nu] for style `style` at `time` seconds after the reset, from qpos[nq] and qvel[nv].
  void control(int style, double time, const double* qpos, const double* qvel, double* ctrl) const;

  const std::vector<GaitStyle>& styles() const { return styles_; }
  // Actuators whose joint gets the balance term (empty without a root pitch hinge).
  const std::vector<int>& balance_actuators() const { return balance_; }

 private:
  std::vector<GaitStyle> styles_;
  std::vector<int> qpos_, qvel_;          // per actuator: its joint's qpos and qvel address
  std::vector<double> low_, high_;        // per actuator: its ctrlrange
  std::vector<int> balance_;              // actuators with the balance term
  int pitch_qpos_ = -1, pitch_qvel_ = -1;  // the root's pitch hinge, -1 when it has none
};

// The MJCF's styles (first `count` of them), or `count` styles drawn from `seed` when it has
// none. Throws (one line) when count < 1, or when the MJCF defines fewer than `count`.
std::vector<GaitStyle> gait_styles(const mjModel* model, const std::string& model_name, int count,
                                   std::uint64_t seed, const GaitKnobs& knobs = {});

// The controller as a batch policy: episode e plays style style_of_episode[e] from its reset.
// Throws (one line) when the environment's observation is not qpos then qvel (the generic MJCF
// task's layout, the state the controller reads).
BatchPolicy scripted_gait_policy(std::shared_ptr<const ScriptedGait> gait, const MujocoEnv& env,
                                 std::vector<int> style_of_episode);

}  // namespace vaegail
