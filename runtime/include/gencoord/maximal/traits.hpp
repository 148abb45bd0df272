// SPDX-License-Identifier: BSD-3-Clause
// What the maximal-coordinate runtime needs of a generated model beyond docs/model_interface.md:
// the nested `M::Maximal` struct (penalty model kernels), and the per-coordinate masses.
#pragma once

#include <type_traits>

#include <Eigen/Core>

#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// The maximal (penalty) kernels of model M: `typename M::Maximal`.
template <class M>
using MaximalOf = typename M::Maximal;

namespace detail {
template <class M, class = void>
struct has_maximal : std::false_type {};
template <class M>
struct has_maximal<M, std::void_t<typename M::Maximal, decltype(M::Maximal::num_constraints),
                                  decltype(M::Maximal::has_generalized_forces),
                                  decltype(M::Maximal::jacobian_x_nonzeros),
                                  decltype(M::Maximal::jacobian_xdot_nonzeros)>> : std::true_type {
};
}  // namespace detail

/// True when M has the generated `Maximal` struct (penalty forces, sparse force Jacobians).
template <class M>
inline constexpr bool has_maximal_v = detail::has_maximal<M>::value;

/// Whether the maximal model of M needs the inverse map (x, xdot) -> (q, v) in its forces:
/// for generalized forces (mapped to x as M J Mt^-1 Q), or for the manifold spring of a model
/// that declares no constraints but has fewer speeds than particles' degrees of freedom.
template <class M>
inline constexpr bool uses_manifold_spring_v = MaximalOf<M>::num_constraints == 0 &&
                                               (nv_of_v<M> < M::nx);
template <class M>
inline constexpr bool needs_inverse_map_v =
    MaximalOf<M>::has_generalized_forces || uses_manifold_spring_v<M>;

/// The diagonal of the maximal mass matrix: each particle's mass repeated dim times (nx).
template <class M>
XVec<M> coordinate_masses(const ParamsOf<M>& p) {
  const Eigen::Matrix<double, M::num_particles, 1> m = M::template particle_masses<double>(p);
  XVec<M> out;
  for (int i = 0; i < M::num_particles; ++i)
    out.template segment<M::dim>(M::dim * i).setConstant(m(i));
  return out;
}

/// The model's suggested initial state (M::initial_q, M::initial_v) as vectors (nq, nv).
template <class M>
QVec<M> initial_q_of() {
  QVec<M> q;
  for (int i = 0; i < M::nq; ++i) q(i) = M::initial_q[static_cast<std::size_t>(i)];
  return q;
}
template <class M>
VVec<M> initial_v_of() {
  VVec<M> v;
  for (int i = 0; i < nv_of_v<M>; ++i) v(i) = M::initial_v[static_cast<std::size_t>(i)];
  return v;
}

}  // namespace gencoord
