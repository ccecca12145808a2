#include "util/numerical_fault.h"

namespace vaegail {

double require_finite(double value, const std::string& what) {
  if (std::isfinite(value)) return value;
  throw NumericalFault(what + " is " + (std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf"));
}

}  // namespace vaegail
