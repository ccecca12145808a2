// Numerical faults: a NaN or an infinity in a loss, a gradient norm or a simulated state. A
// trainer stops on one with one line before the update that would carry it into the weights,
// so the last checkpoint written stays the last good state; a rollout resets a diverged
// episode and counts it rather than let its states poison a batch. LibTorch-free: pass
// loss.item<double>(), or a state buffer.
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace vaegail {

class NumericalFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Returns `value` when finite; else throws NumericalFault "WHAT is nan" (or inf, -inf).
// `what` names the quantity and where it arose: "vae train: epoch 3, batch 7: loss".
double require_finite(double value, const std::string& what);

// Whether all `n` values are finite: a state to check after a physics step.
template <typename T>
bool all_finite(const T* values, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(values[i])) return false;
  return true;
}

}  // namespace vaegail
