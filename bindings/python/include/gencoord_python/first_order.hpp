// SPDX-License-Identifier: BSD-3-Clause
// The model as a first-order system y' = (v, qddot(q, v, t)) with y = (q, v), in the calling
// convention of scipy.integrate.solve_ivp: rhs(t, y) and its exact Jacobian jac(t, y), which
// the implicit methods (Radau, BDF, LSODA) use instead of finite differences. With generalized
// speeds y = (q, v) has nq + nv entries and y' = (G(q) v, v'): solve_ivp then integrates the
// quaternions' entries as they are, which keeps their norm to the method's tolerance only
// (simulate() puts them back on the sphere after each step).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "gencoord/errors.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/tangent_space.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

namespace detail {

/// y = (q, v) of shape (nq + nv,), split.
template <class M>
void split_state(py::handle y, QVec<M>* q, VVec<M>* v) {
  constexpr int size = M::nq + nv_of_v<M>;
  const VectorInput input = vector_input(y, "y", size);
  if (input.batch >= 0)
    throw py::value_error("y: expected one state of shape (" + std::to_string(size) +
                          ",); solve_ivp's vectorized=True is not supported");
  *q = to_vector<QVec<M>>(input.row(0));
  *v = to_vector<VVec<M>>(input.row(0) + M::nq);
}

}  // namespace detail

template <class M>
void bind_first_order(py::module_& module) {
  constexpr int nq = M::nq, nv = nv_of_v<M>;
  module.def(
      "rhs",
      [](double t, py::handle y, py::handle params) {
        QVec<M> q;
        VVec<M> v;
        detail::split_state<M>(y, &q, &v);
        const ParamsInput<M> parameters = params_input<M>(params, -1);
        py::array_t<double> ydot(nq + nv);
        double* out = ydot.mutable_data();
        {
          py::gil_scoped_release unlocked;
          const ParamsOf<M>& p = parameters.at(0);
          const VVec<M> a = acceleration<M>(p, q, v, t);
          if constexpr (has_generalized_speeds_v<M>) {
            const QVec<M> rates = M::coordinate_rates(q, v, t, p);
            for (int k = 0; k < nq; ++k) out[k] = rates(k);
          } else {
            for (int k = 0; k < nq; ++k) out[k] = v(k);
          }
          for (int k = 0; k < nv; ++k) out[nq + k] = a(k);
        }
        return ydot;
      },
      "dy/dt = (q', v') at y = (q, v), shape (nq + nv,), q' = v (or G(q) v with generalized\n"
      "speeds): the fun of scipy.integrate.solve_ivp (pass params with args=(params,)).\n"
      "Raises DynamicsError where Mt is not positive definite or a result is not finite.",
      py::arg("t"), py::arg("y"), py::arg("params") = py::none());
  module.def(
      "jac",
      [](double t, py::handle y, py::handle params) {
        QVec<M> q;
        VVec<M> v;
        detail::split_state<M>(y, &q, &v);
        const ParamsInput<M> parameters = params_input<M>(params, -1);
        constexpr int n = nq + nv;
        py::array_t<double> jacobian({n, n});
        double* out = jacobian.mutable_data();
        {
          py::gil_scoped_release unlocked;
          const ParamsOf<M>& p = parameters.at(0);
          VQMat<M> a_D_q;
          VMat<M> a_D_v;
          acceleration_jacobians<M>(p, q, v, t, &a_D_q, &a_D_v, JacobianSource::Auto);
          // row-major [[dq'/dq, dq'/dv], [da/dq, da/dv]]
          Eigen::MatrixXd rates_D_q = Eigen::MatrixXd::Zero(nq, nq), rates_D_v;
          if constexpr (has_generalized_speeds_v<M>) {
            rates_D_q = coordinate_rates_jacobian<M>(p, q, v, t);
            rates_D_v = coordinate_rate_matrix<M>(p, q, t);
          } else {
            rates_D_v = Eigen::MatrixXd::Identity(nq, nv);
          }
          for (int r = 0; r < nq; ++r)
            for (int c = 0; c < n; ++c)
              out[r * n + c] = c < nq ? rates_D_q(r, c) : rates_D_v(r, c - nq);
          for (int r = 0; r < nv; ++r)
            for (int c = 0; c < n; ++c)
              out[(nq + r) * n + c] = c < nq ? a_D_q(r, c) : a_D_v(r, c - nq);
        }
        return jacobian;
      },
      "d(rhs)/dy, shape (nq + nv, nq + nv): [[0, I], [da/dq, da/dv]] from the generated\n"
      "residual Jacobians (da/dq = -Mt^-1 dr/dq, da/dv = -Mt^-1 dr/dv): the jac of solve_ivp.\n"
      "With generalized speeds the upper rows are [d(G v)/dq, G]. A model with kinematic\n"
      "constraints takes central differences of its constrained acceleration.",
      py::arg("t"), py::arg("y"), py::arg("params") = py::none());
}

}  // namespace gencoord::python
