// Fixed-step simulation loop.
#pragma once

#include <utility>

#include "gencoord/errors.hpp"
#include "gencoord/integrators.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

/// Number of fixed steps of size dt in `duration`: llround(duration / dt).
/// \throws StepSizeError if dt is not positive and finite, duration is negative or not finite,
///         or duration is not a whole number of steps (|n dt - duration| > 1e-6 dt), so a run
///         never stops silently short of or past the requested end.
long long step_count(double dt, double duration);

/// Integrates from `initial` with `num = step_count(dt, duration)` fixed steps of size dt.
/// observer(state) is called with the initial state and after every step (num + 1 calls);
/// step k ends at exactly initial.t + k dt (times are not accumulated, so they do not drift).
/// \param[in]     p         The model parameters.
/// \param[in]     initial   The initial state (q, v of dim M::nq).
/// \param[in]     integrator  Which integrator.
/// \param[in]     dt        The step size.
/// \param[in]     duration  The simulated time; the run ends at initial.t + duration.
/// \param[in]     observer  Callable as observer(const State<M>&), e.g. a TrajectoryCsvWriter.
/// \param[in]     newton    Newton settings (implicit integrators only).
/// \param[in,out] stats     Work counters, incremented; may be null.
/// \return The final state.
/// \throws StepSizeError (see step_count()); DynamicsError, NewtonError from step().
template <class M, class Observer>
State<M> simulate(const ParamsOf<M>& p, State<M> initial, Integrator integrator, double dt,
                  double duration, Observer&& observer, const NewtonOptions& newton = {},
                  StepStats* stats = nullptr) {
  static_assert(assert_model_v<M>);
  const long long num = step_count(dt, duration);
  const double t0 = initial.t;
  State<M> s = std::move(initial);
  observer(std::as_const(s));
  for (long long k = 1; k <= num; ++k) {
    s = step<M>(integrator, p, s, dt, newton, stats);
    s.t = t0 + static_cast<double>(k) * dt;
    observer(std::as_const(s));
  }
  return s;
}

}  // namespace gencoord
