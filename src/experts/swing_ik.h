// The swing leg (Coros 2010; cartwheel-3d's IKVMCController): the ankle on a path from where it
// lifted off to the balance feedback's target, and the two-link inverse kinematics that turns a
// wanted ankle position into a femur orientation in the world and a knee angle. (The plain
// SIMBICON law, a thigh angle from the COM state, was tried on this body and did not walk: the
// foot hung in the air and landed in a split; see the prototype's README.)
#pragma once

#include "experts/balance_feedback.h"
#include "experts/virtual_model.h"

namespace vaegail {

// The swing ankle's wanted world position at `phase` = time in step / step_min_time: horizontally
// a smoothstep from lift_off to target finished at swing_reach_phase; vertically ankle_height
// plus a half sine of swing_height that ends at swing_descent_phase, then a straight descent to
// swing_end_height at phase 1 and on below it, so that the foot always lands.
Vec3 swing_ankle_path(const GaitParameters& p, const Vec2& lift_off, const Vec2& target, double phase,
                      double ankle_height);

struct LegPose {
  Mat3 femur;        // femur orientation in the world: z up the thigh, x forward in the knee's plane
  double knee = 0;   // knee flexion (rad, 0 straight)
};

// The leg that puts the ankle at `ankle` from a hip at `hip` (world, m), with the knee in the
// vertical-ish plane through hip, ankle and `forward` (a horizontal unit vector the knee points
// along). A target nearer than 0.25 m or beyond 0.995 of the leg's length is moved along the
// hip-to-ankle line to that distance.
LegPose two_link_ik(const Vec3& hip, const Vec3& ankle, const Vec3& forward, double thigh, double shank);

// Forward kinematics of a LegPose: where its ankle is (the check on two_link_ik, and what the
// controller assumes the body does with it: the shank turned back from the thigh by the knee
// angle about the femur's y axis).
Vec3 ankle_position(const LegPose& pose, const Vec3& hip, double thigh, double shank);

}  // namespace vaegail
