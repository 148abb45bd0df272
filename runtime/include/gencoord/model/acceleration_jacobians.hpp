// SPDX-License-Identifier: BSD-3-Clause
// Jacobians of the forward dynamics a(q, v, t) with respect to q and v, as needed by the
// Newton iterations of the implicit integrators.
//
// Two sources, selected by JacobianSource:
//  - Generated: from the generated residual Jacobians. a = a(q, v, t) satisfies
//    r(q, v, a(q, v, t), t) = 0 identically, so dr/dq + Mt da/dq = 0 and
//      da/dq = -Mt^-1 dr/dq,   da/dv = -Mt^-1 dr/dv,
//    with the one Cholesky factor of Mt that computing a already needed. Exact to round-off.
//  - FiniteDifference: central differences of acceleration(), 2 (nq + nv) evaluations of the
//    dynamics; kept so that the two can be compared (tests, bench/implicit_bench.cc).
// With generalized speeds, da/dq is nv x nq (a derivative in the embedding of q, quaternion
// entries perturbed off the unit sphere) and da/dv nv x nv.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

#include "gencoord/errors.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// Where the Newton iterations of implicit steps get da/dq and da/dv from.
enum class JacobianSource {
  Auto,              ///< Generated when the model emits residual_jacobians (every generated
                     ///< model does) and has no kinematic constraints, else FiniteDifference;
                     ///< decided at compile time per model.
  Generated,         ///< the generated residual Jacobians; std::invalid_argument if absent
  FiniteDifference,  ///< central differences of acceleration()
};

/// The source that `source` means for model M: Auto resolved, the others unchanged.
template <class M>
constexpr JacobianSource resolve_jacobian_source(JacobianSource source) {
  // the generated residual leaves out the constraint forces: a constrained model's
  // acceleration is differentiated numerically
  if (source == JacobianSource::Auto)
    return has_residual_jacobians_v<M> && !has_kinematic_constraints_v<M>
               ? JacobianSource::Generated
               : JacobianSource::FiniteDifference;
  return source;
}

namespace detail {

// the step of a central difference in x: cbrt(eps) * max(1, |x|), which balances truncation
// and round-off (both O(eps^(2/3)) relative)
inline double central_difference_step(double x) {
  static const double kRelStep = std::cbrt(std::numeric_limits<double>::epsilon());
  return kRelStep * std::max(1.0, std::abs(x));
}

}  // namespace detail

/// Central finite-difference Jacobians of an acceleration a(q, v, t) of model M's state.
/// Each column costs two evaluations; step cbrt(eps) * max(1, |x_j|), truncation and
/// round-off error both O(eps^(2/3)) relative.
/// \param[in]  acceleration  a(q, v, t) -> VVec<M>.
/// \param[in]  q      The generalized coordinates (dim M::nq).
/// \param[in]  v      The generalized velocities or speeds (dim nv).
/// \param[in]  t      The time.
/// \param[out] a_D_q  da/dq (dim nv x nq); must not be null.
/// \param[out] a_D_v  da/dv (dim nv x nv); must not be null.
/// \throws what `acceleration` throws at a perturbed state.
template <class M, class Acceleration>
void central_difference_jacobians(const Acceleration& acceleration, const QVec<M>& q,
                                  const VVec<M>& v, double t, VQMat<M>* a_D_q, VMat<M>* a_D_v) {
  using detail::central_difference_step;
  for (int j = 0; j < M::nq; ++j) {
    // columns of da/dq
    QVec<M> qp = q, qm = q;
    qp[j] += central_difference_step(q[j]);
    qm[j] -= central_difference_step(q[j]);
    // divide by the representable step, not the nominal one
    a_D_q->col(j) = (acceleration(qp, v, t) - acceleration(qm, v, t)) / (qp[j] - qm[j]);
  }
  for (int j = 0; j < nv_of_v<M>; ++j) {
    // columns of da/dv
    VVec<M> vp = v, vm = v;
    vp[j] += central_difference_step(v[j]);
    vm[j] -= central_difference_step(v[j]);
    a_D_v->col(j) = (acceleration(q, vp, t) - acceleration(q, vm, t)) / (vp[j] - vm[j]);
  }
}

