#include "experts/swing_ik.h"

#include <algorithm>
#include <cmath>

namespace vaegail {

Vec3 swing_ankle_path(const GaitParameters& p, const Vec2& lift_off, const Vec2& target, double phase,
                      double ankle_height) {
  double reach = std::clamp(phase / p.swing_reach_phase, 0.0, 1.0);
  reach = reach * reach * (3 - 2 * reach);
  const double lift = std::sin(M_PI * std::clamp(phase / p.swing_descent_phase, 0.0, 1.0));
  const double descent = std::max(0.0, phase - p.swing_descent_phase) / std::max(1 - p.swing_descent_phase, 1e-3);
  return {lift_off[0] + (target[0] - lift_off[0]) * reach, lift_off[1] + (target[1] - lift_off[1]) * reach,
          ankle_height + p.swing_height * lift + p.swing_end_height * descent};
}

namespace {
Vec3 unit_vector(Vec3 v) {
  mju_normalize3(v.data());
  return v;
}
// v without its component along unit vector n, normalised.
Vec3 perpendicular_unit(const Vec3& v, const Vec3& n) {
  const double along = mju_dot3(v.data(), n.data());
  return unit_vector({v[0] - along * n[0], v[1] - along * n[1], v[2] - along * n[2]});
}
}  // namespace

LegPose two_link_ik(const Vec3& hip, const Vec3& ankle, const Vec3& forward, double thigh, double shank) {
  const Vec3 r = {ankle[0] - hip[0], ankle[1] - hip[1], ankle[2] - hip[2]};
  const double length = std::clamp(mju_norm3(r.data()), 0.25, 0.995 * (thigh + shank));
  const Vec3 down = unit_vector(r);
  // Law of cosines: the knee's interior angle, and the thigh's angle off the hip-to-ankle line.
  const double interior = std::acos(std::clamp((thigh * thigh + shank * shank - length * length) / (2 * thigh * shank), -1.0, 1.0));
  const double off_line = std::acos(std::clamp((thigh * thigh + length * length - shank * shank) / (2 * thigh * length), -1.0, 1.0));
  const Vec3 ahead = perpendicular_unit(forward, down);  // in the knee's plane, across the line
  Vec3 along_thigh;  // hip to knee: turned off the line towards the front, so that the knee points forward
  for (int k = 0; k < 3; ++k) along_thigh[k] = std::cos(off_line) * down[k] + std::sin(off_line) * ahead[k];
  const Vec3 z = {-along_thigh[0], -along_thigh[1], -along_thigh[2]};
  const Vec3 x = perpendicular_unit(forward, z);
  Vec3 y;
  mju_cross(y.data(), z.data(), x.data());
  LegPose pose;
  pose.femur = {x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]};
  pose.knee = M_PI - interior;
  return pose;
}

Vec3 ankle_position(const LegPose& pose, const Vec3& hip, double thigh, double shank) {
  const Mat3& f = pose.femur;
  const Vec3 x = {f[0], f[3], f[6]}, z = {f[2], f[5], f[8]};
  const double c = std::cos(pose.knee), s = std::sin(pose.knee);
  Vec3 out;
  for (int k = 0; k < 3; ++k) out[k] = hip[k] - thigh * z[k] + shank * (-c * z[k] - s * x[k]);
  return out;
}

}  // namespace vaegail
