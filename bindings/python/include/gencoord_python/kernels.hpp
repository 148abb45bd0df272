// SPDX-License-Identifier: BSD-3-Clause
// The generated kernels as Python functions over NumPy arrays, one state or a batch.
//
// kernel(q, v, ..., t=0.0, params=None, *, threads=None): q has shape (nq,) for one state or
// (N, nq) for a batch of N, v and qdd (nv,) or (N, nv) (nv = nq unless the model has
// generalized speeds); t is a number, or in a batch also an array
// of N times; params is a Params, None for the defaults, or in a batch also a sequence of N;
// a model with control inputs takes u=, which overrides the inputs the params hold.
// A batch returns arrays with a leading dimension N, computed on `threads` threads (default:
// the machine's cores) with the GIL released, each element by exactly the code a single call
// runs, so the results equal single calls bit for bit. A kernel with a lane-parallel form
// (qddot_simd) evaluates a batch kSimdLanes states per call instead, which equals single
// calls to a few ulp, and takes one parameter set and one u for the whole batch.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gencoord/control/inputs.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/parallel/batch.hpp"
#include "gencoord/simd/pack.hpp"
#include "gencoord_python/arrays.hpp"

namespace gencoord::python {

namespace py = pybind11;

/// One vector of shape (size,), not a batch: a state where only one makes sense.
template <class Vector>
Vector one_vector(py::handle value, const std::string& name, int size) {
  const VectorInput input = vector_input(value, name, size);
  if (input.batch >= 0)
    throw py::value_error(name + ": expected one state of shape (" + std::to_string(size) + ",)");
  return to_vector<Vector>(input.row(0));
}

/// One vector of coordinates, shape (nq,).
template <class M>
QVec<M> one_state_vector(py::handle value, const std::string& name) {
  return one_vector<QVec<M>>(value, name, M::nq);
}

/// One vector of speeds (velocities, accelerations), shape (nv,).
template <class M>
VVec<M> one_speed_vector(py::handle value, const std::string& name) {
  return one_vector<VVec<M>>(value, name, nv_of_v<M>);
}

/// The state vectors of one kernel call: the first K of (q, v, qdd) that it takes.
template <class M>
struct StateVectors {
  QVec<M> q;
  VVec<M> v, qdd;
};

/// The parameters of each batch element: one set for all, or one per element.
template <class M>
struct ParamsInput {
  std::vector<ParamsOf<M>> values;
  const ParamsOf<M>& at(py::ssize_t i) const {
    return values.size() == 1 ? values[0] : values[static_cast<std::size_t>(i)];
  }
};

template <class M>
ParamsInput<M> params_input(py::handle value, py::ssize_t batch) {
  using Params = ParamsOf<M>;
  if (value.is_none()) return {{Params{}}};
  if (py::isinstance<Params>(value)) return {{value.cast<Params>()}};
  const std::string expected = std::string("params: expected a ") + M::name + ".Params or None";
  if (batch < 0 || !py::isinstance<py::sequence>(value))
    throw py::value_error(
        expected +
        (batch < 0 ? "" : " or a sequence of N = " + std::to_string(batch) + " of them"));
  const auto sequence = value.cast<py::sequence>();
  if (static_cast<py::ssize_t>(sequence.size()) != batch)
    throw py::value_error("params: a batch of N = " + std::to_string(batch) +
                          " states needs one Params or N of them, got " +
                          std::to_string(sequence.size()));
  ParamsInput<M> input;
  input.values.reserve(sequence.size());
  for (const auto& item : sequence) {
    if (!py::isinstance<Params>(item))
      throw py::value_error(expected + ", got a sequence holding " +
                            std::string(py::str(py::type::of(item))));
    input.values.push_back(item.cast<Params>());
  }
  return input;
}

/// The time of each batch element: one number, or in a batch an array of N.
struct TimeInput {
  Float64Array data;
  bool shared = true;
  double at(py::ssize_t i) const { return data.data()[shared ? 0 : i]; }
};

inline TimeInput time_input(py::handle value, py::ssize_t batch) {
  const std::string expected =
      batch < 0 ? "a number" : "a number or an array of shape (" + std::to_string(batch) + ",)";
  TimeInput input{float64_array(value, "t", expected)};
  require_finite(input.data, "t");
  const py::array& array = input.data;
  if (array.ndim() == 0) return input;
  if (batch >= 0 && array.ndim() == 1 && array.shape(0) == batch) {
    input.shared = false;
    return input;
  }
  std::vector<py::ssize_t> shape(array.shape(), array.shape() + array.ndim());
  throw py::value_error("t: expected " + expected + ", got shape " + shape_text(shape));
}

/// The control inputs of each batch element: None (those the params hold), one vector of
/// shape (num_inputs,) for all, or in a batch one per element, (N, num_inputs); a model with
/// one input also takes a number.
template <class M>
struct InputsInput {
  VectorInput values;
  bool given = false;