/// Central finite-difference Jacobians of acceleration() at (q, v, t)
/// (central_difference_jacobians()).
/// \throws DynamicsError if the dynamics fail at a perturbed state.
template <class M>
void acceleration_jacobians_fd(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t,
                               VQMat<M>* a_D_q, VMat<M>* a_D_v) {
  central_difference_jacobians<M>([&p](const QVec<M>& qx, const VVec<M>& vx,
                                       double tx) { return acceleration<M>(p, qx, vx, tx); },
                                  q, v, t, a_D_q, a_D_v);
}

namespace detail {

// factors Mt and solves for a, with the checks of acceleration()
template <class M>
void factor_and_solve(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t,
                      Eigen::LLT<PlainOf<VMat<M>>>* llt, VVec<M>* a) {
  using Reason = DynamicsError::Reason;
  constexpr int nv = nv_of_v<M>;
  VMat<M> Mt;
  VVec<M> f;
  M::dynamics(q, v, t, p, &Mt, &f);
  if (!Mt.allFinite())
    throw_dynamics_error(M::name, Reason::kNonFiniteMassMatrix, t, q.data(), v.data(), M::nq, nv);
  if (!f.allFinite())
    throw_dynamics_error(M::name, Reason::kNonFiniteForces, t, q.data(), v.data(), M::nq, nv);
  llt->compute(Mt);
  if (llt->info() != Eigen::Success)
    throw_dynamics_error(M::name, Reason::kNotPositiveDefinite, t, q.data(), v.data(), M::nq, nv);
  *a = llt->solve(f);
  if (!a->allFinite())
    throw_dynamics_error(M::name, Reason::kNonFiniteAcceleration, t, q.data(), v.data(), M::nq, nv);
}

// (L L^T)^-1 = X^T X from the Cholesky factor of a fixed-size matrix, X = L^-1 row by row:
// each row of X is the unit row less a combination of the rows above it, whole rows that the
// compiler vectorizes, where Eigen's column-wise triangular solve is one long chain of
// dependent steps.
template <class Matrix>
Matrix inverse_from_cholesky(const Eigen::LLT<Matrix>& llt) {
  constexpr int n = Matrix::RowsAtCompileTime;
  static_assert(n != Eigen::Dynamic, "inverse_from_cholesky: fixed sizes only");
  using Row = Eigen::Matrix<typename Matrix::Scalar, 1, n>;
  const Matrix& L = llt.matrixLLT();  // L in the lower triangle
  Eigen::Matrix<typename Matrix::Scalar, n, n, Eigen::RowMajor> X;
  for (int i = 0; i < n; ++i) {
    Row row = Row::Unit(i);
    for (int k = 0; k < i; ++k) row -= L(i, k) * X.row(k);
    X.row(i) = row / L(i, i);
  }
  return X.transpose() * X;
}

// Mt^-1 times the residual's Jacobians: *a_D_q = -Mt^-1 r_D_q, *a_D_v = -Mt^-1 r_D_v, and
// Mt^-1 itself into *inverse unless it is null. At fixed sizes up to 24 Eigen's triangular
// solves are bound by latency (the iiwa's 7 x 7: about 430 ns a solve, 55 ns a 7 x 7 product),
// so there Mt^-1 is formed from the factor (inverse_from_cholesky) and the rest are products
// (the floating quadruped's derivatives, nv = 18: 12.0 us against 16.0 us solving each
// block); otherwise each block is solved.
template <class M>
void apply_inverse_mass(const Eigen::LLT<PlainOf<VMat<M>>>& llt, const VQMat<M>& r_D_q,
                        const VMat<M>& r_D_v, VQMat<M>* a_D_q, VMat<M>* a_D_v,
                        VMat<M>* inverse = nullptr) {
  constexpr int size = PlainOf<VMat<M>>::RowsAtCompileTime;
  constexpr bool small = size != Eigen::Dynamic && size <= 24;
  if constexpr (small) {
    const VMat<M> Mt_inverse = inverse_from_cholesky(llt);
    if (inverse) *inverse = Mt_inverse;
    a_D_q->noalias() = -Mt_inverse * r_D_q;
    a_D_v->noalias() = -Mt_inverse * r_D_v;
    return;
  }
  if (inverse) *inverse = llt.solve(PlainOf<VMat<M>>::Identity(nv_of_v<M>, nv_of_v<M>));
  *a_D_q = -llt.solve(r_D_q);
  *a_D_v = -llt.solve(r_D_v);
}

[[noreturn]] inline void throw_no_generated_jacobians(const char* model) {
  throw std::invalid_argument(
      std::string("gencoord: JacobianSource::Generated requested, but model '") + model +
      "' does not emit residual_jacobians() of its whole dynamics (a model with kinematic "
      "constraints has none); use JacobianSource::Auto or FiniteDifference");
}

}  // namespace detail

