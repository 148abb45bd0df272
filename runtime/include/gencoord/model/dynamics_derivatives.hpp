// SPDX-License-Identifier: BSD-3-Clause
// The derivatives of the forward dynamics that model-predictive control and trajectory
// optimization need: with a generalized force tau acting on every speed,
//   Mt(q) a = Ft(q, v) + Fi(q, v) + tau,
// the acceleration a(q, v, tau) has
//   da/dq = -Mt^-1 dr/dq,   da/dv = -Mt^-1 dr/dv,   da/dtau = Mt^-1,
// r = Mt a - Ft - Fi the inverse-dynamics residual. Generated: Mt^-1 and residual_jacobians(),
// which for a joint tree is the derivative of the recursive Newton-Euler residual, in closed
// form for an arm-like tree of revolute and prismatic joints and by forward mode otherwise (the
// route through the inverse dynamics' derivatives and Mt^-1 of Carpentier and Mansard, RSS
// 2018). FiniteDifference: central differences of acceleration(), 2 (nq + nv) dynamics
// evaluations, for comparison.
// With generalized speeds da/dq is nv x nq, in the embedding of q (control/linearize.hpp
// takes it to local coordinates).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/model_traits.hpp"

namespace gencoord {

template <class M>
struct DynamicsDerivatives {
  VVec<M> a;        // the acceleration at tau = 0 (dim nv)
  VQMat<M> a_D_q;   // da/dq (nv x nq)
  VMat<M> a_D_v;    // da/dv (nv x nv)
  VMat<M> a_D_tau;  // da/dtau = Mt^-1 (nv x nv)
};

/// a, da/dq, da/dv and da/dtau at (q, v, t); see the file comment for the sources.
/// \throws DynamicsError where Mt is not positive definite or a result is not finite;
///         std::invalid_argument as acceleration_and_jacobians().
template <class M>
DynamicsDerivatives<M> dynamics_derivatives(const ParamsOf<M>& p, const QVec<M>& q,
                                            const VVec<M>& v, double t,
                                            JacobianSource source = JacobianSource::Auto) {
  static_assert(assert_model_v<M>);
  DynamicsDerivatives<M> out;
  detail::InverseMass<M> inverse_mass;
  inverse_mass.compute(p, q, v, t, &out.a);
  out.a_D_tau = inverse_mass.inverse();
  if (resolve_jacobian_source<M>(source) == JacobianSource::FiniteDifference) {
    acceleration_jacobians_fd<M>(p, q, v, t, &out.a_D_q, &out.a_D_v);
  } else if constexpr (has_residual_jacobians_v<M> && !has_kinematic_constraints_v<M>) {
    VQMat<M> r_D_q;
    VMat<M> r_D_v;
    M::residual_jacobians(q, v, out.a, t, p, &r_D_q, &r_D_v);
    inverse_mass.apply_negated(r_D_q, &out.a_D_q);
    inverse_mass.apply_negated(r_D_v, &out.a_D_v);
  } else {
    detail::throw_no_generated_jacobians(M::name);
  }
  return out;
}

}  // namespace gencoord
