#include "experts/balance_feedback.h"

#include <algorithm>
#include <cmath>

namespace vaegail {

double commanded_heading(const GaitParameters& p, double time) {
  const double turned = std::copysign(std::min(std::abs(p.heading), p.turn_rate * time), p.heading);
  return turned + p.heading_wander * std::sin(2 * M_PI * time / p.wander_period);
}

Vec2 to_heading_frame(const Vec2& w, double heading) {
  const double c = std::cos(heading), s = std::sin(heading);
  return {c * w[0] + s * w[1], -s * w[0] + c * w[1]};
}

Vec2 to_world_frame(const Vec2& l, double heading) { return to_heading_frame(l, -heading); }

Vec2 foot_placement(const GaitParameters& p, const Vec2& stance_ankle, const Vec2& com, const Vec2& com_velocity,
                    double heading, double swing_side) {
  const Vec2 d = to_heading_frame({com[0] - stance_ankle[0], com[1] - stance_ankle[1]}, heading);
  const Vec2 v = to_heading_frame(com_velocity, heading);
  const Vec2 step = {p.place_dx * d[0] + p.place_vx * (v[0] - p.speed) + p.place_offset_x,
                     p.place_dy * d[1] + p.place_vy * (v[1] - swing_side * p.sway_speed) + swing_side * p.step_width};
  const Vec2 world = to_world_frame(step, heading);
  return {stance_ankle[0] + world[0], stance_ankle[1] + world[1]};
}

}  // namespace vaegail
