// SPDX-License-Identifier: BSD-3-Clause
// One sample of a sweep: its parameters and initial state from the table's row, integrated
// with fixed steps to t_end or to the event, its failure (if any) recorded instead of thrown.
// Every sample is computed by this code alone, whichever rank and thread runs it, so the
// results do not depend on how the sweep is spread.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "gencoord/gencoord.hpp"
#include "sweep/results.hpp"
#include "sweep/table.hpp"

namespace gencoord::sweep {

/// The table's settings resolved against the model M: what every sample shares.
template <class M>
struct Plan {
  enum class Kind { kQ, kV, kParameter, kEnergy };
  struct Setter {  // a column: sets q[index], v[index] or the parameter `name`
    Kind kind;
    int index;
    std::string name;
  };
  struct Check {  // an event clause
    Kind kind;
    int index;
    bool absolute;
    std::string op;
    double value;
  };
  ParamsOf<M> params;  // the model's defaults and the table's fixed values
  State<M> initial;    // the model's initial state and the table's initial values
  std::vector<Setter> setters;
  std::vector<Check> checks;
  Integrator integrator = Integrator::RK4;
  double dt = 0.0;
  double duration = 0.0;  // steps x dt: simulate() runs that many fixed steps
  long long every = 0;
  bool stop_at_event = true, need_energy = false;
  Layout layout;
};

namespace detail {

template <class M>
int coordinate_index(const Table& table, const std::string& name) {
  for (int i = 0; i < M::nq; ++i)
    if (name == M::coordinate_names[static_cast<std::size_t>(i)]) return i;
  throw TableError(table.path + ": model " + M::name + " has no coordinate '" + name + "'");
}

/// The names of v's entries: a model's generalized speeds, or its coordinates where v = q'.
template <class M>
std::vector<std::string> speed_names() {
  if constexpr (has_generalized_speeds_v<M>) return {M::speed_names.begin(), M::speed_names.end()};
  else return {M::coordinate_names.begin(), M::coordinate_names.end()};
}

template <class M>
int speed_index(const Table& table, const std::string& name) {
  const std::vector<std::string> names = speed_names<M>();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (name == names[i]) return static_cast<int>(i);
  throw TableError(table.path + ": model " + M::name + " has no speed '" + name + "'");
}

// the index of a q or v entry called `name`
template <class M>
int state_index(const Table& table, typename Plan<M>::Kind kind, const std::string& name) {
  return kind == Plan<M>::Kind::kV ? speed_index<M>(table, name) : coordinate_index<M>(table, name);
}

template <class M>
typename Plan<M>::Kind kind_of(const Table& table, const std::string& kind) {
  using Kind = typename Plan<M>::Kind;
  if (kind == "q") return Kind::kQ;
  if (kind == "v") return Kind::kV;
  if (kind == "parameters") return Kind::kParameter;
  if (kind == "energy") return Kind::kEnergy;
  throw TableError(table.path + ": unknown quantity '" + kind + "'");
}

inline bool compare(double x, const std::string& op, double value) {
  if (op == ">") return x > value;
  if (op == ">=") return x >= value;
  if (op == "<") return x < value;
  return x <= value;
}

}  // namespace detail

/// The plan of `table` for model M. \throws TableError for a name the model lacks.
template <class M>
Plan<M> make_plan(const Table& table) {
  using Kind = typename Plan<M>::Kind;
  Plan<M> plan;
  auto parameter = [&](ParamsOf<M>& p, const std::string& name) {
    double* slot = p.find(name);
    if (!slot)
      throw TableError(table.path + ": model " + M::name + " has no parameter '" + name + "'");
    return slot;
  };
  for (const auto& [name, value] : table.parameters) *parameter(plan.params, name) = value;
  for (int i = 0; i < M::nq; ++i) plan.initial.q[i] = M::initial_q[static_cast<std::size_t>(i)];
  for (int i = 0; i < nv_of_v<M>; ++i)
    plan.initial.v[i] = M::initial_v[static_cast<std::size_t>(i)];
  for (const auto& initial : table.initial) {
    if (initial.kind == "q")
      plan.initial.q[detail::coordinate_index<M>(table, initial.name)] = initial.value;
    else plan.initial.v[detail::speed_index<M>(table, initial.name)] = initial.value;
  }
  for (const Column& column : table.columns) {
    const Kind kind = detail::kind_of<M>(table, column.kind);
    if (kind == Kind::kParameter) {
      ParamsOf<M> probe;
      parameter(probe, column.name);
      plan.setters.push_back({kind, -1, column.name});
    } else {
      plan.setters.push_back({kind, detail::state_index<M>(table, kind, column.name), ""});
    }
  }
  for (const EventClause& clause : table.clauses) {
    const Kind kind = detail::kind_of<M>(table, clause.kind);
    const int index =
        kind == Kind::kEnergy ? -1 : detail::state_index<M>(table, kind, clause.coordinate);
    plan.checks.push_back({kind, index, clause.absolute, clause.op, clause.value});
    plan.need_energy = plan.need_energy || kind == Kind::kEnergy;
  }
  plan.integrator = parse_integrator(table.integrator);
  plan.dt = table.dt;
  plan.duration = static_cast<double>(table.steps) * table.dt;
  plan.every = table.trajectory_every;
  plan.stop_at_event = table.event_stop;
  plan.need_energy = plan.need_energy || table.record_energy_drift;
  plan.layout = {M::nq,
                 nv_of_v<M>,
                 table.trajectory_points(),
                 table.record_final_state,
                 table.record_energy_drift,
                 table.record_event_time};
  return plan;
}

namespace detail {

template <class M>
bool event_happens(const Plan<M>& plan, const State<M>& s, double energy) {
  using Kind = typename Plan<M>::Kind;
  for (const auto& check : plan.checks) {
    double x = check.kind == Kind::kQ   ? s.q[check.index]
               : check.kind == Kind::kV ? s.v[check.index]
                                        : energy;
    if (check.absolute) x = std::abs(x);
    if (compare(x, check.op, check.value)) return true;
  }
  return false;
}

inline std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[kErrorLength];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// "at q = (0.5, -1.2)", cut short with "...)" to fit an error text
inline std::string configuration(const std::vector<double>& q) {
  std::string text = "at q = (";
  for (std::size_t i = 0; i < q.size(); ++i) {
    char number[32];
    std::snprintf(number, sizeof number, "%s%.6g", i == 0 ? "" : ", ", q[i]);
    // room for this number and ")", else for "...)"
    if (text.size() + std::strlen(number) + 4 > kErrorLength - 1) return text + "...)";
    text += number;
  }
  return text + ")";
}

}  // namespace detail

/// Runs sample `i` of a chunk (its values `row`) and stores its results at index i of `out`.
/// A failure of the dynamics ends the sample: its status, time and text are recorded, and the
/// final state is the last one reached.
template <class M>
void run_sample(const Plan<M>& plan, const double* row, long long i, ChunkResults* out) {
  using Kind = typename Plan<M>::Kind;
  ParamsOf<M> p = plan.params;
  State<M> s = plan.initial;
  for (std::size_t k = 0; k < plan.setters.size(); ++k) {
    const auto& setter = plan.setters[k];
    if (setter.kind == Kind::kQ) s.q[setter.index] = row[k];
    else if (setter.kind == Kind::kV) s.v[setter.index] = row[k];
    else *p.find(setter.name) = row[k];
  }
  // the table's values may leave the model's manifold: a constrained model starts on its
  // constraints and is projected back after every step, and a unit quaternion whose
  // components the table set one by one starts normalized (normalize() does both)
  const ReducedSystem<M> system(p);
  if constexpr (has_generalized_speeds_v<M>) normalize(system, &s);
  else if constexpr (has_kinematic_constraints_v<M>) project_onto_constraints<M>(p, &s);
  const auto n = static_cast<std::size_t>(i);
  const auto nq = static_cast<std::size_t>(M::nq);
  const auto nv = static_cast<std::size_t>(nv_of_v<M>);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double e0 = nan, drift = 0.0, event_time = nan;
  long long k = 0;  // the step whose state is observed
  // energy, trajectory and event at step k's state, which it keeps as the last state reached
  // (a failing step throws before it is observed); true when the sample stops there
  auto observe = [&](const State<M>& x) {
    s = x;
    double energy = nan;
    if (plan.need_energy) {
      energy = M::energy(x.q, x.v, x.t, p);
      if (k == 0) e0 = energy;
      const double change = std::abs(energy - e0);
      if (std::isnan(change) || change > drift) drift = change;  // a NaN energy stays NaN
    }
    if (plan.every > 0 && k % plan.every == 0) {
      const std::size_t at = n * static_cast<std::size_t>(plan.layout.trajectory_points) +
                             static_cast<std::size_t>(k / plan.every);
      for (std::size_t j = 0; j < nq; ++j)
        out->trajectory_q[at * nq + j] = x.q[static_cast<Eigen::Index>(j)];
      for (std::size_t j = 0; j < nv; ++j)
        out->trajectory_v[at * nv + j] = x.v[static_cast<Eigen::Index>(j)];
    }
    ++k;
    if (plan.checks.empty() || !std::isnan(event_time)) return false;
    if (!detail::event_happens(plan, x, energy)) return false;
    event_time = x.t;
    return plan.stop_at_event;
  };
  Status status = Status::kOk;
  std::string error;
  double error_time = nan;
  try {
    simulate(system, s, SimulateOptions{plan.integrator, plan.dt, plan.duration}, observe);
  } catch (const DynamicsError& e) {
    using Reason = DynamicsError::Reason;
    status = e.reason() == Reason::kNotPositiveDefinite    ? Status::kNotPositiveDefinite
             : e.reason() == Reason::kNonFiniteMassMatrix  ? Status::kMassMatrixNotFinite
             : e.reason() == Reason::kNonFiniteForces      ? Status::kForcesNotFinite
             : e.reason() == Reason::kDependentConstraints ? Status::kDependentConstraints
             : e.reason() == Reason::kNonFiniteConstraints ? Status::kConstraintsNotFinite
                                                           : Status::kAccelerationNotFinite;
    error_time = e.time();
    error = detail::configuration(e.q());  // the status says what failed
  } catch (const NewtonError& e) {
    status = Status::kNewtonFailed;
    error_time = e.time();
    error = detail::format("Newton: %.0f iterations, |dv| %.3g, |g|/scale %.3g", e.iterations(),
                           e.update_norm(), e.scaled_residual());
  } catch (const DivergedError& e) {
    status = Status::kDiverged;
    error_time = e.time();
    error = detail::format("state not finite after a step of %g s", e.step_size());
  } catch (const std::exception& e) {
    status = Status::kOtherError;
    error_time = s.t;
    error = e.what();
  }
  out->status[n] = static_cast<std::int8_t>(status);
  out->error_time[n] = error_time;
  out->set_error(i, error);
  if (plan.layout.final_state) {
    out->final_t[n] = s.t;
    for (std::size_t j = 0; j < nq; ++j)
      out->final_q[n * nq + j] = s.q[static_cast<Eigen::Index>(j)];
    for (std::size_t j = 0; j < nv; ++j)
      out->final_v[n * nv + j] = s.v[static_cast<Eigen::Index>(j)];
  }
  if (plan.layout.energy_drift) out->energy_drift[n] = drift;
  if (plan.layout.event_time) out->event_time[n] = event_time;
}

}  // namespace gencoord::sweep
