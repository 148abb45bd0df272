// SPDX-License-Identifier: BSD-3-Clause
// linearize(): the model's dynamics linearized about a state and an input
// (gencoord/control/linearize.hpp), as NumPy arrays for controller design.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "gencoord/control/inputs.hpp"
#include "gencoord/control/linearize.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

template <class M>
void bind_control(py::module_& module) {
  module.def(
      "linearize",
      [](py::handle q, py::handle v, py::handle u, double t, py::handle params,
         const std::string& method) {
        const QVec<M> q0 = one_state_vector<M>(q, "q");
        const VVec<M> v0 = one_speed_vector<M>(v, "v");
        const ParamsOf<M> p = params_input<M>(params, -1).at(0);
        const InputsInput<M> controls = inputs_input<M>(u, -1);
        const InputVec<M> u0 =
            controls.given ? to_vector<InputVec<M>>(controls.values.row(0)) : inputs_of<M>(p);
        JacobianSource source = JacobianSource::Generated;
        if (method == "finite_difference") source = JacobianSource::FiniteDifference;
        else if (method != "generated")
          throw py::value_error("method: expected 'generated' or 'finite_difference', got '" +
                                method + "'");
        LinearizedDynamics linear;
        {
          py::gil_scoped_release unlocked;
          linear = linearize<M>(p, q0, v0, u0, t, source);
        }
        return py::make_tuple(matrix_array(linear.A), matrix_array(linear.B));
      },
      "Linearization of x' = f(x, u, t), x = (q, v), at (q, v, u, t): returns (A, B) with\n"
      "A = df/dx of shape (2 nq, 2 nq) and B = df/du of shape (2 nq, num_inputs).\n"
      "qddot's rows come from the generated Jacobians: -Mt^-1 dr/dq, -Mt^-1 dr/dv and\n"
      "Mt^-1 B(q), exact to round-off; method='finite_difference' takes central differences\n"
      "instead. u defaults to the inputs the params hold (0 unless set).\n"
      "With generalized speeds x = (delta, v), 2 nv entries, where q = retract(q, delta)\n"
      "names the configurations near q (local_coordinates(q, q_other) gives delta back).\n"
      "Raises DynamicsError where Mt is singular.",
      py::arg("q"), py::arg("v"), py::arg("u") = py::none(), py::arg("t") = 0.0,
      py::arg("params") = py::none(), py::kw_only(), py::arg("method") = "generated");
}

}  // namespace gencoord::python
