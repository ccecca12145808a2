// The humanoid's walking controller (SIMBICON, Yin, Loken & van de Panne 2007, with the swing
// foot placed by IK as in Coros, Beaudoin & van de Panne 2010; cartwheel-3d's SimBiController):
// it sets every motor at every physics step, as a PhysicsStepController of the environment
// (MujocoEnv::step_controlled records the mean ctrl of each control step as the action).
//
// Per physics step, with the legs from the state machine (gait_state_machine.h):
//   swing leg   the ankle on a path to the balance feedback's target (balance_feedback.h,
//               swing_ik.h); the femur's world orientation from the IK held by a PD torque
//               tau_swing, realised by the three hip hinges; knee PD to the IK's angle; foot
//               kept level in the heading frame
//   torso       the pelvis held at (heading, pelvis_pitch, pelvis_roll) in the world by a PD
//               torque tau_torso, which only the stance hip can exert:
//   stance hip  tau = support (the body above it against gravity, virtual_model.h)
//                     - tau_torso - tau_swing                               (SIMBICON)
//   stance knee PD to stance_knee plus the static torque of the body above it; ankle keeps the
//               foot flat plus stance_ankle
//   back        PD to back_pitch, and a lateral bend that leans the thorax back_roll towards the
//               stance side in the world; neck and head PD to straight
//   arms        PD to a pose, optionally swinging with the opposite thigh
// Swing-side joints and the upper body also get qfrc_bias (gravity and Coriolis of what they
// carry); every torque is divided by its motor's gear and clipped to [-1, 1].
#pragma once

#include <vector>

#include "env/mujoco_env.h"
#include "experts/balance_feedback.h"
#include "experts/gait_parameters.h"
#include "experts/gait_skeleton.h"
#include "experts/gait_state_machine.h"
#include "experts/virtual_model.h"

namespace vaegail {

// Where a foot landed: the new stance ankle at a swap.
struct Foothold {
  double time = 0;   // s since the reset
  double x = 0, y = 0;  // world (m)
  int leg = 0;       // 0 left, 1 right
};

class GaitController : public PhysicsStepController {
 public:
  // The skeleton must outlive the controller. One controller per episode: it starts standing on
  // the left leg with the clock at 0.
  GaitController(const GaitSkeleton& skeleton, GaitParameters parameters);

  void control(const mjModel* model, mjData* data) override;

  const GaitParameters& parameters() const { return p_; }
  const GaitStateMachine& state() const { return machine_; }
  const std::vector<Foothold>& footholds() const { return footholds_; }

 private:
  // Joint PD (N m) towards `target`, plus qfrc_bias when `carry` (a joint whose load is its own).
  void pd(const mjData* d, int joint, double target, double kp, double kd, bool carry);
  Vec3 control_swing_leg(const mjModel* m, mjData* d, double heading);
  void control_stance_leg(const mjModel* m, mjData* d, double heading, const Vec3& swing_torque, bool swing_down);
  void control_upper_body(const mjModel* m, const mjData* d, double heading);

  const GaitSkeleton& skeleton_;
  GaitParameters p_;
  GaitStateMachine machine_;
  Vec2 lift_off_{};             // where the swing ankle left the floor (world x, y)
  bool lifted_ = false;         // lift_off_ set for the current step
  double back_roll_target_ = 0;  // the filtered lateral lean (rad)
  std::vector<double> torque_;  // per joint (N m)
  std::vector<Foothold> footholds_;
};

}  // namespace vaegail
