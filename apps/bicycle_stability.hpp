// SPDX-License-Identifier: BSD-3-Clause
// The Whipple bicycle's (models/whipple_bicycle.py) upright straight running, linearized in
// roll and steer: the state matrix of z = (phi, delta, phi', delta'), its eigenvalues, and the
// weave and capsize speeds where the bicycle starts and stops balancing itself.
//
// The linearization is the generated nonlinear model's (linearize_constrained): pitch is
// solved from the front wheel's contact, the speeds x', y', psi', theta' and theta_f' from
// the rolling constraints, the rear wheel's rate -v / r_r is held (the speed v), and the
// position, heading and wheel angles are held (they do not enter the dynamics).
#pragma once

#include <Eigen/Core>
// GCC 12 warns (-Wmaybe-uninitialized, a false positive) inside Eigen's EigenSolver; silenced
// only while Eigen's header is read
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Eigenvalues>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>

#include "gencoord/control/constrained_linearization.hpp"
#include "generated/whipple_bicycle.hpp"

namespace gencoord::bicycle {

using Bicycle = models::WhippleBicycle;
using Eigenvalues = std::array<std::complex<double>, 4>;

// q = (x, y, psi, phi, theta, theta_r, delta, theta_f), v the same coordinates' rates
enum Index { kX, kY, kYaw, kRoll, kPitch, kRearWheel, kSteer, kFrontWheel };

/// Which coordinates and speeds are independent (roll, steer), dependent (pitch; x', y',
/// psi', theta', theta_f') and held (the rest: position, heading, the wheels' angles and the
/// rear wheel's rate, which sets the speed).
inline CoordinateSplit roll_and_steer() {
  CoordinateSplit split;
  split.independent_q = {kRoll, kSteer};
  split.dependent_q = {kPitch};
  split.independent_v = {kRoll, kSteer};
  split.dependent_v = {kX, kY, kYaw, kPitch, kFrontWheel};
  return split;
}

/// Upright straight running at forward speed `speed` (m/s), the rear wheel turning at
/// -speed / r_r, with a roll rate `roll_rate` (a push; 0 for the steady motion): on the
/// constraints.
inline State<Bicycle> upright(const Bicycle::Params& p, double speed, double roll_rate = 0) {
  State<Bicycle> s;
  s.q.setZero();
  s.v.setZero();
  s.v[kRearWheel] = -speed / p.r_r;
  s.v[kRoll] = roll_rate;
  return state_on_constraints<Bicycle>(p, s, roll_and_steer());
}

/// d z' / d z for z = (phi, delta, phi', delta') about upright running at `speed`.
inline Eigen::Matrix4d roll_steer_matrix(const Bicycle::Params& p, double speed) {
  return linearize_constrained<Bicycle>(p, upright(p, speed), roll_and_steer()).A;
}

/// The four eigenvalues at `speed`, by increasing real part, then imaginary part.
inline Eigenvalues eigenvalues(const Bicycle::Params& p, double speed) {
  const Eigen::EigenSolver<Eigen::Matrix4d> solver(roll_steer_matrix(p, speed), false);
  Eigenvalues values;
  for (int k = 0; k < 4; ++k) values[k] = solver.eigenvalues()[k];
  std::sort(values.begin(), values.end(), [](const auto& a, const auto& b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
  return values;
}

namespace detail {

// the largest real part among the oscillatory (weave) or the real (capsize) eigenvalues
inline double largest_real_part(const Bicycle::Params& p, double speed, bool oscillatory) {
  double largest = -std::numeric_limits<double>::infinity();
  for (const auto& value : eigenvalues(p, speed))
    if ((std::abs(value.imag()) > 1e-9) == oscillatory) largest = std::max(largest, value.real());
  return largest;
}

// the root of f in [low, high] (f changes sign there) by bisection to 1e-13 m/s; NaN if it
// does not change sign
template <class F>
double bisect(const F& f, double low, double high) {
  const bool low_sign = f(low) > 0;
  if (low_sign == (f(high) > 0)) return std::numeric_limits<double>::quiet_NaN();
  while (high - low > 1e-13) {
    const double middle = (low + high) / 2;
    (f(middle) > 0) == low_sign ? low = middle : high = middle;
  }
  return (low + high) / 2;
}

}  // namespace detail

/// The weave speed: where the oscillatory (weave) mode becomes stable, searched in 1..10 m/s.
inline double weave_speed(const Bicycle::Params& p) {
  return detail::bisect([&](double v) { return detail::largest_real_part(p, v, true); }, 1.0, 10.0);
}

/// The capsize speed: where the real capsize mode becomes unstable, above the weave speed.
inline double capsize_speed(const Bicycle::Params& p, double weave) {
  return detail::bisect([&](double v) { return detail::largest_real_part(p, v, false); }, weave,
                        20.0);
}

}  // namespace gencoord::bicycle
