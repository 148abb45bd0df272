// SPDX-License-Identifier: BSD-3-Clause
// simulate(): the runtime's fixed-step loop (integrate/simulate.hpp) from Python, with
// scripted coordinates, control inputs and an observer, returning the trajectory as NumPy arrays.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gencoord/control/controlled_system.hpp"
#include "gencoord/control/inputs.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/numerics/cubic_spline.hpp"
#include "gencoord/scripted/model.hpp"
#include "gencoord/scripted/script.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

namespace detail {

// The index that `key` names: a name among `names` (`kind`s of model M, for the error),
// or an index as given; `argument` is the simulate() argument it came in.
template <class M, std::size_t N>
int index_of(py::handle key, const std::array<const char*, N>& names, const char* argument,
             const char* kind) {
  if (!py::isinstance<py::str>(key)) return key.cast<int>();
  const std::string name = py::str(key);
  std::string known;
  for (std::size_t i = 0; i < N; ++i) {
    if (name == names[i]) return static_cast<int>(i);
    known += (i ? ", " : "") + std::string(names[i]);
  }
  throw py::value_error(std::string(argument) + ": " + M::name + " has no " + kind + " '" + name +
                        "'; its " + kind + "s are " + known);
}

// A Python function that C++ copies may hold and drop without the GIL (the Script's and the
// control law's copies are): one shared reference, let go of with the GIL held.
inline std::shared_ptr<py::function> shared_function(py::handle function) {
  return std::shared_ptr<py::function>(
      new py::function(py::reinterpret_borrow<py::function>(function)), [](py::function* f) {
        py::gil_scoped_acquire locked;
        delete f;
      });
}

// A natural cubic spline through keyframes (times, values) given from Python as `what`.
inline std::shared_ptr<CubicSpline> keyframe_spline(py::handle keyframes, const std::string& what) {
  const auto pair = keyframes.cast<py::sequence>();
  if (pair.size() != 2)
    throw py::value_error(what + ": expected a function of t or keyframes (times, values)");
  const Float64Array times = float64_array(pair[0], what + " times", "an array");
  const Float64Array values = float64_array(pair[1], what + " values", "an array");
  return std::make_shared<CubicSpline>(
      CubicSpline::natural(std::vector<double>(times.data(), times.data() + times.size()),
                           std::vector<double>(values.data(), values.data() + values.size())));
}

// One scripted coordinate: (q, v, a) at time t.
using CoordinateMotion = std::function<std::array<double, 3>(double)>;

inline CoordinateMotion coordinate_motion(py::handle motion, const std::string& name) {
  if (PyCallable_Check(motion.ptr())) {
    const std::shared_ptr<py::function> function = shared_function(motion);
    return [function, name](double t) {
      py::gil_scoped_acquire locked;
      const py::object value = (*function)(t);
      const Float64Array qva = float64_array(value, "scripted[" + name + "](t)", "(q, v, a)");
      if (qva.size() != 3)
        throw py::value_error("scripted[" + name + "](t): expected (q, v, a), got " +
                              std::to_string(qva.size()) + " numbers");
      return std::array<double, 3>{qva.data()[0], qva.data()[1], qva.data()[2]};
    };
  }
  const std::shared_ptr<CubicSpline> spline = keyframe_spline(motion, "scripted[" + name + "]");
  return [spline](double t) {
    std::array<double, 3> qva;
    spline->evaluate(t, &qva[0], &qva[1], &qva[2]);
    return qva;
  };
}

/// The Script of `scripted`: {coordinate name or index: function t -> (q, v, a), or
/// keyframes (times, values) through a natural cubic spline}.
template <class M>
Script script_of(py::handle scripted) {
  if (scripted.is_none()) return Script();
  std::vector<int> coordinates;
  std::vector<CoordinateMotion> motions;
  for (const auto& [key, motion] : scripted.cast<py::dict>()) {
    coordinates.push_back(index_of<M>(key, M::coordinate_names, "scripted", "coordinate"));
    motions.push_back(coordinate_motion(motion, std::string(py::str(key))));
  }
  if (coordinates.empty()) return Script();
  return Script::from_function(coordinates, [motions](double t) {
    const auto k = static_cast<Eigen::Index>(motions.size());
    ScriptSample sample{Eigen::VectorXd(k), Eigen::VectorXd(k), Eigen::VectorXd(k)};
    for (Eigen::Index j = 0; j < k; ++j) {
      const std::array<double, 3> qva = motions[static_cast<std::size_t>(j)](t);
      sample.q(j) = qva[0];
      sample.v(j) = qva[1];
      sample.a(j) = qva[2];
    }
    return sample;
  });
}

/// The model with `script`'s coordinates prescribed; a coordinate that cannot be scripted
/// (a free or ball joint's) is a ValueError.
template <class M>
ScriptedModel<M> scripted_model(const ParamsOf<M>& p, Script script) {
  try {
    return ScriptedModel<M>(p, std::move(script));
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    const std::string prefix = "gencoord: ";
    throw py::value_error(
        "scripted: " + (message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message));
  }
}

/// The control law of `inputs`: a function (t, q, v) -> u of shape (num_inputs,), a feedback
/// law; or {input name or index: f(t) -> value, or keyframes (times, values)}, an input
/// script (an input it does not name is 0).
template <class M>
ControlLaw<M> control_law(py::handle inputs, LawKind* kind) {
  constexpr int m = num_inputs_v<M>;
  if (PyCallable_Check(inputs.ptr())) {
    *kind = LawKind::Feedback;
    const std::shared_ptr<py::function> law = shared_function(inputs);
    return [law](double t, const QVec<M>& q, const VVec<M>& v) {
      py::gil_scoped_acquire locked;
      const py::object value = (*law)(t, read_only_array(q), read_only_array(v));
      const Float64Array u = float64_array(value, "inputs(t, q, v)", "an array of the inputs");
      if (u.size() != m)
        throw py::value_error("inputs(t, q, v): expected " + std::to_string(m) +
                              " input values, got " + std::to_string(u.size()));
      return to_vector<InputVec<M>>(u.data());
    };
  }
  if (!py::isinstance<py::dict>(inputs))
    throw py::value_error(
        "inputs: expected a function (t, q, v) -> u or a dict {input: f(t) "
        "or keyframes (times, values)}");
  *kind = LawKind::OpenLoop;
  std::vector<std::pair<int, std::function<double(double)>>> signals;
  for (const auto& [key, signal] : inputs.cast<py::dict>()) {
    const int k = index_of<M>(key, M::input_names, "inputs", "input");
    if (k < 0 || k >= m)
      throw py::value_error("inputs: index " + std::to_string(k) + " is out of range for " +
                            std::to_string(m) + " inputs");
    const std::string what = "inputs[" + std::string(py::str(key)) + "]";
    if (PyCallable_Check(signal.ptr())) {
      const std::shared_ptr<py::function> function = shared_function(signal);
      signals.emplace_back(k, [function, what](double t) {
        py::gil_scoped_acquire locked;
        const Float64Array value = float64_array((*function)(t), what + "(t)", "a number");
        if (value.size() != 1)
          throw py::value_error(what + "(t): expected a number, got " +
                                std::to_string(value.size()) + " values");
        return value.data()[0];
      });
    } else {
      const std::shared_ptr<CubicSpline> spline = keyframe_spline(signal, what);
      signals.emplace_back(k, [spline](double t) {
        double value, rate, acceleration;
        spline->evaluate(t, &value, &rate, &acceleration);
        return value;
      });
    }
  }
  return [signals](double t, const QVec<M>&, const VVec<M>&) {
    InputVec<M> u = InputVec<M>::Zero();
    for (const auto& [k, signal] : signals) u[k] = signal(t);
    return u;
  };
}

// `value` as a vector of `size` entries, or the model file's `initial` values for None
template <class Vector, std::size_t N>
Vector state_vector(py::handle value, const char* name, const std::array<double, N>& initial) {
  if (value.is_none()) return to_vector<Vector>(initial.data());
  return one_vector<Vector>(value, name, static_cast<int>(N));
}

}  // namespace detail

