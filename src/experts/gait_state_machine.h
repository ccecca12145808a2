// SIMBICON's finite-state machine, one state per step (cartwheel-3d's SimBiController): which leg
// stands and how long the step has lasted. The legs swap when the swing foot touches the floor
// once the step has lasted step_min_time (an earlier touch is a scuff, not a landing), or at
// step_max_time whatever the feet do (a foot that never lands must not stall the gait).
#pragma once

namespace vaegail {

class GaitStateMachine {
 public:
  static constexpr int kLeft = 0, kRight = 1;

  // Advances the step's clock by dt (s); returns whether the legs swapped (the clock then
  // restarts at 0 and the swing leg is the old stance leg).
  bool advance(double dt, bool swing_foot_on_floor, double min_time, double max_time);

  int stance() const { return stance_; }
  int swing() const { return 1 - stance_; }
  // +1 for the left leg, -1 for the right: the sign of the leg's outward direction along y.
  static double side_sign(int leg) { return leg == kLeft ? 1.0 : -1.0; }
  double time_in_step() const { return time_; }
  int steps() const { return steps_; }

 private:
  int stance_ = kLeft;  // the right leg swings first from the standing start
  double time_ = 0;
  int steps_ = 0;
};

}  // namespace vaegail
