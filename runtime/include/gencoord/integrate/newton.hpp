// SPDX-License-Identifier: BSD-3-Clause
// Newton's method on the end velocity of an implicit step: its settings, work counters and
// the iteration loop of backward_euler_step().
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "gencoord/errors.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"

namespace gencoord {

/// Newton's method settings for implicit steps. Converged means both tests below pass at the
/// returned end velocity v1: a small last update, and a small residual of the implicit
/// equation g(v1) = m (v1 - v0) - h F(v1) (backward_euler.hpp).
struct NewtonOptions {
  /// Update test: the last Newton update dv satisfies
  /// |dv|_inf <= tolerance * (1 + |v1|_inf): absolute near v = 0, relative for large v.
  double tolerance = 1e-12;
  /// Newton updates allowed per implicit (sub)step before NewtonError is thrown.
  int max_iterations = 20;
  /// Where da/dq and da/dv come from: the generated residual Jacobians (Auto, for every
  /// generated model) or finite differences. There is no fallback from one to the other.
  JacobianSource jacobian = JacobianSource::Auto;
  /// Take the first Newton update and accept it without the convergence test (the linearly
  /// implicit Euler of large mass-spring systems: one sparse solve per step).
  bool linearized = false;
  /// Residual test, at v1 after the last update:
  /// |g|_inf <= residual_tolerance * (|m|_inf + |m v0|_inf + |m v1|_inf + h |F|_inf),
  /// the scale being the sizes of the terms of g (momenta; velocities for a unit-mass
  /// system), so it measures how many digits of the balance m (v1 - v0) = h F hold. A small
  /// update alone does not mean a solution: when h^2 dF/dq dominates the Jacobian, updates
  /// are tiny while g is as large as h F. Accurate steps give 1e-16 to 1e-10; steps of many
  /// periods of the fastest mode (h omega > 1e5) reach 1e-6 from rounding alone.
  double residual_tolerance = 1e-6;
};

/// Work counters, incremented (never reset) by the steps that receive a pointer to them.
struct StepStats {
  long steps = 0;                 // calls of step()
  long newton_solves = 0;         // implicit (sub)steps solved
  long newton_iterations = 0;     // Newton updates, summed over all solves
  int max_newton_iterations = 0;  // most Newton updates in one solve
};

/// The residual of the implicit equation at an iterate: |g|_inf and its scale (NewtonOptions).
struct NewtonResidual {
  double norm = std::numeric_limits<double>::infinity();
  double scale = 1.0;
  bool within(double tolerance) const { return std::isfinite(norm) && norm <= tolerance * scale; }
};

/// The norms of one Newton update, as an update function reports them.
struct NewtonUpdate {
  NewtonResidual residual;     // g at the iterate the update was computed from
  double update_norm = 0.0;    // |dv|_inf; NaN/inf (singular Jacobian) ends the iteration
  double velocity_norm = 0.0;  // |v1|_inf after the update, for the relative test
};

namespace detail {

// std::invalid_argument unless the Newton settings are usable
inline void check_newton_options(const NewtonOptions& options) {
  if (options.max_iterations < 1 || !(options.tolerance >= 0.0) ||
      !(options.residual_tolerance >= 0.0))
    throw std::invalid_argument(
        "gencoord: NewtonOptions need max_iterations >= 1, tolerance >= 0 and "
        "residual_tolerance >= 0");
}

/// Calls update() (one Newton update: assemble, solve, apply; returns its norms) until the
/// update test |dv|_inf <= tolerance (1 + |v1|_inf) passes and then residual() (g at the
/// updated iterate) passes the residual test; counts the work in stats (may be null) and
/// throws NewtonError naming `model`, t and h when that does not happen in max_iterations
/// updates or an update is not finite. options.linearized accepts the first update without
/// either test. `solved` skips the loop (nothing to solve for).
template <class Update, class Residual>
void newton_iterate(const char* model, double t, double h, const NewtonOptions& options,
                    StepStats* stats, bool solved, Update&& update, Residual&& residual) {
  check_newton_options(options);
  NewtonUpdate last;
  NewtonResidual latest;  // at the latest iterate where g was evaluated
  int it = 0;
  while (it < options.max_iterations && !solved) {
    last = update();
    latest = last.residual;
    ++it;
    if (!std::isfinite(last.update_norm)) break;
    if (options.linearized) {
      solved = true;
    } else if (last.update_norm <= options.tolerance * (1.0 + last.velocity_norm)) {
      latest = residual();
      solved = latest.within(options.residual_tolerance);
    }
  }
  if (stats) {
    ++stats->newton_solves;
    stats->newton_iterations += it;
    stats->max_newton_iterations = std::max(stats->max_newton_iterations, it);
  }
  if (!solved)
    throw_newton_error(model, t, h, it, last.update_norm, latest.norm, options.tolerance,
                       latest.scale, options.residual_tolerance);
}

}  // namespace detail
}  // namespace gencoord
