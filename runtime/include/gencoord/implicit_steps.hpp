// Implicit one-step integrators of y = (q, v), ydot = (v, a(q, v, t)), solved by Newton's
// method on the end velocity. The trapezoidal rule and implicit midpoint are compositions of
// forward and backward Euler half steps (the lecture notes' construction), not separate solvers.
//
// Newton is assembled on g(v1) = v1 - v0 - h a(q0 + h v1, v1, t1) with
// dg/dv1 = I - h (h da/dq + da/dv), where da/dq = -Mt^-1 dr/dq and da/dv = -Mt^-1 dr/dv come
// from the generated residual Jacobians (acceleration_jacobians.hpp) by default. Assembling it
// directly on the residual, r(q0 + h v1, v1, (v1 - v0) / h) = 0 with Jacobian
// h dr/dq + dr/dv + Mt / h, would save the two triangular solves, but it is a different Newton
// map: keeping this one means NewtonOptions::jacobian changes only the Jacobian, so generated
// and finite-difference iteration counts compare like with like.
#pragma once

#include <Eigen/LU>

#include "gencoord/acceleration_jacobians.hpp"
#include "gencoord/dynamics.hpp"
#include "gencoord/errors.hpp"
#include "gencoord/explicit_steps.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/newton.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

/// Backward Euler: y1 = y0 + h f(y1, t0 + h). First order, L-stable (damps energy).
/// Solves g(v1) = v1 - v0 - h a(q0 + h v1, v1, t0 + h) = 0 by Newton from v1 = v0, with
/// dg/dv1 = I - h (h da/dq + da/dv) from acceleration_and_jacobians() with
/// options.jacobian; then q1 = q0 + h v1.
/// \param[in]     p        The model parameters.
/// \param[in]     s        The state at the start of the step.
/// \param[in]     h        The step size.
/// \param[in]     options  Newton settings.
/// \param[in,out] stats    Work counters; may be null.
/// \throws NewtonError if Newton does not converge in options.max_iterations updates (or its
///         Jacobian is singular or not finite); DynamicsError if the dynamics fail at an
///         iterate; std::invalid_argument if options.max_iterations < 1 or
///         options.tolerance < 0, or options.jacobian is Generated and M has no
///         residual_jacobians().
template <class M>
State<M> backward_euler_step(const ParamsOf<M>& p, const State<M>& s, double h,
                             const NewtonOptions& options = {}, StepStats* stats = nullptr) {
  const double t1 = s.t + h;
  QVec<M> v1 = s.v;
  QVec<M> a;
  QMat<M> a_D_q, a_D_v;
  detail::newton_iterate(M::name, s.t, h, options, stats, false, [&] {
    // residual and its Jacobian at the current iterate
    const QVec<M> q1 = s.q + h * v1;
    acceleration_and_jacobians<M>(p, q1, v1, t1, options.jacobian, &a, &a_D_q, &a_D_v);
    const QVec<M> g = v1 - s.v - h * a;
    const QMat<M> g_D_v = QMat<M>::Identity() - h * (h * a_D_q + a_D_v);
    // Newton update; a singular Jacobian shows up as a non-finite update
    const QVec<M> dv = -g_D_v.partialPivLu().solve(g);
    NewtonUpdate norms{g.template lpNorm<Eigen::Infinity>(),
                       dv.template lpNorm<Eigen::Infinity>(), 0.0};
    if (dv.allFinite()) v1 += dv;
    norms.velocity_norm = v1.template lpNorm<Eigen::Infinity>();
    return norms;
  });
  State<M> out;
  out.t = t1;
  out.q = s.q + h * v1;
  out.v = v1;
  return out;
}

/// Trapezoidal rule y1 = y0 + h/2 (f(y0, t0) + f(y1, t0 + h)), built as a forward-Euler half
/// step (h/2 from t0) followed by a backward-Euler half step (h/2, ending at t0 + h).
/// Second order, A-stable.
/// \throws NewtonError, DynamicsError as backward_euler_step().
template <class M>
State<M> trapezoidal_step(const ParamsOf<M>& p, const State<M>& s, double h,
                          const NewtonOptions& options = {}, StepStats* stats = nullptr) {
  const State<M> half = forward_euler_step<M>(p, s, 0.5 * h);
  State<M> out = backward_euler_step<M>(p, half, 0.5 * h, options, stats);
  out.t = s.t + h;  // not (t0 + h/2) + h/2, which may differ in the last bit
  return out;
}

/// Implicit midpoint y1 = y0 + h f((y0 + y1) / 2, t0 + h/2), built as a backward-Euler half
/// step (h/2 from t0, giving the midpoint state) followed by a forward-Euler half step (h/2)
/// from the midpoint. Second order, symplectic, A-stable.
/// \throws NewtonError, DynamicsError as backward_euler_step().
template <class M>
State<M> implicit_midpoint_step(const ParamsOf<M>& p, const State<M>& s, double h,
                                const NewtonOptions& options = {}, StepStats* stats = nullptr) {
  const State<M> mid = backward_euler_step<M>(p, s, 0.5 * h, options, stats);
  State<M> out = forward_euler_step<M>(p, mid, 0.5 * h);
  out.t = s.t + h;
  return out;
}

}  // namespace gencoord
