// SPDX-License-Identifier: BSD-3-Clause
// Inverse dynamics: the generalized force r = Mt(q, t) a - Ft(q, v, t) - Fi(q, v, t) that
// produces the acceleration a, and its Jacobians dr/dq, dr/dv (dr/da = Mt), from the
// generated kernels M::inverse_dynamics and M::residual_jacobians.
#pragma once

#include <type_traits>
#include <utility>

#include "gencoord/model/model_traits.hpp"

namespace gencoord {

namespace detail {

template <class M>
using inverse_dynamics_op =
    require_convertible<decltype(M::inverse_dynamics(q_arg<M>(), v_arg<M>(), v_arg<M>(), t_arg(),
                                                     p_arg<M>())),
                        VVec<M>>;
template <class M>
using residual_jacobians_op =
    decltype(M::residual_jacobians(q_arg<M>(), v_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>(),
                                   std::declval<VQMat<M>*>(), std::declval<VMat<M>*>()));

}  // namespace detail

/// True when M emits `QVector<S> inverse_dynamics(q, v, qdd, t, p)` (every generated model
/// does; hand-written test models may not).
template <class M>
inline constexpr bool has_inverse_dynamics_v = detail::detected_v<M, detail::inverse_dynamics_op>;

/// True when M emits `void residual_jacobians(q, v, qdd, t, p, VQMatrix<S>* dr_dq,
/// VMatrix<S>* dr_dv)` (QMatrix both without generalized speeds), the exact Jacobians of the
/// inverse-dynamics residual.
template <class M>
inline constexpr bool has_residual_jacobians_v =
    detail::detected_v<M, detail::residual_jacobians_op>;

/// Inverse dynamics: the generalized force tau = Mt(q, t) qdd - Ft(q, v, t) - Fi(q, v, t)
/// that makes model M accelerate at qdd. For a robot arm in joint angles it is the joint
/// torque; at qdd = acceleration<M>(p, q, v, t) it is zero (to round-off).
/// Uses the generated kernel M::inverse_dynamics where the model has one, else
/// M::mass_matrix(q, t) qdd - M::forces(q, v, t) (same value, two kernel calls).
/// \param[in] p    The model parameters.
/// \param[in] q    The generalized coordinates (dim M::nq).
/// \param[in] v    The generalized velocities or speeds (dim nv_of_v<M>).
/// \param[in] qdd  Their rates v' (dim nv_of_v<M>).
/// \param[in] t    The time.
/// \return tau (dim nv_of_v<M>). Throws nothing; NaN/inf in the inputs propagate to the result.
template <class M>
VVec<M> inverse_dynamics(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v,
                         const VVec<M>& qdd, double t) {
  static_assert(assert_model_v<M>);
  if constexpr (has_inverse_dynamics_v<M>) {
    return M::inverse_dynamics(q, v, qdd, t, p);
  } else {
    return M::mass_matrix(q, t, p) * qdd - M::forces(q, v, t, p);
  }
}

/// Exact Jacobians of the residual r(q, v, qdd, t) of inverse_dynamics(): dr/dq and dr/dv,
/// (dim nv x nq and nv x nv); dr/dqdd is M::mass_matrix(q, t). Compiles only for models that
/// emit M::residual_jacobians (has_residual_jacobians_v<M>).
/// \param[out] r_D_q  dr/dq (dim nv x nq); must not be null.
/// \param[out] r_D_v  dr/dv (dim nv x nv); must not be null.
/// Throws nothing; NaN/inf in the inputs propagate to the result.
template <class M>
void residual_jacobians(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v,
                        const VVec<M>& qdd, double t, VQMat<M>* r_D_q, VMat<M>* r_D_v) {
  static_assert(has_residual_jacobians_v<M>,
                "gencoord: this model does not emit residual_jacobians(q, v, qdd, t, p, "
                "dr_dq, dr_dv); regenerate it with the current generator");
  M::residual_jacobians(q, v, qdd, t, p, r_D_q, r_D_v);
}

}  // namespace gencoord
