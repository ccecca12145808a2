// Terms the built-in tasks' rewards share.
#pragma once

#include <algorithm>

namespace vaegail {

// weight * mean over the action's components of clip(a, -1, 1)^2: the effort a reward charges,
// clipped to the action box as the environment applies it, so that commands beyond it cost no more.
inline double effort_charge(double weight, const float* action, int act_dim) {
  double effort = 0.0;
  for (int a = 0; a < act_dim; ++a) {
    const double u = std::clamp(static_cast<double>(action[a]), -1.0, 1.0);
    effort += u * u;
  }
  return weight * effort / act_dim;
}

}  // namespace vaegail
