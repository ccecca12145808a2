#include "experts/gait_skeleton.h"

#include <stdexcept>
#include <utility>

namespace vaegail {

namespace {
int named(const mjModel* m, const std::string& model_name, mjtObj type, const std::string& name, const char* what) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::invalid_argument(model_name + ": the gait controller needs a " + what + " named " + name);
  return id;
}
}  // namespace

GaitSkeleton::GaitSkeleton(const mjModel* m, const std::string& name) : model(m), model_name(name) {
  root = named(m, name, mjOBJ_BODY, "root", "body");
  floor_geom = named(m, name, mjOBJ_GEOM, "floor", "geom");
  // Each side's joints, by the CMU names without their l/r prefix.
  const std::pair<int GaitLeg::*, const char*> leg_joints[] = {
      {&GaitLeg::hip_rz, "femurrz"}, {&GaitLeg::hip_ry, "femurry"},  {&GaitLeg::hip_rx, "femurrx"},
      {&GaitLeg::knee, "tibiarx"},   {&GaitLeg::ankle_rz, "footrz"}, {&GaitLeg::ankle_rx, "footrx"},
      {&GaitLeg::toe, "toesrx"}};
  const std::pair<int GaitArm::*, const char*> arm_joints[] = {
      {&GaitArm::clavicle_rz, "claviclerz"}, {&GaitArm::clavicle_ry, "claviclery"}, {&GaitArm::shoulder_rz, "humerusrz"},
      {&GaitArm::shoulder_ry, "humerusry"},  {&GaitArm::shoulder_rx, "humerusrx"},  {&GaitArm::elbow, "radiusrx"}};
  const char* const distal[6] = {"wristry", "handrz", "handrx", "fingersrx", "thumbrz", "thumbrx"};
  const char* const side[2] = {"l", "r"};
  for (int s = 0; s < 2; ++s) {
    const auto sided = [&](const char* part) { return side[s] + std::string(part); };
    GaitLeg& leg = legs[s];
    leg.femur = named(m, name, mjOBJ_BODY, sided("femur"), "body");
    leg.tibia = named(m, name, mjOBJ_BODY, sided("tibia"), "body");
    leg.foot = named(m, name, mjOBJ_BODY, sided("foot"), "body");
    leg.foot_geom = named(m, name, mjOBJ_GEOM, sided("foot"), "geom");
    leg.toes_geom = named(m, name, mjOBJ_GEOM, sided("toes"), "geom");
    for (const auto& [member, part] : leg_joints) leg.*member = joint(sided(part));
    for (const auto& [member, part] : arm_joints) arms[s].*member = joint(sided(part));
    for (int k = 0; k < 6; ++k) arms[s].distal[k] = joint(sided(distal[k]));
  }
  const char* const back_segments[3] = {"lowerback", "upperback", "thorax"};
  for (int k = 0; k < 3; ++k)
    back[k] = {joint(back_segments[k] + std::string("rx")), joint(back_segments[k] + std::string("rz")),
               joint(back_segments[k] + std::string("ry"))};
  const char* const neck_segments[3] = {"lowerneck", "upperneck", "head"};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) neck[3 * k + a] = joint(neck_segments[k] + std::string(a == 0 ? "rz" : a == 1 ? "ry" : "rx"));
  thigh = mju_norm3(m->body_pos + 3 * legs[0].tibia);
  shank = mju_norm3(m->body_pos + 3 * legs[0].foot);
  motor.assign(m->njnt, -1);
  gear.assign(m->njnt, 0.0);
  for (int a = 0; a < m->nu; ++a)
    if (m->actuator_trntype[a] == mjTRN_JOINT) {
      motor[m->actuator_trnid[2 * a]] = a;
      gear[m->actuator_trnid[2 * a]] = m->actuator_gear[6 * a];
    }
  for (int j = 0; j < m->njnt; ++j)
    if (m->jnt_type[j] == mjJNT_HINGE && motor[j] < 0)
      throw std::invalid_argument(name + ": the gait controller needs a motor on hinge " + mj_id2name(m, mjOBJ_JOINT, j));
  // The rest pose's ankle height: where the swing path lands the ankle.
  mjData* rest = mj_makeData(m);
  mj_kinematics(m, rest);
  ankle_height = rest->xpos[3 * legs[0].foot + 2];  // the floor is z = 0
  mj_deleteData(rest);
}

int GaitSkeleton::joint(const std::string& joint_name) const {
  return named(model, model_name, mjOBJ_JOINT, joint_name, "joint");
}

bool GaitSkeleton::foot_on_floor(const mjData* d, int side) const {
  const GaitLeg& leg = legs[side];
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const int other = c.geom1 == floor_geom ? c.geom2 : c.geom2 == floor_geom ? c.geom1 : -1;
    if (other == leg.foot_geom || other == leg.toes_geom) return true;
  }
  return false;
}

}  // namespace vaegail