  ParamsOf<M> apply(const ParamsOf<M>& p, py::ssize_t i) const {
    return with_inputs<M>(p, to_vector<InputVec<M>>(values.row(i)));
  }
};

template <class M>
InputsInput<M> inputs_input(py::handle value, py::ssize_t batch) {
  if (value.is_none()) return {};
  constexpr int m = num_inputs_v<M>;
  InputsInput<M> input;
  input.given = true;
  if (m == 1 && (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value))) {
    input.values = vector_input(py::make_tuple(value), "u", m);
    return input;
  }
  input.values = vector_input(value, "u", m);
  if (input.values.batch >= 0 && input.values.batch != batch)
    throw py::value_error("u: expected one input vector for every state or one per state (" +
                          (batch < 0 ? std::string("one state") : "N = " + std::to_string(batch)) +
                          "), got N = " + std::to_string(input.values.batch));
  return input;
}

/// Threads for a batch: `threads`, at most the batch's size; refused below 1 and above 64
/// times the machine's hardware threads, where starting them fails (and aborted the process).
inline int thread_count(py::handle threads, py::ssize_t batch) {
  const long wanted = threads.is_none() ? default_batch_threads() : threads.cast<long>();
  const long most = 64L * default_batch_threads();
  if (wanted < 1 || wanted > most)
    throw py::value_error("threads: expected 1 to " + std::to_string(most) + " (64 per hardware " +
                          "thread), got " + std::to_string(wanted));
  if (batch < 2) return 1;
  return static_cast<int>(std::min<py::ssize_t>(wanted, batch));
}

namespace detail {

// What one element's kernel call returns, as a tuple: a kernel with out-parameters returns
// a tuple of them, any other its one value.
template <class Value>
struct AsTuple {
  using Type = std::tuple<Value>;
  static Type of(Value value) { return Type(std::move(value)); }
};
template <class... Values>
struct AsTuple<std::tuple<Values...>> {
  using Type = std::tuple<Values...>;
  static Type of(Type values) { return values; }
};

}  // namespace detail

/// The batch size the first `count` vector arguments agree on (-1 for one state), or
/// ValueError.
inline py::ssize_t common_batch(const std::array<VectorInput, 3>& inputs,
                                const std::array<const char*, 3>& names, std::size_t count) {
  py::ssize_t batch = count ? inputs[0].batch : -1;
  for (std::size_t k = 1; k < count; ++k)
    if (inputs[k].batch != batch)
      throw py::value_error(std::string(names[k]) + ": expected the batch shape of " + names[0] +
                            " (" + (batch < 0 ? "one state" : "N = " + std::to_string(batch)) +
                            "), got " +
                            (inputs[k].batch < 0 ? std::string("one state")
                                                 : "N = " + std::to_string(inputs[k].batch)));
  return batch;
}

/// One kernel as the bindings run it: its evaluation at one state, writing each result
/// row-major to its output, behind a std::function. Every kernel of a model with the same
/// arguments then shares one bound Python function type and one batch loop: pybind11
/// instantiates its whole call machinery for each distinct callable it binds, which made
/// the kernels the largest part of a module's compile time.
template <class M>
struct KernelEntry {
  using Evaluate =
      std::function<void(const StateVectors<M>&, double, const ParamsOf<M>&, double* const*)>;
  /// Its lane-parallel form, where it has one: kLanes states (q[k], v[k], t[k]) in one call,
  /// sharing one parameter set, the one result of state k written to out[k] (NaN or infinite
  /// where the single call's may be); empty otherwise. Plain arrays, as qddot_lanes() takes.
  using EvaluateLanes = std::function<void(const double* const*, const double* const*,
                                           const double*, const ParamsOf<M>&, double* const*)>;
  static constexpr int kLanes = kSimdLanes;

  Evaluate evaluate;
  EvaluateLanes lanes;
  std::vector<std::vector<py::ssize_t>> shapes;  // each result's shape for one state
  std::array<const char*, 3> names{};            // its vector arguments, the first `arity`
  std::size_t arity = 0;
};

