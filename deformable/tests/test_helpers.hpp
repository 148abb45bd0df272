// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by the deformable tests: pi, pulse set-up and arrival-time measurement.

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace gencoord::deformable::testing {

inline constexpr double kPi = 3.14159265358979323846;

/// A right-travelling Gaussian pulse of axial displacement u = a exp(-((p - p0) / w)^2), with
/// the velocity -c du/dp that makes it travel toward +p at speed c.
struct GaussianPulse {
  double amplitude = 1e-3;  ///< a (m)
  double center = 0.0;      ///< p0 (m)
  double width = 0.1;       ///< w (m)
  double speed = 1.0;       ///< c (m/s)
  double displacement(double p) const {
    const double s = (p - center) / width;
    return amplitude * std::exp(-s * s);
  }
  double velocity(double p) const {
    return speed * 2.0 * (p - center) / (width * width) * displacement(p);
  }
};

/// Time of the largest sample of a uniformly sampled signal, refined by fitting a parabola
/// through the peak sample and its two neighbours (s).
inline double peak_time(const std::vector<double>& signal, double dt) {
  size_t best = 0;
  for (size_t k = 1; k < signal.size(); ++k) {
    if (signal[k] > signal[best]) best = k;
  }
  if (best == 0 || best + 1 >= signal.size()) return best * dt;
  const double a = signal[best - 1], b = signal[best], c = signal[best + 1];
  const double denom = a - 2.0 * b + c;
  const double shift = denom != 0.0 ? 0.5 * (a - c) / denom : 0.0;
  return (static_cast<double>(best) + shift) * dt;
}

}  // namespace gencoord::deformable::testing
