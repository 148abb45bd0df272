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
#include <type_traits>

#include <Eigen/Cholesky>

#include "gencoord/errors.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/numerics/small_dense.hpp"

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

// Mt^-1 at a state, as the derivative paths apply it. Where Mt has a fixed size of at most
// kSmallDenseMaxOrder, Mt^-1 is formed whole and applied as products by the runtime library's
// small dense kernels (numerics/small_dense.hpp: compiled once, for the machine's vector
// instructions; docs/performance.md, section 9, times the path); otherwise Eigen's Cholesky
// factor of Mt is kept and solved with.
template <class M>
class InverseMass {
 public:
  using Matrix = PlainOf<VMat<M>>;
  static constexpr bool kSmall = Matrix::RowsAtCompileTime != Eigen::Dynamic &&
                                 Matrix::RowsAtCompileTime <= kSmallDenseMaxOrder;

  /// Mt and f at (q, v, t), Mt^-1 and *a = Mt^-1 f, with the checks of acceleration().
  /// \throws DynamicsError as acceleration() does.
  void compute(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t, VVec<M>* a) {
    using Reason = DynamicsError::Reason;
    constexpr int nv = nv_of_v<M>;
    const auto fail = [&](Reason reason) {
      throw_dynamics_error(M::name, reason, t, q.data(), v.data(), M::nq, nv);
    };
    VMat<M> Mt;
    VVec<M> f;
    M::dynamics(q, v, t, p, &Mt, &f);
    if (!Mt.allFinite()) fail(Reason::kNonFiniteMassMatrix);
    if (!f.allFinite()) fail(Reason::kNonFiniteForces);
    if constexpr (kSmall) {
      if (!small_spd_inverse(nv, Mt.data(), inverse_.data())) fail(Reason::kNotPositiveDefinite);
      small_product(nv, 1, inverse_.data(), f.data(), 1.0, a->data());
    } else {
      llt_.compute(Mt);
      if (llt_.info() != Eigen::Success) fail(Reason::kNotPositiveDefinite);
      *a = llt_.solve(f);
    }
    if (!a->allFinite()) fail(Reason::kNonFiniteAcceleration);
  }

  /// Mt^-1.
  Matrix inverse() const {
    if constexpr (kSmall) {
      return inverse_;
    } else {
      return llt_.solve(Matrix::Identity(nv_of_v<M>, nv_of_v<M>));
    }
  }

  /// *result = -Mt^-1 rhs, for rhs of nv rows (dr/dq, dr/dv: the derivatives of a).
  template <class Rhs>
  void apply_negated(const Rhs& rhs, Rhs* result) const {
    if constexpr (kSmall) {
      static_assert(!Rhs::IsRowMajor, "small_product() reads and writes column-major data");
      small_product(nv_of_v<M>, static_cast<int>(rhs.cols()), inverse_.data(), rhs.data(), -1.0,
                    result->data());
    } else {
      *result = -llt_.solve(rhs);
    }
  }

 private:
  struct Unused {};
  std::conditional_t<kSmall, Matrix, Unused> inverse_;
  std::conditional_t<kSmall, Unused, Eigen::LLT<Matrix>> llt_;
};

[[noreturn]] inline void throw_no_generated_jacobians(const char* model) {
  throw std::invalid_argument(
      std::string("gencoord: JacobianSource::Generated requested, but model '") + model +
      "' does not emit residual_jacobians() of its whole dynamics (a model with kinematic "
      "constraints has none); use JacobianSource::Auto or FiniteDifference");
}

}  // namespace detail

/// The acceleration and its Jacobians in one pass: a = acceleration<M>(p, q, v, t),
/// da/dq and da/dv from `source`. With generated Jacobians this costs one dynamics
/// evaluation, Mt^-1 (detail::InverseMass), one residual_jacobians() call and Mt^-1
/// applied to its nq + nv columns; with finite differences,
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
    detail::InverseMass<M> inverse_mass;
    inverse_mass.compute(p, q, v, t, a);
    VQMat<M> r_D_q;
    VMat<M> r_D_v;
    M::residual_jacobians(q, v, *a, t, p, &r_D_q, &r_D_v);
    inverse_mass.apply_negated(r_D_q, a_D_q);
    inverse_mass.apply_negated(r_D_v, a_D_v);
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
