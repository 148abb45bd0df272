// SPDX-License-Identifier: BSD-3-Clause
// The kinematic constraints of a model with closed loops or rolling contacts, for Python:
// their generated kernels, the constrained acceleration and its multipliers, the projection
// onto the constraints, inverse dynamics (one input per degree of freedom) and the
// linearization in independent coordinates and speeds (gencoord/model/constrained_dynamics.hpp,
// gencoord/control/constrained_inverse_dynamics.hpp, constrained_linearization.hpp).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <string>
#include <vector>

#include "gencoord/control/constrained_inverse_dynamics.hpp"
#include "gencoord/control/constrained_linearization.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

template <class M>
void bind_constraints(py::module_& m) {
  using P = ParamsOf<M>;
  using V = VVec<M>;
  using X = StateVectors<M>;
  using CJacobian = typename M::template CJacobian<double>;
  const std::array<const char*, 1> q{"q"};
  const std::array<const char*, 2> qv{"q", "v"};
  m.attr("num_constraints") = M::num_constraints;
  py::tuple names(M::num_constraints);
  for (int k = 0; k < M::num_constraints; ++k) names[k] = py::str(M::constraint_names[k]);
  m.attr("constraint_names") = names;
  int holonomic = 0;
  if constexpr (has_holonomic_constraints_v<M>) {
    holonomic = M::num_holonomic_constraints;
    using HJacobian = typename M::template HJacobian<double>;
    def_kernel<M>(m, "holonomic_constraints",
                  "The holonomic constraints C(q, t), zero on the constraints: "
                  "(num_holonomic_constraints,).",
                  q, [](const X& x, double t, const P& p) {
                    return
                        typename M::template HVector<double>(M::holonomic_constraints(x.q, t, p));
                  });
    def_kernel<M>(m, "holonomic_jacobian", "dC/dq: (num_holonomic_constraints, nq).", q,
                  [](const X& x, double t, const P& p) {
                    return AsMatrix<HJacobian>{M::holonomic_jacobian(x.q, t, p)};
                  });
  }
  m.attr("num_holonomic_constraints") = holonomic;
  def_kernel<M>(m, "constraint_jacobian",
                "The constraint Jacobian A(q, t) of A v + b = 0 (every constraint, holonomic "
                "ones differentiated): (num_constraints, nq).",
                q, [](const X& x, double t, const P& p) {
                  return AsMatrix<CJacobian>{M::constraint_jacobian(x.q, t, p)};
                });
  def_kernel<M>(m, "constraint_velocities",
                "A v + b, zero when the speeds satisfy the constraints: (num_constraints,).", qv,
                [](const X& x, double t, const P& p) {
                  return CVec<M>(M::constraint_velocities(x.q, x.v, t, p));
                });
  def_kernel<M>(
      m, "constraint_bias", "gamma, with A v' + gamma = 0 on the constraints: (num_constraints,).",
      qv,
      [](const X& x, double t, const P& p) { return CVec<M>(M::constraint_bias(x.q, x.v, t, p)); });
  def_kernel<M>(m, "constrained_qddot",
                "The constrained acceleration v' (what rhs and simulate integrate; qddot is the "
                "tree's, its loops open): (nq,). Raises DynamicsError where the constraints are "
                "dependent.",
                qv, [](const X& x, double t, const P& p) {
                  return V(constrained_acceleration<M>(p, x.q, x.v, t));
                });
  def_kernel<M>(m, "constraint_forces",
                "The multipliers lambda of Mt v' = Ft + Fi + A^T lambda: each constraint's "
                "force in its own units (for a closed loop, the force on its second point in "
                "newtons): (num_constraints,).",
                qv, [](const X& x, double t, const P& p) {
                  CVec<M> lambda;
                  constrained_acceleration<M>(p, x.q, x.v, t, &lambda);
                  return lambda;
                });
  m.def(
      "project",
      [](py::handle q, py::handle v, double t, py::handle params) {
        State<M> s;
        s.q = one_state_vector<M>(q, "q");
        s.v = one_state_vector<M>(v, "v");
        s.t = t;
        const P p = params_input<M>(params, -1).at(0);
        {
          py::gil_scoped_release unlocked;
          project_onto_constraints<M>(p, &s);
        }
        return py::make_tuple(vector_array(s.q), vector_array(s.v));
      },
      "(q, v) moved onto the constraints: Gauss-Newton least-change steps on C(q, t) = 0, then "
      "the least-kinetic-energy change of v onto A v + b = 0 (what every integration step "
      "does). Returns (q, v).",
      py::arg("q"), py::arg("v"), py::arg("t") = 0.0, py::arg("params") = py::none());
  if constexpr (has_inputs_v<M>) {
    if constexpr (num_inputs_v<M> + M::num_constraints == nv_of_v<M>) {
      m.def(
          "inverse_dynamics_constrained",
          [](py::handle q, py::handle v, std::vector<int> independent, py::handle prescribed,
             double t, py::handle params) {
            State<M> s;
            s.q = one_state_vector<M>(q, "q");
            s.v = one_state_vector<M>(v, "v");
            s.t = t;
            const P p = params_input<M>(params, -1).at(0);
            const auto wanted = py::cast<std::vector<double>>(prescribed);
            const Eigen::VectorXd accelerations =
                Eigen::Map<const Eigen::VectorXd>(wanted.data(), Eigen::Index(wanted.size()));
            ConstrainedInverseDynamics<M> out;
            try {
              py::gil_scoped_release unlocked;
              out = constrained_inverse_dynamics<M>(p, s, independent, accelerations);
            } catch (const std::invalid_argument& error) {
              throw py::value_error(error.what());
            }
            return py::make_tuple(vector_array(out.inputs), vector_array(out.multipliers),
                                  vector_array(out.acceleration));
          },
          "The control inputs that give the independent speeds v[independent] the\n"
          "accelerations `prescribed` at a state on the constraints (one input per degree of\n"
          "freedom). Returns (u, lambda, vdot): the inputs, the constraint forces and the\n"
          "whole acceleration, which constrained_qddot gives back with those inputs. Raises\n"
          "ValueError for wrong indices or sizes, DynamicsError where the inputs cannot\n"
          "produce the motion.",
          py::arg("q"), py::arg("v"), py::arg("independent"), py::arg("prescribed"),
          py::arg("t") = 0.0, py::arg("params") = py::none());
    }
  }
  m.def(
      "linearize_constrained",
      [](py::handle q, py::handle v, std::vector<int> independent_q, std::vector<int> dependent_q,
         std::vector<int> independent_v, std::vector<int> dependent_v, double t,
         py::handle params) {
        State<M> reference;
        reference.q = one_state_vector<M>(q, "q");
        reference.v = one_state_vector<M>(v, "v");
        reference.t = t;
        const P p = params_input<M>(params, -1).at(0);
        const CoordinateSplit split{std::move(independent_q), std::move(dependent_q),
                                    std::move(independent_v), std::move(dependent_v)};
        ConstrainedLinearization linear;
        try {
          py::gil_scoped_release unlocked;
          linear = linearize_constrained<M>(p, reference, split);
        } catch (const std::invalid_argument& error) {
          throw py::value_error(error.what());
        }
        return py::make_tuple(matrix_array(linear.A), matrix_array(linear.B),
                              vector_array(linear.zdot));
      },
      "Linearization about a state on the constraints (an equilibrium or a steady motion) in\n"
      "the reduced state z = (q[independent_q], v[independent_v]): the dependent coordinates\n"
      "and speeds (one per holonomic constraint, one per constraint) are solved from the\n"
      "constraints, the other coordinates and speeds held at the reference. Returns (A, B,\n"
      "zdot): z' ~ zdot + A (z - z0) + B (u - u0), from central differences with one\n"
      "Richardson extrapolation. Raises ValueError for a split of the wrong sizes.",
      py::arg("q"), py::arg("v"), py::arg("independent_q"), py::arg("dependent_q"),
      py::arg("independent_v"), py::arg("dependent_v"), py::arg("t") = 0.0,
      py::arg("params") = py::none());
}

}  // namespace gencoord::python
