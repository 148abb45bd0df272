// SPDX-License-Identifier: BSD-3-Clause
// The maximal-coordinate cross-check: run the reduced model (RK4, small fixed step) as the
// reference, run the maximal penalty model from the same consistent initial state for each
// penalty stiffness kappa, and compare particle positions at common sample times. As
// kappa -> infinity the maximal trajectory converges to the reduced one, the error shrinking
// roughly like 1/kappa (docs/crosscheck.md).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/maximal/model.hpp"
#include "gencoord/maximal/stability.hpp"
#include "gencoord/maximal/state.hpp"
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/numerics/loglog_fit.hpp"

namespace gencoord {

/// The maximal model's integrators a cross-check compiles and runs (CrosscheckOptions::
/// integrator): the explicit ones at their stability limits, and backward Euler.
using CrosscheckIntegrators =
    IntegratorSet<Integrator::SymplecticEuler, Integrator::RK4, Integrator::BackwardEuler>;

/// Settings of a cross-check run.
struct CrosscheckOptions {
  double duration = 5.0;       // simulated time (s)
  int points = 100;            // sample intervals: positions compared at points + 1 times
  double reference_dt = 1e-4;  // reduced RK4 step, at most (rounded down to divide the interval)
  Integrator integrator = Integrator::RK4;  // of the maximal model: CrosscheckIntegrators
  double safety = 0.9;                      // maximal step <= safety * explicit stability limit
  double max_dt = 1e-4;             // maximal step <= max_dt (accuracy), whatever the stability
  double penalty_damping = 0;       // damping of the penalty springs
  NewtonOptions newton{1e-10, 30};  // backward Euler's Newton settings
};

/// The reduced reference run, sampled.
template <class M>
struct ReducedReference {
  std::vector<State<M>> samples;          // reduced states at the sample times
  double max_constraint_violation = 0.0;  // max |C(X(q))| over every step (declared constraints)
  double reference_dt = 0.0;              // the step used
  long long steps = 0;
  double wall_seconds = 0.0;
};

/// One row of the cross-check: the maximal model at one kappa against the reference.
struct CrosscheckRow {
  double kappa = 0;
  double omega_max = 0;  // stiffest mode along the reference (rad/s)
  double dt = 0;         // maximal step used
  long long steps = 0;
  double max_position_error = 0;        // max over samples and particles of |x_i - X_i(q_ref)|
  double energy_drift = 0;              // max over samples of |E - E(0)| of the maximal run
  double max_constraint_violation = 0;  // max over samples (MaximalModel::max_constraint_violation)
  double wall_seconds = 0;              // the maximal run (integration and sampling)
};

/// Sample interval duration / points. \throws std::invalid_argument for bad options.
inline double sample_interval(const CrosscheckOptions& o) {
  if (!(o.duration > 0) || o.points < 1 || !(o.reference_dt > 0) || !(o.max_dt > 0) ||
      !(o.safety > 0))
    throw std::invalid_argument(
        "gencoord: cross-check needs duration > 0, points >= 1, reference_dt > 0, "
        "max_dt > 0, safety > 0");
  return o.duration / o.points;
}

/// The largest step <= limit that divides `interval` a whole number of times.
inline double divisor_step(double interval, double limit) {
  const double n = std::max(1.0, std::ceil(interval / limit * (1.0 - 1e-12)));
  return interval / n;
}

/// Runs the reduced model with RK4 from `initial` and samples it every duration / points.
/// Also records the largest declared-constraint violation of X(q) over every step. A model
/// with kinematic constraints starts from `initial` projected onto them and is kept on them
/// after every step (ReducedSystem's projection). Joint limits are left out, as the maximal
/// model has none.
/// \throws std::invalid_argument for bad options; DynamicsError from the reduced dynamics.
template <class M>
ReducedReference<M> reduced_reference(const ParamsOf<M>& p, const State<M>& initial,
                                      const CrosscheckOptions& o) {
  const double interval = sample_interval(o);
  ReducedReference<M> ref;
  ref.reference_dt = divisor_step(interval, o.reference_dt);
  const long long per_sample = std::llround(interval / ref.reference_dt);
  const auto start = std::chrono::steady_clock::now();
  auto violation = [&](const State<M>& s) {
    if constexpr (MaximalOf<M>::num_constraints > 0)
      ref.max_constraint_violation =
          std::max(ref.max_constraint_violation,
                   MaximalOf<M>::constraint_violations(M::positions(s.q, s.t, p), s.t, p)
                       .cwiseAbs()
                       .maxCoeff());
  };
  State<M> start_state = initial;
  if constexpr (has_kinematic_constraints_v<M>) project_onto_constraints<M>(p, &start_state);
  ReducedSystem<M> system(p);
  if constexpr (has_joint_limits_v<M>) system.set_joint_limits(false);
  long long k = 0;  // states observed
  simulate<IntegratorSet<Integrator::RK4>>(
      system, start_state, SimulateOptions{Integrator::RK4, ref.reference_dt, interval * o.points},
      [&](const State<M>& s) {
        violation(s);
        if (k++ % per_sample == 0) ref.samples.push_back(s);
      });
  ref.steps = k - 1;
  ref.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return ref;
}

/// The stiffest mode's frequency of the maximal model, maximized over the reference samples
/// (the maximal trajectory stays near them): sets an explicit step that stays stable along
/// the motion. \throws InverseMapError as omega_max().
template <class M>
double omega_max_along(const MaximalModel<M>& model, const ReducedReference<M>& ref) {
  double omega = 0.0;
  for (const State<M>& s : ref.samples)
    omega = std::max(omega, omega_max(model, to_maximal<M>(model.params(), s)));
  return omega;
}

/// The default sample observer of crosscheck_at(): nothing.
struct IgnoreSamples {
  template <class Reduced, class Maximal>
  void operator()(const Reduced&, const Maximal&) const {}
};

/// The maximal model at one kappa against the reference: consistent initial state
/// (x = X(q0), xdot = J v0 + X_t), step = the largest divisor of the sample interval below
/// both the stability limit (safety times, with omega_max_along()) and o.max_dt.
/// `on_sample(reduced, maximal)` sees both states at every sample time (a side-by-side
/// trajectory). `Integrators`, the set compiled, may be narrowed to o.integrator alone: each
/// integrator instantiated on a model costs compile time.
/// \throws MaximalDivergedError, InverseMapError, NewtonError from the run;
///         std::invalid_argument for an integrator outside Integrators.
template <class M, class Integrators = CrosscheckIntegrators, class SampleObserver = IgnoreSamples>
CrosscheckRow crosscheck_at(const ParamsOf<M>& p, const ReducedReference<M>& ref, double kappa,
                            const CrosscheckOptions& o, SampleObserver&& on_sample = {}) {
  const double interval = sample_interval(o);
  const MaximalModel<M> model(p, kappa, o.penalty_damping, ref.samples.front().q);
  CrosscheckRow row;
  row.kappa = kappa;
  row.omega_max = omega_max_along(model, ref);
  row.dt = divisor_step(interval,
                        std::min(o.max_dt, stable_step(o.integrator, row.omega_max, o.safety)));
  const long long per_sample = std::llround(interval / row.dt);
  const MaximalState<M> initial = to_maximal<M>(p, ref.samples.front());
  const double e0 = model.energy(initial);
  long long k = 0;
  const auto start = std::chrono::steady_clock::now();
  const SimulateOptions run{o.integrator, row.dt, interval * o.points, o.newton};
  simulate<Integrators>(model, initial, run, [&](const MaximalState<M>& s) {
    if (k++ % per_sample != 0) return;
    const State<M>& r = ref.samples[static_cast<std::size_t>((k - 1) / per_sample)];
    on_sample(r, s);
    row.max_position_error =
        std::max(row.max_position_error, max_particle_distance<M>(s.q, M::positions(r.q, r.t, p)));
    row.energy_drift = std::max(row.energy_drift, std::abs(model.energy(s) - e0));
    row.max_constraint_violation =
        std::max(row.max_constraint_violation, model.max_constraint_violation(s.q, s.t));
  });
  row.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.steps = k - 1;
  return row;
}

/// `count` log-spaced values from lo to hi (both included; lo alone if count == 1).
inline std::vector<double> log_spaced(double lo, double hi, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i)
    out.push_back(count == 1 ? lo
                             : std::pow(10.0, std::log10(lo) + (std::log10(hi) - std::log10(lo)) *
                                                                   i / (count - 1)));
  return out;
}

/// The error slope against kappa a cross-check of M expects at least: -0.8 (1/kappa, with
/// room), or -0.4 with velocity constraints, whose maximal form is a viscous penalty of
/// coefficient sqrt(kappa m) and converges like kappa^-1/2.
template <class M>
constexpr double expected_error_slope() {
  return has_velocity_constraints_v<M> ? -0.4 : -0.8;
}

/// Whether the maximal model of M is the reduced one in other coordinates (no declared
/// constraints, nv == nx): its error does not depend on kappa and sits at the integration floor.
template <class M>
inline constexpr bool kappa_independent_v =
    MaximalOf<M>::num_constraints == 0 && nv_of_v<M> == M::nx;

}  // namespace gencoord
