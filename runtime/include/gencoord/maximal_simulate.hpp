// The maximal model's integrators by name, one step() entry point, and a fixed-step loop.
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "gencoord/implicit_steps.hpp"
#include "gencoord/maximal_backward_euler.hpp"
#include "gencoord/maximal_errors.hpp"
#include "gencoord/maximal_explicit_steps.hpp"
#include "gencoord/maximal_model.hpp"
#include "gencoord/maximal_stability.hpp"
#include "gencoord/maximal_state.hpp"
#include "gencoord/simulate.hpp"

namespace gencoord {

/// The integrators of the maximal model.
enum class MaximalIntegrator { SymplecticEuler, RK4, BackwardEuler };

/// MaximalIntegrator from "symplectic_euler", "rk4" or "backward_euler".
/// \throws std::invalid_argument naming the valid names otherwise.
inline MaximalIntegrator parse_maximal_integrator(std::string_view name) {
  if (name == "symplectic_euler") return MaximalIntegrator::SymplecticEuler;
  if (name == "rk4") return MaximalIntegrator::RK4;
  if (name == "backward_euler") return MaximalIntegrator::BackwardEuler;
  throw std::invalid_argument("gencoord: unknown maximal integrator '" + std::string(name) +
                              "'; valid: symplectic_euler, rk4, backward_euler");
}

/// The name parse_maximal_integrator() accepts.
inline const char* to_string(MaximalIntegrator integrator) {
  switch (integrator) {
    case MaximalIntegrator::SymplecticEuler: return "symplectic_euler";
    case MaximalIntegrator::RK4: return "rk4";
    case MaximalIntegrator::BackwardEuler: return "backward_euler";
  }
  return "?";
}

/// Largest stable step of an integrator for a stiffest-mode frequency omega (omega_max()),
/// times safety: 2 / omega (symplectic Euler), 2 sqrt(2) / omega (RK4), infinity (backward Euler).
inline double stable_step(MaximalIntegrator integrator, double omega, double safety = 0.9) {
  switch (integrator) {
    case MaximalIntegrator::SymplecticEuler: return symplectic_euler_stable_step(omega, safety);
    case MaximalIntegrator::RK4: return rk4_stable_step(omega, safety);
    case MaximalIntegrator::BackwardEuler: break;
  }
  return std::numeric_limits<double>::infinity();
}

/// One step of size h of `integrator` from s; returns the state at s.t + h.
/// \throws InverseMapError (forces), NewtonError (backward Euler), as the steps themselves.
template <class M>
MaximalState<M> maximal_step(MaximalIntegrator integrator, const MaximalModel<M>& model,
                             const MaximalState<M>& s, double h, const NewtonOptions& newton = {},
                             StepStats* stats = nullptr) {
  if (stats) ++stats->steps;
  switch (integrator) {
    case MaximalIntegrator::SymplecticEuler: return maximal_symplectic_euler_step(model, s, h);
    case MaximalIntegrator::RK4: return maximal_rk4_step(model, s, h);
    case MaximalIntegrator::BackwardEuler:
      return maximal_backward_euler_step(model, s, h, newton, stats);
  }
  throw std::invalid_argument("gencoord: invalid MaximalIntegrator value");
}

/// Integrates the maximal model from `initial` with step_count(dt, duration) fixed steps;
/// observer(const MaximalState<M>&) sees the initial state and every step's end (step k ends
/// at exactly initial.t + k dt).
/// \return The final state.
/// \throws MaximalDivergedError as soon as a state is not finite; StepSizeError (see
///         step_count()); InverseMapError, NewtonError from the steps.
template <class M, class Observer>
MaximalState<M> simulate_maximal(const MaximalModel<M>& model, MaximalState<M> initial,
                                 MaximalIntegrator integrator, double dt, double duration,
                                 Observer&& observer, const NewtonOptions& newton = {},
                                 StepStats* stats = nullptr) {
  const long long num = step_count(dt, duration);
  const double t0 = initial.t;
  MaximalState<M> s = std::move(initial);
  observer(std::as_const(s));
  for (long long k = 1; k <= num; ++k) {
    s = maximal_step(integrator, model, s, dt, newton, stats);
    s.t = t0 + static_cast<double>(k) * dt;
    if (!s.x.allFinite() || !s.xdot.allFinite())
      throw MaximalDivergedError(M::name, s.t, dt, model.kappa());
    observer(std::as_const(s));
  }
  return s;
}

}  // namespace gencoord
