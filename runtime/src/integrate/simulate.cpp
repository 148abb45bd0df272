// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/integrate/simulate.hpp"

#include <cmath>
#include <sstream>

namespace gencoord {

long long step_count(double dt, double duration) {
  std::ostringstream msg;
  msg.precision(17);
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    msg << "gencoord: step size must be positive and finite, got dt = " << dt;
    throw StepSizeError(msg.str());
  }
  if (!(duration >= 0.0) || !std::isfinite(duration)) {
    msg << "gencoord: duration must be non-negative and finite, got " << duration;
    throw StepSizeError(msg.str());
  }
  const double ratio = duration / dt;
  if (ratio > 1e15) {
    msg << "gencoord: duration " << duration << " needs more than 1e15 steps of dt = " << dt;
    throw StepSizeError(msg.str());
  }
  const long long num = std::llround(ratio);
  // tolerate round-off in duration / dt (1.0 / 0.1 = 9.999...), nothing more
  if (std::abs(static_cast<double>(num) * dt - duration) > 1e-6 * dt) {
    msg << "gencoord: duration " << duration << " is not a whole number of steps of dt = " << dt
        << " (ratio " << ratio << "); use dt = duration / n for an integer n, e.g. dt = "
        << duration / static_cast<double>(num > 0 ? num : 1);
    throw StepSizeError(msg.str());
  }
  return num;
}

}  // namespace gencoord
