// Newton's method on the end velocity of an implicit step: its settings, work counters and
// the iteration loop of backward_euler_step().
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gencoord/acceleration_jacobians.hpp"
#include "gencoord/errors.hpp"

namespace gencoord {

/// Newton's method settings for implicit steps.
struct NewtonOptions {
  /// Converged when the last Newton update dv satisfies
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
};

/// Work counters, incremented (never reset) by the steps that receive a pointer to them.
struct StepStats {
  long steps = 0;                 // calls of step()
  long newton_solves = 0;         // implicit (sub)steps solved
  long newton_iterations = 0;     // Newton updates, summed over all solves
  int max_newton_iterations = 0;  // most Newton updates in one solve
};

/// The norms of one Newton update, as an update function reports them.
struct NewtonUpdate {
  double residual_norm = 0.0;  // |g|_inf at the iterate
  double update_norm = 0.0;    // |dv|_inf; NaN/inf (singular Jacobian) ends the iteration
  double velocity_norm = 0.0;  // |v1|_inf after the update, for the relative test
};

namespace detail {

// std::invalid_argument unless the Newton settings are usable
inline void check_newton_options(const NewtonOptions& options) {
  if (options.max_iterations < 1 || !(options.tolerance >= 0.0))
    throw std::invalid_argument(
        "gencoord: NewtonOptions need max_iterations >= 1 and tolerance >= 0");
}

/// Calls update() (one Newton update: assemble, solve, apply; returns its norms) until
/// |dv|_inf <= tolerance (1 + |v1|_inf), counts the work in stats (may be null) and throws
/// NewtonError naming `model`, t and h when it does not converge in max_iterations updates
/// or an update is not finite. `solved` skips the loop (nothing to solve for).
template <class Update>
void newton_iterate(const std::string& model, double t, double h, const NewtonOptions& options,
                    StepStats* stats, bool solved, Update&& update) {
  check_newton_options(options);
  NewtonUpdate last;
  int it = 0;
  while (it < options.max_iterations && !solved) {
    last = update();
    ++it;
    if (!std::isfinite(last.update_norm)) break;
    solved =
        options.linearized || last.update_norm <= options.tolerance * (1.0 + last.velocity_norm);
  }
  if (stats) {
    ++stats->newton_solves;
    stats->newton_iterations += it;
    stats->max_newton_iterations = std::max(stats->max_newton_iterations, it);
  }
  if (!solved)
    throw_newton_error(model.c_str(), t, h, it, last.update_norm, last.residual_norm,
                       options.tolerance);
}

}  // namespace detail
}  // namespace gencoord
