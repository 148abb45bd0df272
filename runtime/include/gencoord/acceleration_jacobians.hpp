// Jacobians of the forward dynamics a(q, v, t) with respect to q and v, as needed by the
// Newton iterations of the implicit integrators.
//
// Today they come from central finite differences. The seam for generated derivatives is
// acceleration_jacobians(): once models emit the inverse-dynamics residual Jacobians dr/dq and
// dr/dv (DESIGN.md section 1), it will use a_D_q = -Mt^-1 dr/dq and a_D_v = -Mt^-1 dr/dv
// (selected with `if constexpr` on a detection trait) and no caller changes.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "gencoord/dynamics.hpp"
#include "gencoord/model_traits.hpp"

namespace gencoord {

/// Central finite-difference Jacobians of acceleration() at (q, v, t).
/// Each column costs two evaluations; step cbrt(eps) * max(1, |x_j|), truncation and
/// round-off error both O(eps^(2/3)) relative.
/// \param[in]  p      The model parameters.
/// \param[in]  q      The generalized coordinates (dim M::nq).
/// \param[in]  v      The generalized velocities (dim M::nq).
/// \param[in]  t      The time.
/// \param[out] a_D_q  da/dq (dim M::nq x M::nq); must not be null.
/// \param[out] a_D_v  da/dv (dim M::nq x M::nq); must not be null.
/// \throws DynamicsError if the dynamics fail at a perturbed state.
template <class M>
void acceleration_jacobians_fd(const ParamsOf<M>& p, const QVec<M>& q, const QVec<M>& v,
                               double t, QMat<M>* a_D_q, QMat<M>* a_D_v) {
  static const double kRelStep = std::cbrt(std::numeric_limits<double>::epsilon());
  for (int j = 0; j < M::nq; ++j) {
    // columns of da/dq
    QVec<M> qp = q, qm = q;
    qp[j] += kRelStep * std::max(1.0, std::abs(q[j]));
    qm[j] -= kRelStep * std::max(1.0, std::abs(q[j]));
    // divide by the representable step, not the nominal one
    a_D_q->col(j) =
        (acceleration<M>(p, qp, v, t) - acceleration<M>(p, qm, v, t)) / (qp[j] - qm[j]);
    // columns of da/dv
    QVec<M> vp = v, vm = v;
    vp[j] += kRelStep * std::max(1.0, std::abs(v[j]));
    vm[j] -= kRelStep * std::max(1.0, std::abs(v[j]));
    a_D_v->col(j) =
        (acceleration<M>(p, q, vp, t) - acceleration<M>(p, q, vm, t)) / (vp[j] - vm[j]);
  }
}

/// Jacobians da/dq and da/dv of acceleration() at (q, v, t), each (dim M::nq x M::nq).
/// Currently acceleration_jacobians_fd(); this is where generated Jacobians will plug in.
/// \throws DynamicsError if the dynamics fail near (q, v, t).
template <class M>
void acceleration_jacobians(const ParamsOf<M>& p, const QVec<M>& q, const QVec<M>& v, double t,
                            QMat<M>* a_D_q, QMat<M>* a_D_v) {
  acceleration_jacobians_fd<M>(p, q, v, t, a_D_q, a_D_v);
}

}  // namespace gencoord