namespace detail {

constexpr std::size_t max_kernel_results = 4;

// The one parameter set of a lane-parallel batch: its inputs those of `controls` where given.
template <class M>
ParamsOf<M> lane_params(const ParamsInput<M>& parameters, const InputsInput<M>& controls) {
  if (parameters.values.size() != 1 || (controls.given && controls.values.batch >= 0))
    throw py::value_error(
        "params, u: the lanes of a SIMD batch share one parameter set: pass one Params and one "
        "u for the whole batch, or call the scalar kernel (qddot) for one per state");
  return controls.given ? controls.apply(parameters.values[0], 0) : parameters.values[0];
}

// Elements i .. i + kLanes - 1 in one lane-parallel call, writing rows of `out` (`size`
// entries each); an element whose result is not finite is evaluated again by `evaluate`, the
// single call, so it is NaN exactly where the single call's is.
template <class M, class Evaluate>
void evaluate_lanes(const KernelEntry<M>& kernel, const std::array<VectorInput, 3>& inputs,
                    const TimeInput& times, const ParamsOf<M>& params, py::ssize_t i, double* out,
                    py::ssize_t size, const Evaluate& evaluate) {
  constexpr int lanes = KernelEntry<M>::kLanes;
  std::array<const double*, lanes> q{}, v{};
  std::array<double, lanes> t{};
  std::array<double*, lanes> rows{};
  for (int k = 0; k < lanes; ++k) {
    q[k] = inputs[0].row(i + k);
    v[k] = inputs[1].row(i + k);
    t[k] = times.at(i + k);
    rows[k] = out + (i + k) * size;
  }
  kernel.lanes(q.data(), v.data(), t.data(), params, rows.data());
  for (int k = 0; k < lanes; ++k)
    if (!std::all_of(rows[k], rows[k] + size, [](double x) { return std::isfinite(x); }))
      evaluate(i + k);
}

// kernel(values..., t, params, u, threads) for one state or a batch (see the file comment)
template <class M>
py::object call_kernel(const KernelEntry<M>& kernel, const std::array<py::object, 3>& values,
                       py::object t, py::object params, py::object u, py::object threads) {
  std::array<VectorInput, 3> inputs;
  for (std::size_t k = 0; k < kernel.arity; ++k)
    inputs[k] = vector_input(values[k], kernel.names[k], k == 0 ? M::nq : nv_of_v<M>);
  const py::ssize_t batch = common_batch(inputs, kernel.names, kernel.arity);
  const TimeInput times = time_input(t, batch);
  const ParamsInput<M> parameters = params_input<M>(params, batch);
  const InputsInput<M> controls = inputs_input<M>(u, batch);
  const int workers = thread_count(threads, batch);
  const std::size_t count = kernel.shapes.size();
  const py::ssize_t elements = std::max<py::ssize_t>(batch, 1);
  std::vector<py::array_t<double>> arrays;
  std::array<double*, max_kernel_results> data{};
  std::array<py::ssize_t, max_kernel_results> sizes{};
  for (std::size_t r = 0; r < count; ++r) {
    arrays.push_back(output_array(batch, kernel.shapes[r]));
    data[r] = arrays[r].mutable_data();
    sizes[r] = arrays[r].size() / elements;
  }
  const auto evaluate = [&](py::ssize_t i) {
    StateVectors<M> x;
    if (kernel.arity > 0) x.q = to_vector<QVec<M>>(inputs[0].row(i));
    if (kernel.arity > 1) x.v = to_vector<VVec<M>>(inputs[1].row(i));
    if (kernel.arity > 2) x.qdd = to_vector<VVec<M>>(inputs[2].row(i));
    std::array<double*, max_kernel_results> out{};
    for (std::size_t r = 0; r < count; ++r) out[r] = data[r] + i * sizes[r];
    if (controls.given) {
      kernel.evaluate(x, times.at(i), controls.apply(parameters.at(i), i), out.data());
    } else {
      kernel.evaluate(x, times.at(i), parameters.at(i), out.data());
    }
  };
  if (kernel.lanes && batch >= 0) {
    const ParamsOf<M> shared = lane_params(parameters, controls);
    py::gil_scoped_release unlocked;
    gencoord::detail::parallel_chunks(
        static_cast<std::size_t>(elements), workers, [&](std::size_t begin, std::size_t end) {
          auto i = static_cast<py::ssize_t>(begin);
          for (; i + KernelEntry<M>::kLanes <= static_cast<py::ssize_t>(end);
               i += KernelEntry<M>::kLanes) {
            evaluate_lanes(kernel, inputs, times, shared, i, data[0], sizes[0], evaluate);
          }
          for (; i < static_cast<py::ssize_t>(end); ++i) evaluate(i);
        });
  } else {
    py::gil_scoped_release unlocked;
    gencoord::detail::parallel_chunks(
        static_cast<std::size_t>(elements), workers, [&](std::size_t begin, std::size_t end) {
          for (auto i = static_cast<py::ssize_t>(begin); i < static_cast<py::ssize_t>(end); ++i)
            evaluate(i);
        });
  }
  const auto finish = [batch](py::array_t<double>& array) -> py::object {
    if (batch < 0 && array.ndim() == 0) return py::float_(*array.data());
    return std::move(array);
  };
  if (count == 1) return finish(arrays[0]);
  py::tuple results(count);
  for (std::size_t r = 0; r < count; ++r) results[r] = finish(arrays[r]);
  return results;
}

// Binds `kernel` as module.name(<its vector arguments>..., t=0.0, params=None, *,
// threads=None), with u=None before threads for a model with inputs. Not a template of the
// kernel: one instantiation per model and arity.
template <class M, std::size_t... I>
void def_kernel_entry(py::module_& module, const char* name, const std::string& doc,
                      std::shared_ptr<const KernelEntry<M>> kernel, std::index_sequence<I...>) {
  if constexpr (has_inputs_v<M>) {
    module.def(
        name,
        [kernel](std::conditional_t<true, py::object, decltype(I)>... values, py::object t,
                 py::object params, py::object u, py::object threads) {
          return call_kernel(*kernel, {std::move(values)...}, t, params, u, threads);
        },
        doc.c_str(), py::arg(kernel->names[I])..., py::arg("t") = 0.0,
        py::arg("params") = py::none(), py::kw_only(), py::arg("u") = py::none(),
        py::arg("threads") = py::none());
  } else {
    module.def(
        name,
        [kernel](std::conditional_t<true, py::object, decltype(I)>... values, py::object t,
                 py::object params, py::object threads) {
          return call_kernel(*kernel, {std::move(values)...}, t, params, py::none(), threads);
        },
        doc.c_str(), py::arg(kernel->names[I])..., py::arg("t") = 0.0,
        py::arg("params") = py::none(), py::kw_only(), py::arg("threads") = py::none());
  }
}

// The entry of `kernel`, whose results are Values (a tuple)
template <class M, class Value, class Kernel, std::size_t... R>
KernelEntry<M> kernel_entry(Kernel kernel, std::index_sequence<R...>) {
  using Values = typename AsTuple<Value>::Type;
  static_assert(sizeof...(R) <= max_kernel_results, "def_kernel: too many results");
  KernelEntry<M> entry;
  entry.shapes = {Result<std::tuple_element_t<R, Values>>::shape()...};
  entry.evaluate = [kernel](const StateVectors<M>& x, double t, const ParamsOf<M>& p,
                            double* const* out) {
    const Values values = AsTuple<Value>::of(kernel(x, t, p));
    (Result<std::tuple_element_t<R, Values>>::copy(std::get<R>(values), out[R]), ...);
  };
  return entry;
}

}  // namespace detail

