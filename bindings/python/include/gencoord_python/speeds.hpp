// SPDX-License-Identifier: BSD-3-Clause
// What a model with generalized speeds (free and ball joints: unit quaternions in q,
// q' = G(q) v) adds to its module: the kinematic equation, and the local coordinates
// (gencoord/model/tangent_space.hpp) in which linearize() states its A and B.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/tangent_space.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/kernels.hpp"

namespace gencoord::python {

namespace py = pybind11;

template <class M>
void bind_speeds(py::module_& m) {
  using P = ParamsOf<M>;
  const std::array<const char*, 2> qv{"q", "v"};
  def_kernel<M>(m, "coordinate_rates",
                "The coordinates' rates q' = G(q) v (linear in the speeds v).\n\nReturns (nq,); "
                "with a batch of N states, one per state (leading dimension N).",
                qv, [](const StateVectors<M>& x, double t, const P& p) {
                  return QVec<M>(M::coordinate_rates(x.q, x.v, t, p));
                });
  m.def(
      "retract",
      [](py::handle q0, py::handle delta, py::handle params) {
        const QVec<M> q = one_state_vector<M>(q0, "q0");
        const VVec<M> d = one_speed_vector<M>(delta, "delta");
        return vector_array(retract<M>(params_input<M>(params, -1).at(0), q, d));
      },
      "q0 moved by local coordinates delta (nv,): each unit quaternion turned by\n"
      "q0_k (x) exp(delta_k) about its own axes, every other coordinate moved by G(q0) delta\n"
      "(a free joint's position along its body axes). Returns q, shape (nq,).",
      py::arg("q0"), py::arg("delta"), py::arg("params") = py::none());
  m.def(
      "local_coordinates",
      [](py::handle q0, py::handle q, py::handle params) {
        const QVec<M> from = one_state_vector<M>(q0, "q0");
        const QVec<M> to = one_state_vector<M>(q, "q");
        return vector_array(local_coordinates<M>(params_input<M>(params, -1).at(0), from, to));
      },
      "The local coordinates delta of q about q0, shape (nv,): the inverse of retract (the\n"
      "shorter turn of each quaternion). linearize's states are (delta, v).",
      py::arg("q0"), py::arg("q"), py::arg("params") = py::none());
}

}  // namespace gencoord::python
