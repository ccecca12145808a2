// Balance feedback (SIMBICON; Coros, Beaudoin & van de Panne 2010; cartwheel-3d's
// BalanceFeedback): where the swing foot lands, from the centre of mass's position and velocity
// relative to the stance ankle, in both planes, in the frame of the commanded heading. Stepping
// further ahead than the COM's drift slows the body down; the speed term makes that drift the
// desired speed's.
//   x_f = place_dx d_x + place_vx (v_x - speed) + place_offset_x
//   y_f = place_dy d_y + place_vy (v_y - s_swing sway_speed) + s_swing step_width
// (heading frame, relative to the stance ankle; s_swing +1 when the left leg swings).
#pragma once

#include <array>

#include "experts/gait_parameters.h"

namespace vaegail {

using Vec2 = std::array<double, 2>;

// The commanded heading (rad) at `time` s since the reset: turning from 0 (the reset faces world
// x) towards `heading` at turn_rate, plus the sinusoidal wander.
double commanded_heading(const GaitParameters& p, double time);

// Horizontal world vector turned into the frame of `heading` (x along it), and back.
Vec2 to_heading_frame(const Vec2& world, double heading);
Vec2 to_world_frame(const Vec2& local, double heading);

// The world (x, y) target of the swing ankle. com, com_velocity and stance_ankle are world
// horizontal positions (m) and the COM's velocity (m/s); swing_side +1 left, -1 right.
Vec2 foot_placement(const GaitParameters& p, const Vec2& stance_ankle, const Vec2& com, const Vec2& com_velocity,
                    double heading, double swing_side);

}  // namespace vaegail
