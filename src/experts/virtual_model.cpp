#include "experts/virtual_model.h"

#include <cmath>

namespace vaegail {

Vec3 gravity_torque(const mjModel* m, const mjData* d, int body, const double* point) {
  const double mass = m->body_subtreemass[body];
  const double arm[3] = {d->subtree_com[3 * body] - point[0], d->subtree_com[3 * body + 1] - point[1],
                         d->subtree_com[3 * body + 2] - point[2]};
  const double weight[3] = {mass * m->opt.gravity[0], mass * m->opt.gravity[1], mass * m->opt.gravity[2]};
  Vec3 torque;
  mju_cross(torque.data(), arm, weight);
  return torque;
}

Vec3 support_torque(const mjModel* m, const mjData* d, int root, int leg, const double* point) {
  const Vec3 all = gravity_torque(m, d, root, point), below = gravity_torque(m, d, leg, point);
  return {all[0] - below[0], all[1] - below[1], all[2] - below[2]};
}

Vec3 hinge_torques(const double* a0, const double* a1, const double* a2, const Vec3& t) {
  return {mju_dot3(a0, t.data()), mju_dot3(a1, t.data()), mju_dot3(a2, t.data())};
}

Vec3 orientation_error(const Mat3& target, const double* current) {
  double relative[9], quat[4];
  mju_mulMatMatT(relative, target.data(), current, 3, 3, 3);  // target * current^T: current to target, in the world
  mju_mat2Quat(quat, relative);
  if (quat[0] < 0)  // the shorter way round
    for (double& q : quat) q = -q;
  Vec3 error;
  mju_quat2Vel(error.data(), quat, 1.0);
  return error;
}

Vec3 orientation_pd(const Mat3& target, const double* current, const double* angular_velocity, double kp, double kd) {
  const Vec3 e = orientation_error(target, current);
  return {kp * e[0] - kd * angular_velocity[0], kp * e[1] - kd * angular_velocity[1], kp * e[2] - kd * angular_velocity[2]};
}

Mat3 rotation_z(double a) { return {std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1}; }
Mat3 rotation_y(double a) { return {std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)}; }
Mat3 rotation_x(double a) { return {1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a)}; }

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 c;
  mju_mulMatMat(c.data(), a.data(), b.data(), 3, 3, 3);
  return c;
}

}  // namespace vaegail
