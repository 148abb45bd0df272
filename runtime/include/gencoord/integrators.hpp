// Integrator selection by name and a single step() entry point for all integrators.
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "gencoord/errors.hpp"
#include "gencoord/explicit_steps.hpp"
#include "gencoord/implicit_steps.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

enum class Integrator {
  ForwardEuler,
  SymplecticEuler,
  RK4,
  BackwardEuler,
  Trapezoidal,
  ImplicitMidpoint,
};

/// Integrator from its name: "forward_euler", "symplectic_euler", "rk4", "backward_euler",
/// "trapezoidal" or "implicit_midpoint" (case-insensitive; '-' and ' ' read as '_').
/// \throws std::invalid_argument naming the valid names if `name` is none of them.
Integrator parse_integrator(std::string_view name);

/// The canonical name of an integrator, as accepted by parse_integrator().
const char* to_string(Integrator integrator);

/// The valid names, comma separated ("forward_euler, symplectic_euler, ...").
std::string integrator_names();

/// Order of accuracy of the global error (1, 2 or 4).
int order(Integrator integrator);

/// Whether the integrator solves a nonlinear system (Newton) each step.
bool is_implicit(Integrator integrator);

/// One step of size dt of `integrator` from `s`; returns the state at s.t + dt.
/// \param[in]     integrator  Which integrator.
/// \param[in]     p           The model parameters.
/// \param[in]     s           The state at the start of the step (q, v of dim M::nq).
/// \param[in]     dt          The step size; positive and finite.
/// \param[in]     newton      Newton settings (implicit integrators only).
/// \param[in,out] stats       Work counters, incremented; may be null.
/// \throws StepSizeError if dt is not positive and finite; DynamicsError if the dynamics fail;
///         NewtonError if an implicit step does not converge.
template <class M>
State<M> step(Integrator integrator, const ParamsOf<M>& p, const State<M>& s, double dt,
              const NewtonOptions& newton = {}, StepStats* stats = nullptr) {
  static_assert(assert_model_v<M>);
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw StepSizeError("gencoord: step size must be positive and finite, got dt = " +
                        std::to_string(dt));
  if (stats) ++stats->steps;
  switch (integrator) {
    case Integrator::ForwardEuler:
      return forward_euler_step<M>(p, s, dt);
    case Integrator::SymplecticEuler:
      return symplectic_euler_step<M>(p, s, dt);
    case Integrator::RK4:
      return rk4_step<M>(p, s, dt);
    case Integrator::BackwardEuler:
      return backward_euler_step<M>(p, s, dt, newton, stats);
    case Integrator::Trapezoidal:
      return trapezoidal_step<M>(p, s, dt, newton, stats);
    case Integrator::ImplicitMidpoint:
      return implicit_midpoint_step<M>(p, s, dt, newton, stats);
  }
  throw std::invalid_argument("gencoord: invalid Integrator value " +
                              std::to_string(static_cast<int>(integrator)));
}

}  // namespace gencoord