/// The acceleration and its Jacobians in one pass: a = acceleration<M>(p, q, v, t),
/// da/dq and da/dv from `source`. With generated Jacobians this costs one dynamics
/// evaluation, one Cholesky factorization of Mt, one residual_jacobians() call and Mt^-1
/// applied to its nq + nv columns (detail::apply_inverse_mass); with finite differences,
/// 2 (nq + nv) + 1 acceleration() evaluations.
/// \param[in]  p       The model parameters.
/// \param[in]  q       The generalized coordinates (dim M::nq).
/// \param[in]  v       The generalized velocities or speeds (dim nv).
/// \param[in]  t       The time.
/// \param[in]  source  Where the Jacobians come from (see JacobianSource).
/// \param[out] a       The acceleration (dim nv); must not be null.
/// \param[out] a_D_q   da/dq (dim nv x nq); must not be null.
/// \param[out] a_D_v   da/dv (dim nv x nv); must not be null.
/// \throws DynamicsError if the dynamics fail at (q, v, t) (or, for finite differences, at a
///         perturbed state); std::invalid_argument if source is Generated and the model has no
///         residual_jacobians(). Non-finite generated Jacobians are not checked here: they
///         make the Newton update non-finite, which the implicit steps report as NewtonError.
template <class M>
void acceleration_and_jacobians(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t,
                                JacobianSource source, VVec<M>* a, VQMat<M>* a_D_q,
                                VMat<M>* a_D_v) {
  static_assert(assert_model_v<M>);
  const JacobianSource resolved = resolve_jacobian_source<M>(source);
  if (resolved == JacobianSource::FiniteDifference) {
    *a = acceleration<M>(p, q, v, t);
    acceleration_jacobians_fd<M>(p, q, v, t, a_D_q, a_D_v);
    return;
  }
  if constexpr (has_residual_jacobians_v<M> && !has_kinematic_constraints_v<M>) {
    // r(q, v, a(q, v)) = 0  =>  Mt da/dq = -dr/dq, Mt da/dv = -dr/dv
    Eigen::LLT<PlainOf<VMat<M>>> llt;
    detail::factor_and_solve<M>(p, q, v, t, &llt, a);
    VQMat<M> r_D_q;
    VMat<M> r_D_v;
    M::residual_jacobians(q, v, *a, t, p, &r_D_q, &r_D_v);
    detail::apply_inverse_mass<M>(llt, r_D_q, r_D_v, a_D_q, a_D_v);
  } else {
    detail::throw_no_generated_jacobians(M::name);
  }
}

/// Jacobians da/dq (nv x nq) and da/dv (nv x nv) of acceleration() at (q, v, t); see
/// acceleration_and_jacobians() for the sources and their cost.
/// \throws DynamicsError, std::invalid_argument as acceleration_and_jacobians().
template <class M>
void acceleration_jacobians(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t,
                            VQMat<M>* a_D_q, VMat<M>* a_D_v,
                            JacobianSource source = JacobianSource::Auto) {
  VVec<M> a;
  acceleration_and_jacobians<M>(p, q, v, t, source, &a, a_D_q, a_D_v);
}

}  // namespace gencoord
