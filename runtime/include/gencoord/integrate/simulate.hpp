// SPDX-License-Identifier: BSD-3-Clause
// The fixed-step simulation loop, for any system.
#pragma once

#include <type_traits>
#include <utility>

#include "gencoord/errors.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/newton.hpp"
#include "gencoord/integrate/step.hpp"

namespace gencoord {

/// Number of fixed steps of size dt in `duration`: llround(duration / dt).
/// \throws StepSizeError if dt is not positive and finite, duration is negative or not finite,
///         or duration is not a whole number of steps (|n dt - duration| > 1e-6 dt), so a run
///         never stops silently short of or past the requested end.
long long step_count(double dt, double duration);

/// How simulate() runs. The constructor lets a call spell the leading options in braces,
/// {Integrator::RK4, dt, duration}, and leave the rest at their defaults.
struct SimulateOptions {
  SimulateOptions(Integrator integrator = Integrator::RK4, double dt = 1e-3, double duration = 0.0,
                  const NewtonOptions& newton = {}, StepStats* stats = nullptr)
      : integrator(integrator), dt(dt), duration(duration), newton(newton), stats(stats) {}

  Integrator integrator;
  double dt;             // step size (s)
  double duration;       // simulated time (s), a whole number of steps
  NewtonOptions newton;  // implicit integrators only
  StepStats* stats;      // work counters, incremented; may be null
};

/// An observer that ignores every state.
struct IgnoreStates {
  template <class State>
  void operator()(const State&) const {}
};

namespace detail {
// Calls observer(s); true when the observer returns a bool and it is true (stop the run).
template <class Observer, class State>
bool observe(Observer& observer, const State& s) {
  if constexpr (std::is_same_v<decltype(observer(s)), bool>) {
    return observer(s);
  } else {
    observer(s);
    return false;
  }
}
}  // namespace detail

/// Integrates `system` from `initial` with step_count(options.dt, options.duration) fixed steps.
/// observer(state) is called with the initial state and after every step (num + 1 calls); an
/// observer that returns bool ends the run early by returning true (an event), and the state
/// it was given is the one returned. Step k ends at exactly initial.t + k dt (times are not
/// accumulated, so they do not drift).
/// Prescribed entries (S::impose()) are set at every observed state. The observer is a
/// template parameter, not part of the options, so that its calls are resolved at compile
/// time.
/// \param[in] system    The system (integrate/system.hpp).
/// \param[in] initial   The initial state.
/// \param[in] options   Integrator, step size, duration, Newton settings, work counters.
/// \param[in] observer  Callable as observer(const S::State&), e.g. a TrajectoryCsvWriter;
///                      returning void, or bool: true stops the run.
/// \return The final state.
/// \throws StepSizeError (see step_count()); what step() throws; std::invalid_argument for an
///         integrator outside Methods (the integrators compiled: step.hpp's IntegratorSet).
template <class Methods = AllIntegrators, class S, class Observer = IgnoreStates>
typename S::State simulate(const S& system, typename S::State initial,
                           const SimulateOptions& options, Observer&& observer = {}) {
  const long long num = step_count(options.dt, options.duration);
  const double t0 = initial.t;
  typename S::State s = std::move(initial);
  system.impose(&s);
  if (detail::observe(observer, std::as_const(s))) return s;
  for (long long k = 1; k <= num; ++k) {
    s = step<Methods>(system, options.integrator, s, options.dt, options.newton, options.stats);
    s.t = t0 + static_cast<double>(k) * options.dt;
    system.impose(&s);  // at the exact end time of the step
    if (detail::observe(observer, std::as_const(s))) break;
  }
  return s;
}

}  // namespace gencoord
