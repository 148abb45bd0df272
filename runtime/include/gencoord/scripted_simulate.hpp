// Fixed-step simulation loop with scripted coordinates (simulate() of simulate.hpp for a
// ScriptedModel).
#pragma once

#include <utility>

#include "gencoord/errors.hpp"
#include "gencoord/integrators.hpp"
#include "gencoord/scripted_steps.hpp"
#include "gencoord/simulate.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

/// Integrates from `initial` with step_count(dt, duration) fixed steps of size dt, the scripted
/// coordinates following sm's script. observer(state) is called with the initial state (its
/// scripted entries set from the script) and after every step; step k ends at exactly
/// initial.t + k dt. sm.driving_force(state) gives the driving forces at an observed state.
/// \param[in]     sm          The model with its script.
/// \param[in]     initial     The initial state; only its free entries and t are used.
/// \param[in]     integrator  Which integrator.
/// \param[in]     dt          The step size.
/// \param[in]     duration    The simulated time.
/// \param[in]     observer    Callable as observer(const State<M>&).
/// \param[in]     newton      Newton settings (implicit integrators only).
/// \param[in,out] stats       Work counters, incremented; may be null.
/// \return The final state.
/// \throws StepSizeError (see step_count()); DynamicsError, NewtonError from the steps; what
///         the script throws (std::out_of_range from keyframes that do not cover the run).
template <class M, class Observer>
State<M> simulate_scripted(const ScriptedModel<M>& sm, const State<M>& initial,
                           Integrator integrator, double dt, double duration,
                           Observer&& observer, const NewtonOptions& newton = {},
                           StepStats* stats = nullptr) {
  const long long num = step_count(dt, duration);
  const double t0 = initial.t;
  State<M> s = sm.imposed(initial);
  observer(std::as_const(s));
  for (long long k = 1; k <= num; ++k) {
    s = scripted_step<M>(integrator, sm, s, dt, newton, stats);
    s.t = t0 + static_cast<double>(k) * dt;
    s = sm.imposed(s);  // at the exact end time of the step
    observer(std::as_const(s));
  }
  return s;
}

}  // namespace gencoord
