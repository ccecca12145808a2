#include "experts/gait_controller.h"

#include <algorithm>
#include <cmath>

#include "experts/swing_ik.h"

namespace vaegail {

namespace {
// A body's pitch about the heading's lateral axis (+ when its z axis leans forward) and its roll
// about the forward axis (+ when its y axis, its left side, rises), from its world orientation.
double pitch_in_heading(const double* xmat, double heading) {
  return std::atan2(std::cos(heading) * xmat[2] + std::sin(heading) * xmat[5], xmat[8]);
}
double body_roll(const double* xmat) { return std::atan2(xmat[7], xmat[8]); }
const double* joint_world_axis(const mjData* d, int joint) { return d->xaxis + 3 * joint; }
// The angular part of a body's velocity (world frame).
const double* body_angular_velocity(const mjData* d, int body) { return d->cvel + 6 * body; }
}  // namespace

GaitController::GaitController(const GaitSkeleton& skeleton, GaitParameters parameters)
    : skeleton_(skeleton), p_(parameters), torque_(skeleton.model->njnt, 0.0) {}

void GaitController::pd(const mjData* d, int joint, double target, double kp, double kd, bool carry) {
  const mjModel* m = skeleton_.model;
  const int dof = m->jnt_dofadr[joint];
  torque_[joint] = kp * (target - d->qpos[m->jnt_qposadr[joint]]) - kd * d->qvel[dof] + (carry ? d->qfrc_bias[dof] : 0.0);
}

void GaitController::control(const mjModel* m, mjData* d) {
  const bool swapped = machine_.advance(m->opt.timestep, skeleton_.foot_on_floor(d, machine_.swing()),
                                        p_.step_min_time, p_.step_max_time);
  if (swapped) {
    const double* ankle = d->xpos + 3 * skeleton_.legs[machine_.stance()].foot;
    footholds_.push_back({d->time, ankle[0], ankle[1], machine_.stance()});
  }
  if (swapped || !lifted_) {
    const double* ankle = d->xpos + 3 * skeleton_.legs[machine_.swing()].foot;
    lift_off_ = {ankle[0], ankle[1]};
    lifted_ = true;
  }
  const double heading = commanded_heading(p_, d->time);
  const Vec3 swing_torque = control_swing_leg(m, d, heading);
  control_stance_leg(m, d, heading, swing_torque, skeleton_.foot_on_floor(d, machine_.swing()));
  control_upper_body(m, d, heading);
  for (int j = 0; j < m->njnt; ++j)
    if (skeleton_.motor[j] >= 0) d->ctrl[skeleton_.motor[j]] = std::clamp(torque_[j] / skeleton_.gear[j], -1.0, 1.0);
}

Vec3 GaitController::control_swing_leg(const mjModel* m, mjData* d, double heading) {
  const GaitLeg& swing = skeleton_.legs[machine_.swing()];
  const GaitLeg& stance = skeleton_.legs[machine_.stance()];
  const double side = GaitStateMachine::side_sign(machine_.swing());
  mj_subtreeVel(m, d);
  const double* com = d->subtree_com + 3 * skeleton_.root;
  const double* com_velocity = d->subtree_linvel + 3 * skeleton_.root;
  const double* stance_ankle = d->xpos + 3 * stance.foot;
  const Vec2 target = foot_placement(p_, {stance_ankle[0], stance_ankle[1]}, {com[0], com[1]},
                                     {com_velocity[0], com_velocity[1]}, heading, side);
  const double phase = machine_.time_in_step() / p_.step_min_time;
  const Vec3 ankle = swing_ankle_path(p_, lift_off_, target, phase, skeleton_.ankle_height);
  const double knee_direction = heading + side * p_.toe_out;
  const double* hip = d->xanchor + 3 * swing.hip_rx;
  const LegPose pose = two_link_ik({hip[0], hip[1], hip[2]}, ankle, {std::cos(knee_direction), std::sin(knee_direction), 0},
                                   skeleton_.thigh, skeleton_.shank);

  const Vec3 swing_torque = orientation_pd(pose.femur, d->xmat + 9 * swing.femur, body_angular_velocity(d, swing.femur),
                                           p_.kp_swing_hip, p_.kd_swing_hip);
  const Vec3 hips = hinge_torques(joint_world_axis(d, swing.hip_rz), joint_world_axis(d, swing.hip_ry), joint_world_axis(d, swing.hip_rx),
                                  swing_torque);
  const int hip_joints[3] = {swing.hip_rz, swing.hip_ry, swing.hip_rx};
  for (int k = 0; k < 3; ++k) torque_[hip_joints[k]] = hips[k] + d->qfrc_bias[m->jnt_dofadr[hip_joints[k]]];

  pd(d, swing.knee, pose.knee, p_.kp_knee, p_.kd_knee, true);
  const double* tibia = d->xmat + 9 * swing.tibia;
  const double foot_pitch = phase < 1 ? p_.swing_ankle : p_.swing_ankle_late;
  pd(d, swing.ankle_rx, foot_pitch - pitch_in_heading(tibia, heading), p_.kp_ankle, p_.kd_ankle, true);
  pd(d, swing.ankle_rz, -body_roll(tibia), p_.kp_ankle, p_.kd_ankle, true);
  pd(d, swing.toe, 0, 4 * p_.kp_distal, 4 * p_.kd_distal, true);
  return swing_torque;
}

void GaitController::control_stance_leg(const mjModel* m, mjData* d, double heading, const Vec3& swing_torque,
                                        bool swing_down) {
  const GaitLeg& stance = skeleton_.legs[machine_.stance()];
  const double side = GaitStateMachine::side_sign(machine_.stance());
  // Right after a swap the old stance foot still carries part of the body.
  const double share = swing_down ? std::clamp(0.5 + 0.5 * machine_.time_in_step() / p_.support_ramp, 0.5, 1.0) : 1.0;
  const Mat3 pelvis_target =
      multiply(rotation_z(heading), multiply(rotation_y(p_.pelvis_pitch), rotation_x(-side * p_.pelvis_roll)));
  const Vec3 torso_torque = orientation_pd(pelvis_target, d->xmat + 9 * skeleton_.root,
                                           body_angular_velocity(d, skeleton_.root), p_.kp_torso, p_.kd_torso);
  const Vec3 support = support_torque(m, d, skeleton_.root, stance.femur, d->xanchor + 3 * stance.hip_rx);
  Vec3 hip_torque;
  for (int k = 0; k < 3; ++k) hip_torque[k] = share * p_.hip_support * support[k] - torso_torque[k] - swing_torque[k];
  const Vec3 hips = hinge_torques(joint_world_axis(d, stance.hip_rz), joint_world_axis(d, stance.hip_ry), joint_world_axis(d, stance.hip_rx),
                                  hip_torque);
  torque_[stance.hip_rz] = hips[0];
  torque_[stance.hip_ry] = hips[1];
  torque_[stance.hip_rx] = hips[2];

  pd(d, stance.knee, p_.stance_knee, p_.kp_knee, p_.kd_knee, false);
  const Vec3 above_knee = support_torque(m, d, skeleton_.root, stance.tibia, d->xanchor + 3 * stance.knee);
  torque_[stance.knee] += share * p_.knee_support * mju_dot3(joint_world_axis(d, stance.knee), above_knee.data());

  const double* tibia = d->xmat + 9 * stance.tibia;
  pd(d, stance.ankle_rx, p_.stance_ankle - pitch_in_heading(tibia, heading), p_.kp_ankle, p_.kd_ankle, false);
  pd(d, stance.ankle_rz, -body_roll(tibia), p_.kp_ankle, p_.kd_ankle, false);
  const Vec3 above_ankle = support_torque(m, d, skeleton_.root, stance.foot, d->xanchor + 3 * stance.ankle_rx);
  for (int joint : {stance.ankle_rx, stance.ankle_rz})
    torque_[joint] += share * p_.ankle_support * mju_dot3(joint_world_axis(d, joint), above_ankle.data());
  pd(d, stance.toe, 0, 4 * p_.kp_distal, 4 * p_.kd_distal, false);
}

void GaitController::control_upper_body(const mjModel* m, const mjData* d, double heading) {
  const double stance_side = GaitStateMachine::side_sign(machine_.stance());
  // The lateral lean's target is filtered: it flips sides at every swap.
  back_roll_target_ += (-stance_side * p_.back_roll - back_roll_target_) * std::min(1.0, m->opt.timestep / p_.back_roll_filter);
  // The back bends so that the thorax, on the rolling pelvis, leans as wanted in the world.
  const double bend = std::clamp(back_roll_target_ - body_roll(d->xmat + 9 * skeleton_.root), -0.5, 0.5);
  for (const auto& [flexion, lateral, twist] : skeleton_.back) {
    pd(d, flexion, p_.back_pitch / 3, p_.kp_back, p_.kd_back, true);
    pd(d, lateral, bend / 3, p_.kp_back, p_.kd_back, true);
    pd(d, twist, 0, p_.kp_back, p_.kd_back, true);
  }
  for (int joint : skeleton_.neck) pd(d, joint, 0, p_.kp_neck, p_.kd_neck, true);
  for (int s = 0; s < 2; ++s) {
    const GaitArm& arm = skeleton_.arms[s];
    const double outward = GaitStateMachine::side_sign(s);
    // Arms swing with the opposite thigh: forward as it goes back.
    const double opposite_thigh = -pitch_in_heading(d->xmat + 9 * skeleton_.legs[1 - s].femur, heading);
    pd(d, arm.clavicle_rz, 0, p_.kp_arm, p_.kd_arm, true);
    pd(d, arm.clavicle_ry, 0, p_.kp_arm, p_.kd_arm, true);
    pd(d, arm.shoulder_rz, outward * p_.arm_abduction, p_.kp_arm, p_.kd_arm, true);
    pd(d, arm.shoulder_ry, outward * p_.arm_twist, p_.kp_arm, p_.kd_arm, true);
    pd(d, arm.shoulder_rx, -(p_.arm_flexion + p_.arm_swing * opposite_thigh), p_.kp_arm, p_.kd_arm, true);
    pd(d, arm.elbow, -p_.elbow, p_.kp_arm, p_.kd_arm, true);
    for (int joint : arm.distal) pd(d, joint, 0, p_.kp_distal, p_.kd_distal, true);
  }
}

}  // namespace vaegail
