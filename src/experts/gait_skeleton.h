// What the gait controller needs to know of the body: the CMU humanoid's bodies, hinges and
// motors by name (models/humanoid_cmu.xml), and the leg geometry measured from the model.
//
// It assumes of the skeleton (as cartwheel-3d's IK controller states its own): a free root
// (the pelvis, "root"); per leg l/r a femur with three hip hinges (rz abduction, ry twist, rx
// flexion), a tibia with a knee hinge (rx), a foot with two ankle hinges (rz, rx) and toes (rx);
// in the rest pose the femur's z axis runs up the thigh and its x axis points forward; the feet
// and toes are the geoms named lfoot, ltoes, rfoot, rtoes; the back, neck and arm hinges carry the
// CMU names (lowerbackrx ..., lclaviclerz ..., lthumbrx); every hinge has one motor.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

namespace vaegail {

struct GaitLeg {
  int femur = -1, tibia = -1, foot = -1;                       // bodies
  int hip_rz = -1, hip_ry = -1, hip_rx = -1, knee = -1, ankle_rz = -1, ankle_rx = -1, toe = -1;  // joints
  int foot_geom = -1, toes_geom = -1;
};

struct GaitArm {
  int clavicle_rz = -1, clavicle_ry = -1, shoulder_rz = -1, shoulder_ry = -1, shoulder_rx = -1, elbow = -1;
  std::array<int, 6> distal{};  // wrist, hand (2), fingers, thumb (2)
};

struct GaitSkeleton {
  // Throws (one line naming the model and the object) when the model lacks a body, joint or geom
  // named above, or a hinge has no motor.
  GaitSkeleton(const mjModel* model, const std::string& model_name);

  // Joint id of `name`; throws naming the model and the joint.
  int joint(const std::string& name) const;
  // Whether foot `side` (0 left, 1 right) or its toes touch the floor in data's contacts.
  bool foot_on_floor(const mjData* data, int side) const;

  const mjModel* model;
  std::string model_name;
  int root = -1, floor_geom = -1;
  std::array<GaitLeg, 2> legs;   // 0 left, 1 right
  std::array<GaitArm, 2> arms;   // 0 left, 1 right
  std::array<std::array<int, 3>, 3> back{};  // lowerback, upperback, thorax: their rx (flexion), rz (lateral), ry (twist)
  std::array<int, 9> neck{};     // lower neck, upper neck, head: rz, ry, rx each
  double thigh = 0, shank = 0;   // m: hip to knee, knee to ankle (the body offsets along the leg)
  double ankle_height = 0;       // m: the ankle's height above the floor in the rest pose
  std::vector<int> motor;        // per joint: its actuator, -1 for the root
  std::vector<double> gear;      // per joint: its motor's gear (N m per unit of ctrl)
};

}  // namespace vaegail
