// SPDX-License-Identifier: BSD-3-Clause
// The linearization of a model's dynamics about a state and an input, for controller design.
//
// With x = (q, v) and qdot = v, qddot = a(q, v, u, t) the first-order system is
// xdot = f(x, u, t), and its Jacobians are
//   A = df/dx = [[0, I], [da/dq, da/dv]],   B = df/du = [[0], [da/du]].
// a solves r(q, v, a, u, t) = Mt a - Ft - Fi = 0, so with the generated Jacobians
//   da/dq = -Mt^-1 dr/dq,   da/dv = -Mt^-1 dr/dv,   da/du = Mt^-1 dFt/du = Mt^-1 B(q),
// from one Cholesky factor of Mt, residual_jacobians() and input_matrix().
// A model with generalized speeds (unit quaternions in q, q' = G(q) v) is linearized in the
// local coordinates of model/tangent_space.hpp, x = (delta, v) with q = retract(q0, delta):
//   A = [[d delta'/d delta, d delta'/d v], [da/dq G(q0), da/dv]],   2 nv square,
// whose upper blocks are 0 and I at rest (tangent_rates()).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "gencoord/control/inputs.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/tangent_space.hpp"

namespace gencoord {

/// xdot ~ xdot0 + A (x - x0) + B (u - u0) near the operating point (x0, u0).
/// With generalized speeds, nq reads nv and x = (delta, v) (the file comment).
struct LinearizedDynamics {
  Eigen::VectorXd xdot;  // f(x0, u0, t) = (v, a) (dim 2 nq)
  Eigen::MatrixXd A;     // df/dx (2 nq x 2 nq), x = (q, v)
  Eigen::MatrixXd B;     // df/du (2 nq x num_inputs)
};

/// da/du of a model's acceleration (dim nv x num_inputs_v<M>).
template <class M>
using InputJacobian = Eigen::Matrix<double, nv_of_v<M>, num_inputs_v<M>>;

/// The acceleration a(q, v, u, t) and its Jacobians da/dq, da/dv and, unless a_D_u is null,
/// da/du. Generated: one Cholesky factor of Mt serves all three (the file comment);
/// FiniteDifference: central differences of acceleration(), 2 per column.
/// \param[in]  p       The model parameters; their input fields are replaced by u.
/// \param[in]  u       The control inputs (dim num_inputs_v<M>).
/// \param[out] a, a_D_q, a_D_v  Must not be null (dims nv, nv x nq, nv x nv).
/// \param[out] a_D_u   da/du; may be null when it is not wanted.
/// \throws DynamicsError, std::invalid_argument as acceleration_and_jacobians().
template <class M>
void acceleration_and_input_jacobians(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v,
                                      const InputVec<M>& u, double t, JacobianSource source,
                                      VVec<M>* a, VQMat<M>* a_D_q, VMat<M>* a_D_v,
                                      InputJacobian<M>* a_D_u) {
  static_assert(!has_kinematic_constraints_v<M>,
                "gencoord: a model with kinematic constraints is linearized in its independent "
                "coordinates and speeds: use linearize_constrained() "
                "(gencoord/control/constrained_linearization.hpp)");
  const ParamsOf<M> pu = with_inputs<M>(p, u);
  if (resolve_jacobian_source<M>(source) == JacobianSource::FiniteDifference) {
    acceleration_and_jacobians<M>(pu, q, v, t, source, a, a_D_q, a_D_v);
    if constexpr (has_inputs_v<M>) {
      if (!a_D_u) return;
      for (int k = 0; k < M::num_inputs; ++k) {
        InputVec<M> up = u, um = u;
        up[k] += detail::central_difference_step(u[k]);
        um[k] -= detail::central_difference_step(u[k]);
        a_D_u->col(k) = (acceleration<M>(with_inputs<M>(p, up), q, v, t) -
                         acceleration<M>(with_inputs<M>(p, um), q, v, t)) /
                        (up[k] - um[k]);
      }
    }
  } else if constexpr (has_residual_jacobians_v<M>) {
    detail::InverseMass<M> inverse_mass;
    inverse_mass.compute(pu, q, v, t, a);
    VQMat<M> r_D_q;
    VMat<M> r_D_v;
    M::residual_jacobians(q, v, *a, t, pu, &r_D_q, &r_D_v);
    inverse_mass.apply_negated(r_D_q, a_D_q);
    inverse_mass.apply_negated(r_D_v, a_D_v);
    if constexpr (has_inputs_v<M>)
      if (a_D_u) *a_D_u = inverse_mass.inverse() * M::input_matrix(q, v, t, pu);
  } else {
    detail::throw_no_generated_jacobians(M::name);
  }
}

/// The linearization of model M's dynamics at (q, v, u, t); see LinearizedDynamics.
/// \param[in] p       The model parameters; their input fields are replaced by u.
/// \param[in] q       The generalized coordinates (dim M::nq).
/// \param[in] v       The generalized velocities or speeds (dim nv).
/// \param[in] u       The control inputs (dim num_inputs_v<M>).
/// \param[in] t       The time.
/// \param[in] source  Generated (the default where the model has residual_jacobians()):
///                    exact to round-off; FiniteDifference: central differences of
///                    acceleration() in q, v and u, for comparison.
/// \throws DynamicsError if the dynamics fail at the point (or at a perturbed one);
///         std::invalid_argument as acceleration_and_jacobians().
template <class M>
LinearizedDynamics linearize(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v,
                             const InputVec<M>& u, double t,
                             JacobianSource source = JacobianSource::Auto) {
  static_assert(assert_model_v<M>);
  constexpr int n = nv_of_v<M>;
  VVec<M> a;
  VQMat<M> a_D_q;
  VMat<M> a_D_v;
  InputJacobian<M> a_D_u;
  acceleration_and_input_jacobians<M>(p, q, v, u, t, source, &a, &a_D_q, &a_D_v, &a_D_u);
  LinearizedDynamics out;
  out.xdot.resize(2 * n);
  for (int i = 0; i < n; ++i) {  // entry by entry: GCC 12 misreads a vectorized block copy
    out.xdot[i] = v[i];
    out.xdot[n + i] = a[i];
  }
  out.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  if constexpr (has_generalized_speeds_v<M>) {
    const TangentRates tangent = tangent_rates<M>(with_inputs<M>(p, u), q, v, t);
    out.A.topLeftCorner(n, n) = tangent.rate_D_delta;
    out.A.topRightCorner(n, n) = tangent.rate_D_v;
    out.A.bottomLeftCorner(n, n) = Eigen::MatrixXd(a_D_q) * tangent.G;
  } else {
    out.A.topRightCorner(n, n).setIdentity();
    out.A.bottomLeftCorner(n, n) = a_D_q;
  }
  out.A.bottomRightCorner(n, n) = a_D_v;
  out.B = Eigen::MatrixXd::Zero(2 * n, num_inputs_v<M>);
  // (GCC 12 warns of a 0-column copy)
  if constexpr (num_inputs_v < M >> 0) out.B.bottomRows(n) = a_D_u;
  return out;
}

}  // namespace gencoord
