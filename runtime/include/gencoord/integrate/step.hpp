// SPDX-License-Identifier: BSD-3-Clause
// One step of any integrator for any system: the one place that maps Integrator to a method,
// and the one place that normalizes (system.hpp): the step's end state only, so that stages
// and half steps stay the method's own arithmetic.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include "gencoord/errors.hpp"
#include "gencoord/integrate/backward_euler.hpp"
#include "gencoord/integrate/explicit_rk.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/newton.hpp"

namespace gencoord {

/// The integrators a program compiles for a system: step() and simulate() take the set as
/// their first template argument, default every integrator. Each method instantiated is code
/// the compiler builds for that system (an implicit one: Newton and a dense LU), so a program
/// that runs only some of them names those, e.g. IntegratorSet<Integrator::RK4>.
template <Integrator... Methods>
struct IntegratorSet {};

using AllIntegrators =
    IntegratorSet<Integrator::ForwardEuler, Integrator::SymplecticEuler, Integrator::RK4,
                  Integrator::BackwardEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint>;

/// Whether `integrator` is one of the set's.
template <Integrator... Methods>
constexpr bool includes(IntegratorSet<Methods...>, Integrator integrator) {
  return ((integrator == Methods) || ...);
}

namespace detail {

// the method I (step() checks dt and the result)
template <Integrator I, class S>
typename S::State step_with(const S& system, const typename S::State& s, double dt,
                            const NewtonOptions& newton, StepStats* stats) {
  if constexpr (I == Integrator::ForwardEuler) return forward_euler_step(system, s, dt);
  if constexpr (I == Integrator::SymplecticEuler) return symplectic_euler_step(system, s, dt);
  if constexpr (I == Integrator::RK4) return rk4_step(system, s, dt);
  if constexpr (I == Integrator::BackwardEuler)
    return backward_euler_step(system, s, dt, newton, stats);
  if constexpr (I == Integrator::Trapezoidal) return trapezoidal_step(system, s, dt, newton, stats);
  if constexpr (I == Integrator::ImplicitMidpoint)
    return implicit_midpoint_step(system, s, dt, newton, stats);
}

// the method `integrator`, one of the set's
template <class S, Integrator... Methods>
typename S::State step_of(IntegratorSet<Methods...>, const S& system, Integrator integrator,
                          const typename S::State& s, double dt, const NewtonOptions& newton,
                          StepStats* stats) {
  typename S::State out;
  const bool found =
      ((integrator == Methods && (out = step_with<Methods>(system, s, dt, newton, stats), true)) ||
       ...);
  if (!found)
    throw std::invalid_argument("gencoord: integrator " + std::string(to_string(integrator)) +
                                " is not compiled into this program for " +
                                std::string(system.name()));
  return out;
}

}  // namespace detail

/// One step of size dt of `integrator` from `s`; returns the state at s.t + dt, normalized by
/// the system's normalize() where it has one (unit quaternions).
/// \param[in]     system      The system (system.hpp).
/// \param[in]     integrator  Which integrator.
/// \param[in]     s           The state at the start of the step.
/// \param[in]     dt          The step size; positive and finite.
/// \param[in]     newton      Newton settings (implicit integrators only).
/// \param[in,out] stats       Work counters, incremented; may be null.
/// \throws StepSizeError if dt is not positive and finite or s.t is not finite; NewtonError
///         if an implicit step does not converge; for a step that ends at a state that is
///         not finite, what S::check() throws for it (MaximalDivergedError, ...) or else
///         DivergedError; what the system throws (DynamicsError, ...).
template <class Methods = AllIntegrators, class S>
typename S::State step(const S& system, Integrator integrator, const typename S::State& s,
                       double dt, const NewtonOptions& newton = {}, StepStats* stats = nullptr) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw StepSizeError("gencoord: step size must be positive and finite, got dt = " +
                        std::to_string(dt));
  if (!std::isfinite(s.t))
    throw StepSizeError("gencoord: a step must start at a finite time, got t = " +
                        std::to_string(s.t));
  if (stats) ++stats->steps;
  typename S::State out = detail::step_of(Methods{}, system, integrator, s, dt, newton, stats);
  normalize(system, &out);
  if (!std::isfinite(detail::max_abs(out.q)) || !std::isfinite(detail::max_abs(out.v))) {
    system.check(out, dt);  // the system's own error for it, if it has one
    detail::throw_diverged_error(system.name(), to_string(integrator), s.t, dt);
  }
  return out;
}

}  // namespace gencoord
