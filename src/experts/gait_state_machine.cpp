#include "experts/gait_state_machine.h"

namespace vaegail {

bool GaitStateMachine::advance(double dt, bool swing_foot_on_floor, double min_time, double max_time) {
  time_ += dt;
  if (!((time_ >= min_time && swing_foot_on_floor) || time_ >= max_time)) return false;
  stance_ = swing();
  time_ = 0;
  ++steps_;
  return true;
}

}  // namespace vaegail