template <class M>
void bind_simulation(py::module_& module) {
  module.def(
      "simulate",
      [](py::handle q0, py::handle v0, double t_end, double dt, const std::string& integrator,
         py::handle params, double t0, py::handle scripted, py::handle inputs, py::handle observer,
         long every, double baumgarte, bool joint_limits) {
        (void)joint_limits;  // used only for a model with joint limits
        if (every < 1)
          throw py::value_error("every: expected at least 1, got " + std::to_string(every));
        State<M> initial;
        initial.t = t0;
        initial.q = detail::state_vector<QVec<M>>(q0, "q0", M::initial_q);
        initial.v = detail::state_vector<VVec<M>>(v0, "v0", M::initial_v);
        const ParamsOf<M> p = params_input<M>(params, -1).at(0);
        const SimulateOptions options{parse_integrator(integrator), dt, t_end - t0};
        const long long steps = step_count(dt, t_end - t0);
        const auto rows = static_cast<py::ssize_t>(steps / every + 1);
        constexpr int nv = nv_of_v<M>;
        py::array_t<double> t({rows}), q({rows, py::ssize_t{M::nq}}), v({rows, py::ssize_t{nv}}),
            energy({rows});
        double *t_out = t.mutable_data(), *q_out = q.mutable_data(), *v_out = v.mutable_data(),
               *e_out = energy.mutable_data();
        py::ssize_t row = 0;
        long long k = 0;
        const bool observed = !observer.is_none();
        py::function observe = observed ? observer.cast<py::function>() : py::function();
        const auto record = [&](const State<M>& s) {
          if (k++ % every) return;
          t_out[row] = s.t;
          e_out[row] = M::energy(s.q, s.v, s.t, p);
          for (int i = 0; i < M::nq; ++i) q_out[row * M::nq + i] = s.q(i);
          for (int i = 0; i < nv; ++i) v_out[row * nv + i] = s.v(i);
          if (observed) {
            py::gil_scoped_acquire locked;
            observe(s.t, read_only_array(s.q), read_only_array(s.v));
          }
          ++row;
        };
        Script script = detail::script_of<M>(scripted);
        if (!(baumgarte >= 0) || !std::isfinite(baumgarte))
          throw py::value_error("baumgarte: expected a rate >= 0 (1/s), got " +
                                std::to_string(baumgarte));
        if constexpr (has_kinematic_constraints_v<M>) {
          if (script.size() != 0 || !inputs.is_none())
            throw py::value_error(
                "scripted, inputs: a model with kinematic constraints takes neither yet; set "
                "constant inputs in its params");
          project_onto_constraints<M>(p, &initial);  // as every step's end state is
          // Baumgarte's feedback, critically damped, replaces the projection after each step
          const ConstraintStabilization stabilization{baumgarte == 0, {baumgarte, baumgarte}};
          ReducedSystem<M> system(p, stabilization);
          if constexpr (has_joint_limits_v<M>) system.set_joint_limits(joint_limits);
          py::gil_scoped_release unlocked;
          simulate(system, initial, options, record);
        } else if (baumgarte > 0) {
          throw py::value_error("baumgarte: " + std::string(M::name) +
                                " has no kinematic constraints to keep");
        } else if (!inputs.is_none()) {
          if constexpr (has_inputs_v<M>) {
            if (script.size() != 0)
              throw py::value_error(
                  "inputs: scripted coordinates and inputs cannot be combined "
                  "in one simulation");
            LawKind kind = LawKind::Feedback;
            ControlLaw<M> law = detail::control_law<M>(inputs, &kind);
            ControlledSystem<M> system(p, std::move(law), kind);
            if constexpr (has_joint_limits_v<M>) system.set_joint_limits(joint_limits);
            py::gil_scoped_release unlocked;
            simulate(system, initial, options, record);
          } else {
            throw py::value_error("inputs: " + std::string(M::name) +
                                  " declares no inputs (model.input() in its model file)");
          }
        } else {
          if (script.size() == 0) {
            ReducedSystem<M> system(p);
            if constexpr (has_joint_limits_v<M>) system.set_joint_limits(joint_limits);
            py::gil_scoped_release unlocked;
            simulate(system, initial, options, record);
          } else {
            const ScriptedModel<M> system = detail::scripted_model<M>(p, std::move(script));
            py::gil_scoped_release unlocked;
            simulate(system, initial, options, record);
          }
        }
        return py::make_tuple(t, q, v, energy);
      },
      "Integrates from (q0, v0) at t0 to t_end with fixed steps dt; returns (t, q, v, energy)\n"
      "as arrays of shapes (K,), (K, nq), (K, nv), (K,) holding every `every`-th state,\n"
      "the first and the last included when every divides the step count.\n"
      "  q0, v0      initial state (default: the model file's initial_q, initial_v)\n"
      "  integrator  one of `integrators` (rk4 default)\n"
      "  scripted    {coordinate name or index: f(t) -> (q, v, a), or keyframes (times,\n"
      "              values) followed through a natural cubic spline}: prescribed\n"
      "              coordinates, driven by whatever force it takes\n"
      "  inputs      the control inputs (models with model.input()): a feedback law\n"
      "              f(t, q, v) -> u, or {input name or index: f(t) -> value, or\n"
      "              keyframes (times, values)}; by default those the params hold\n"
      "  observer    called as observer(t, q, v) at each recorded state\n"
      "  baumgarte   a model with kinematic constraints: 0 (default) projects each step's\n"
      "              end state onto them; a rate > 0 (1/s) applies Baumgarte's feedback,\n"
      "              critically damped, instead\n"
      "  joint_limits  a model with joint limits: True (default) keeps its limited\n"
      "              coordinates in their ranges (an inelastic stop at each end); False\n"
      "              lets them pass; scripted runs do not enforce them\n"
      "A model with kinematic constraints starts from q0, v0 projected onto them and takes\n"
      "neither scripted coordinates nor an inputs argument.\n"
      "Raises DynamicsError, NewtonError, or ValueError for a step that does not divide\n"
      "t_end - t0.",
      py::arg("q0") = py::none(), py::arg("v0") = py::none(), py::arg("t_end") = 10.0,
      py::arg("dt") = 1e-3, py::arg("integrator") = "rk4", py::arg("params") = py::none(),
      py::kw_only(), py::arg("t0") = 0.0, py::arg("scripted") = py::none(),
      py::arg("inputs") = py::none(), py::arg("observer") = py::none(), py::arg("every") = 1,
      py::arg("baumgarte") = 0.0, py::arg("joint_limits") = true);
}

}  // namespace gencoord::python
