// SPDX-License-Identifier: BSD-3-Clause
// The model as a first-order system y' = (v, qddot(q, v, t)) with y = (q, v), in the calling
// convention of scipy.integrate.solve_ivp: rhs(t, y) and its exact Jacobian jac(t, y), which
// the implicit methods (Radau, BDF, LSODA) use instead of finite differences.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "gencoord/errors.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

namespace detail {

/// y = (q, v) of shape (2 nq,), split.
template <class M>
void split_state(py::handle y, QVec<M>* q, QVec<M>* v) {
  const VectorInput input = vector_input(y, "y", 2 * M::nq);
  if (input.batch >= 0)
    throw py::value_error("y: expected one state of shape (" + std::to_string(2 * M::nq) +
                          ",); solve_ivp's vectorized=True is not supported");
  *q = to_vector<QVec<M>>(input.row(0));
  *v = to_vector<QVec<M>>(input.row(0) + M::nq);
}

}  // namespace detail

template <class M>
void bind_first_order(py::module_& module) {
  module.def(
      "rhs",
      [](double t, py::handle y, py::handle params) {
        QVec<M> q, v;
        detail::split_state<M>(y, &q, &v);
        const ParamsInput<M> parameters = params_input<M>(params, -1);
        py::array_t<double> ydot(2 * M::nq);
        double* out = ydot.mutable_data();
        {
          py::gil_scoped_release unlocked;
          const QVec<M> a = acceleration<M>(parameters.at(0), q, v, t);
          for (int k = 0; k < M::nq; ++k) {
            out[k] = v(k);
            out[M::nq + k] = a(k);
          }
        }
        return ydot;
      },
      "dy/dt = (v, qddot) at y = (q, v), shape (2 nq,): the fun of scipy.integrate.solve_ivp\n"
      "(pass params with args=(params,)). Raises DynamicsError where Mt is not positive\n"
      "definite or a result is not finite.",
      py::arg("t"), py::arg("y"), py::arg("params") = py::none());
  module.def(
      "jac",
      [](double t, py::handle y, py::handle params) {
        QVec<M> q, v;
        detail::split_state<M>(y, &q, &v);
        const ParamsInput<M> parameters = params_input<M>(params, -1);
        constexpr int n = M::nq;
        py::array_t<double> jacobian({2 * n, 2 * n});
        double* out = jacobian.mutable_data();
        {
          py::gil_scoped_release unlocked;
          QMat<M> a_D_q, a_D_v;
          acceleration_jacobians<M>(parameters.at(0), q, v, t, &a_D_q, &a_D_v,
                                    JacobianSource::Auto);
          // row-major [[0, I], [da/dq, da/dv]]
          for (int r = 0; r < n; ++r)
            for (int c = 0; c < 2 * n; ++c) {
              out[r * 2 * n + c] = c == n + r ? 1.0 : 0.0;
              out[(n + r) * 2 * n + c] = c < n ? a_D_q(r, c) : a_D_v(r, c - n);
            }
        }
        return jacobian;
      },
      "d(rhs)/dy, shape (2 nq, 2 nq): [[0, I], [da/dq, da/dv]] from the generated residual\n"
      "Jacobians (da/dq = -Mt^-1 dr/dq, da/dv = -Mt^-1 dr/dv): the jac of solve_ivp. A model\n"
      "with kinematic constraints takes central differences of its constrained acceleration.",
      py::arg("t"), py::arg("y"), py::arg("params") = py::none());
}

}  // namespace gencoord::python
