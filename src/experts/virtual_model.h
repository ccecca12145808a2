// Virtual-model control (Pratt's virtual model control; cartwheel-3d's VirtualModelController):
// torques wanted in the world, on a body or a chain, realised by the hinges that carry it.
//   * hinge_torques: a torque pair (tau on a body, -tau on its parent) as the generalised forces
//     of the hinges between them, by the Jacobian transpose: the body turns relative to its parent
//     at sum_k a_k qdot_k (a_k the hinges' world axes), so f_k = a_k . tau. (The prototype solved
//     A f = tau instead; that agrees only while the axes stay orthonormal, near the rest pose.)
//   * gravity_torque: gravity's torque on a subtree about a point, from its centre of mass.
//   * support_torque: the Jacobian-transpose gravity compensation of a standing leg: the torque a
//     joint exerts on the leg below it so that its reaction holds the rest of the body still,
//     gravity's torque on that rest (the whole body's minus the leg's).
//   * orientation_pd: a PD torque turning a body towards a world orientation.
#pragma once

#include <mujoco/mujoco.h>

#include <array>

namespace vaegail {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<double, 9>;  // row-major, as mjData's xmat

// Gravity's torque (world frame, N m) about `point` on the subtree rooted at `body`:
// (c - point) x (M g), c and M the subtree's centre of mass (data->subtree_com) and mass.
Vec3 gravity_torque(const mjModel* model, const mjData* data, int body, const double* point);

// The torque (world frame, N m) about `point` that a joint there exerts on the subtree `leg` to
// hold the rest of `root`'s subtree (the whole articulated body) still against gravity:
// gravity_torque(root) - gravity_torque(leg).
Vec3 support_torque(const mjModel* model, const mjData* data, int root, int leg, const double* point);

// Generalised forces f_k = a_k . torque (N m) of three hinges with unit world axes a0..a2 that
// exert `torque` on their body and its reaction on the parent.
Vec3 hinge_torques(const double* a0, const double* a1, const double* a2, const Vec3& torque);

// The rotation vector (world frame, rad) that turns orientation `current` into `target`.
Vec3 orientation_error(const Mat3& target, const double* current);

// kp * orientation_error(target, current) - kd * angular_velocity (world frame).
Vec3 orientation_pd(const Mat3& target, const double* current, const double* angular_velocity, double kp, double kd);

// Rotation matrices about z, y and x, and their product a * b.
Mat3 rotation_z(double angle);
Mat3 rotation_y(double angle);
Mat3 rotation_x(double angle);
Mat3 multiply(const Mat3& a, const Mat3& b);

}  // namespace vaegail
