// SPDX-License-Identifier: BSD-3-Clause
// Forward dynamics: qddot = Mt^-1 (Ft + Fi), by the model's articulated-body recursion when
// it has a cheaper one, else by a fixed-size factorization of Mt. This is the integrators'
// hot path: no heap allocation for fixed-size models, and the error diagnosis is out of line
// (errors.cpp).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <utility>

#include "gencoord/errors.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

namespace detail {
template <class M>
using solve_op = decltype(M::solve(std::declval<const VMat<M>&>(), std::declval<const VVec<M>&>(),
                                   std::declval<VVec<M>*>()));
}  // namespace detail

/// Solves Mt a = f for SPD Mt: the generated model's straight-line LDL^T (M::solve) when it
/// has one, Eigen's fixed-size LLT otherwise. False when Mt is not positive definite.
template <class M>
bool solve_mass_matrix(const VMat<M>& Mt, const VVec<M>& f, VVec<M>* a) {
  if constexpr (detail::detected_v<M, detail::solve_op>) {
    return M::solve(Mt, f, a);
  } else {
    const Eigen::LLT<PlainOf<VMat<M>>> llt(Mt);
    if (llt.info() != Eigen::Success) return false;
    *a = llt.solve(f);
    return true;
  }
}

/// Generalized acceleration a = Mt(q, t)^-1 (Ft + Fi)(q, v, t) of model M; with kinematic
/// constraints, the constrained one (constrained_acceleration()).
/// \param[in] p  The model parameters.
/// \param[in] q  The generalized coordinates (dim M::nq).
/// \param[in] v  The generalized velocities or speeds (dim nv_of_v<M>).
/// \param[in] t  The time.
/// \return The generalized acceleration v' (dim nv_of_v<M>).
/// \throws DynamicsError if Mt is not positive definite, or Mt, the forces or the result
///         contain NaN or inf. A model with a recursive qddot reports an indefinite Mt only
///         where the recursion meets a zero pivot: its pivots are not checked for sign.
///         A constrained model also when its constraints are dependent at q.
template <class M>
VVec<M> acceleration(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t) {
  static_assert(assert_model_v<M>);
  using Reason = DynamicsError::Reason;
  if constexpr (has_kinematic_constraints_v<M>) return constrained_acceleration<M>(p, q, v, t);
  if constexpr (has_recursive_qddot_v<M>) {
    // the recursion divides by the articulated inertias, so a singular Mt shows as NaN or
    // inf and goes to the diagnosis below; an indefinite one (a negative mass) does not
    VVec<M> a = M::qddot(q, v, t, p);
    if (a.allFinite()) return a;
  }
  VMat<M> Mt;
  VVec<M> f;
  M::dynamics(q, v, t, p, &Mt, &f);
  VVec<M> a;
  const bool solved = solve_mass_matrix<M>(Mt, f, &a);
  // the hot path: NaN/inf in f or below Mt's diagonal reach a or stop the factorization;
  // an infinite diagonal entry would not (its pivot's inverse is 0), hence its own test
  if (solved && a.allFinite() && Mt.diagonal().allFinite()) return a;
  // diagnosis, off the hot path
  if (!Mt.allFinite())
    detail::throw_dynamics_error(M::name, Reason::kNonFiniteMassMatrix, t, q.data(), v.data(),
                                 M::nq, nv_of_v<M>);
  if (!f.allFinite())
    detail::throw_dynamics_error(M::name, Reason::kNonFiniteForces, t, q.data(), v.data(), M::nq,
                                 nv_of_v<M>);
  if (!solved)
    detail::throw_dynamics_error(M::name, Reason::kNotPositiveDefinite, t, q.data(), v.data(),
                                 M::nq, nv_of_v<M>);
  detail::throw_dynamics_error(M::name, Reason::kNonFiniteAcceleration, t, q.data(), v.data(),
                               M::nq, nv_of_v<M>);
}

/// Generalized acceleration at a state; see acceleration(p, q, v, t).
/// \throws DynamicsError as acceleration(p, q, v, t).
template <class M>
VVec<M> acceleration(const ParamsOf<M>& p, const State<M>& s) {
  return acceleration<M>(p, s.q, s.v, s.t);
}

}  // namespace gencoord