/// Binds `kernel(vectors, t, params)` as module.name(<names>..., t=0.0, params=None, *,
/// threads=None), with u=None before threads for a model with inputs; `kernel` gets the K
/// vectors, which are the first K of (q, v, qdd), as StateVectors<M>, and returns a value
/// (a number, an Eigen vector or matrix, an AsMatrix) or a tuple of them. `lanes`, where
/// given, is its lane-parallel form for (q, v) kernels of one result, which batches use.
template <class M, std::size_t K, class Kernel>
void def_kernel(py::module_& module, const char* name, const std::string& doc,
                const std::array<const char*, K>& names, Kernel kernel,
                typename KernelEntry<M>::EvaluateLanes lanes = {}) {
  static_assert(K <= 3, "def_kernel: a kernel takes q, v and qdd at most");
  using Value = decltype(kernel(std::declval<const StateVectors<M>&>(), 0.0,
                                std::declval<const ParamsOf<M>&>()));
  constexpr std::size_t results = std::tuple_size_v<typename detail::AsTuple<Value>::Type>;
  auto entry = std::make_shared<KernelEntry<M>>(
      detail::kernel_entry<M, Value>(std::move(kernel), std::make_index_sequence<results>{}));
  for (std::size_t k = 0; k < K; ++k) entry->names[k] = names[k];
  entry->arity = K;
  entry->lanes = std::move(lanes);
  detail::def_kernel_entry<M>(module, name, doc, std::shared_ptr<const KernelEntry<M>>(entry),
                              std::make_index_sequence<K>{});
}

}  // namespace gencoord::python
