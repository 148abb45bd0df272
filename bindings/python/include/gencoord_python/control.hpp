// SPDX-License-Identifier: BSD-3-Clause
// linearize(): the model's dynamics linearized about a state and an input
// (gencoord/control/linearize.hpp), and dynamics_derivatives() (model/dynamics_derivatives.hpp),
// as NumPy arrays for controller design and trajectory optimization.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <string>
#include <tuple>

#include "gencoord/control/inputs.hpp"
#include "gencoord/control/linearize.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/dynamics_derivatives.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

template <class M>
void bind_control(py::module_& module) {
  const std::array<const char*, 2> qv{"q", "v"};
  def_kernel<M>(
      module, "dynamics_derivatives",
      "The forward dynamics' derivatives for control, with a generalized force tau on every\n"
      "speed (Mt a = Ft + Fi + tau): returns (a, da_dq, da_dv, da_dtau) of shapes (nv,),\n"
      "(nv, nq), (nv, nv), (nv, nv), da_dtau = Mt^-1; da/dq and da/dv from the generated\n"
      "residual Jacobians (a tree's: Newton-Euler's, differentiated) and one Cholesky factor\n"
      "of Mt. With a batch of N states, one tuple of arrays with a leading dimension N.\n"
      "Raises DynamicsError where Mt is not positive definite.",
      qv, [](const StateVectors<M>& x, double t, const ParamsOf<M>& p) {
        DynamicsDerivatives<M> d = dynamics_derivatives<M>(p, x.q, x.v, t);
        return std::make_tuple(d.a, d.a_D_q, d.a_D_v, d.a_D_tau);
      });
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
