// SPDX-License-Identifier: BSD-3-Clause
// The inverse map: from a maximal state (x, xdot) at time t to the reduced state (q, v).
//
// q minimizes |x - X(q, t)|_2 (Gauss-Newton with the generated J from a guess q0, with a
// backtracking line search; Newton with a finite-difference curvature term far off the manifold); v
// is the mass-weighted least-squares solution of J v = xdot - X_t, i.e. Mt v = J^T M (xdot - X_t)
// with X_t = velocities(q, 0, t). On the manifold this recovers (q, v) exactly; off it, q is the
// closest point (the maximal model uses that for its manifold spring and for mapping generalized
// forces). J = d xdot / d v has a column per speed: the iterations step in the speeds' local
// coordinates, q + dq where the speeds are the rates, retract(q, dq) (tangent_space.hpp) for a
// model with generalized speeds, whose quaternions so stay unit.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/QR>

#include "gencoord/maximal/errors.hpp"
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/model/tangent_space.hpp"

namespace gencoord {

namespace detail {
// q moved by dq along the speeds (nv): q + dq where the speeds are the rates, else retract()
template <class M>
QVec<M> moved_along_speeds(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& dq, double t) {
  if constexpr (has_generalized_speeds_v<M>) return retract<M>(p, q, dq, t);
  else return q + dq;
}
}  // namespace detail

/// Settings of the inverse map.
struct InverseMapOptions {
  /// Gauss-Newton iterations allowed before InverseMapError (kNotConverged).
  int max_iterations = 50;
  /// Converged when the last step dq (nv, along the speeds) satisfies
  /// |dq|_inf <= step_tolerance * (1 + |q|_inf).
  double step_tolerance = 1e-13;
  /// Largest |x - X(q, t)|_2 accepted at the solution (length units); a point farther from the
  /// manifold throws InverseMapError (kOffManifold). Infinity accepts the closest point of any x.
  double max_residual = 1e-6;
};

/// The result of inverse_map_positions().
template <class M>
struct InversePositions {
  QVec<M> q;              // the closest point's coordinates (nq)
  double residual = 0.0;  // |x - X(q, t)|_2
  int iterations = 0;     // Gauss-Newton iterations performed
};

/// Coordinates q minimizing |x - X(q, t)|_2 from q0: Gauss-Newton steps near the manifold,
/// Newton steps (curvature term by central differences of J) farther than 1e-6 (1 + |x|) from
/// it, each with an Armijo backtracking line search.
/// \param[in] p        The model parameters.
/// \param[in] x        Particle positions (nx).
/// \param[in] t        The time.
/// \param[in] q0       The initial guess (nq); the solution is the local minimum nearest to it
///                     (angles are not wrapped: the branch is q0's).
/// \param[in] options  Iteration limits and the residual accepted.
/// \return q, the residual and the iteration count.
/// \throws InverseMapError: kNotConverged when the iterations run out or no descent step is
///         found; kOffManifold when the residual exceeds options.max_residual; kSingular when
///         J is rank deficient or anything is NaN/inf.
template <class M>
InversePositions<M> inverse_map_positions(const ParamsOf<M>& p, const XVec<M>& x, double t,
                                          const QVec<M>& q0,
                                          const InverseMapOptions& options = {}) {
  static_assert(assert_model_v<M>);
  using Reason = InverseMapError::Reason;
  InversePositions<M> out;
  out.q = q0;
  XVec<M> r = x - M::positions(out.q, t, p);
  double f = r.norm();
  auto fail = [&](Reason reason) {
    throw InverseMapError(M::name, reason, t, f, out.iterations, options.max_residual);
  };
  if (!std::isfinite(f) || !q0.allFinite()) fail(Reason::kSingular);
  while (true) {
    if (out.iterations >= options.max_iterations) fail(Reason::kNotConverged);
    ++out.iterations;
    // Gauss-Newton step: least squares J dq = r (rank-revealing, so singular J is caught)
    const XJac<M> J = M::jacobian(out.q, t, p);
    const Eigen::ColPivHouseholderQR<PlainOf<XJac<M>>> qr(J);
    if (!J.allFinite() || qr.rank() < nv_of_v<M>) fail(Reason::kSingular);
    VVec<M> dq = qr.solve(r);
    // far from the manifold Gauss-Newton converges only linearly (slowly where the manifold is
    // curved): there, take Newton's step with the curvature term of the Hessian,
    // H = J^T J - sum_i r_i d2X_i/dq2, the second term by central differences of J^T r
    if (f > 1e-6 * (1.0 + x.template lpNorm<Eigen::Infinity>())) {
      VMat<M> H = J.transpose() * J;
      VVec<M> e = VVec<M>::Zero();
      for (int j = 0; j < nv_of_v<M>; ++j) {
        const double h =
            1e-5 * (1.0 + (has_generalized_speeds_v<M> ? out.q.template lpNorm<Eigen::Infinity>()
                                                       : std::abs(out.q(j))));
        e(j) = h;
        const QVec<M> qp = detail::moved_along_speeds<M>(p, out.q, e, t);
        const QVec<M> qm = detail::moved_along_speeds<M>(p, out.q, (-e).eval(), t);
        e(j) = 0.0;
        H.col(j) -= (M::jacobian(qp, t, p) - M::jacobian(qm, t, p)).transpose() * r / (2.0 * h);
      }
      const Eigen::LLT<PlainOf<VMat<M>>> llt(0.5 * (H + H.transpose()));
      if (llt.info() == Eigen::Success) {  // else beyond a focal point: keep Gauss-Newton's
        const VVec<M> newton = llt.solve(J.transpose() * r);
        if (newton.allFinite()) dq = newton;
      }
    }
    if (!dq.allFinite()) fail(Reason::kSingular);
    const double dq_norm = dq.template lpNorm<Eigen::Infinity>();
    if (dq_norm <= options.step_tolerance * (1.0 + out.q.template lpNorm<Eigen::Infinity>())) {
      out.q = detail::moved_along_speeds<M>(p, out.q, dq, t);
      r = x - M::positions(out.q, t, p);
      f = r.norm();
      break;
    }
    // step control (Armijo on |r|^2, halving): the predicted decrease of |r|^2 is
    // 2 (J^T r) . dq; once it is below the rounding noise of |r|^2 (r = x - X has absolute
    // noise ~ 1e-14 |x|), the full step is taken as is
    const double predicted = 2.0 * (J.transpose() * r).dot(dq);
    if (!(predicted > 0.0) && dq_norm > 0.0) fail(Reason::kNotConverged);  // not a descent step
    const double noise = 1e-14 * (1.0 + x.template lpNorm<Eigen::Infinity>());
    const bool unresolvable = 1e-4 * predicted <= 2.0 * f * noise + noise * noise;
    double alpha = 1.0;
    bool accepted = false;
    for (int halvings = 0; halvings < 40 && !accepted; ++halvings, alpha *= 0.5) {
      const QVec<M> q_try = detail::moved_along_speeds<M>(p, out.q, (alpha * dq).eval(), t);
      const XVec<M> r_try = x - M::positions(q_try, t, p);
      const double f_try = r_try.norm();
      if (std::isfinite(f_try) &&
          (unresolvable || (f_try < f && f_try * f_try <= f * f - 1e-4 * alpha * predicted))) {
        out.q = q_try;
        r = r_try;
        f = f_try;
        accepted = true;
      }
    }
    if (!accepted) fail(Reason::kNotConverged);
  }
  out.residual = f;
  if (!(f <= options.max_residual)) fail(Reason::kOffManifold);
  return out;
}

/// Generalized velocities v at q: the mass-weighted least-squares solution of
/// J v = xdot - X_t, i.e. Mt v = J^T M (xdot - X_t), with X_t = velocities(q, 0, t).
/// \param[in] p     The model parameters.
/// \param[in] q     Generalized coordinates (nq), e.g. from inverse_map_positions().
/// \param[in] xdot  Particle velocities (nx).
/// \param[in] t     The time.
/// \return v (nv).
/// \throws InverseMapError (kSingular) when Mt is not positive definite or v is not finite.
template <class M>
VVec<M> inverse_map_velocities(const ParamsOf<M>& p, const QVec<M>& q, const XVec<M>& xdot,
                               double t) {
  static_assert(assert_model_v<M>);
  const XJac<M> J = M::jacobian(q, t, p);
  const XVec<M> x_t = M::velocities(q, VVec<M>::Zero().eval(), t, p);
  const XVec<M> m = coordinate_masses<M>(p);
  const VMat<M> Mt = J.transpose() * m.asDiagonal() * J;
  const Eigen::LLT<PlainOf<VMat<M>>> llt(Mt);
  VVec<M> v = VVec<M>::Zero();
  if (llt.info() == Eigen::Success) v = llt.solve(J.transpose() * (m.asDiagonal() * (xdot - x_t)));
  if (llt.info() != Eigen::Success || !v.allFinite())
    throw InverseMapError(M::name, InverseMapError::Reason::kSingular, t,
                          std::numeric_limits<double>::quiet_NaN(), 0,
                          std::numeric_limits<double>::quiet_NaN());
  return v;
}

/// The reduced state (t, q, v) of a maximal state (x, xdot) at time t: q by
/// inverse_map_positions() from q0, then v by inverse_map_velocities().
/// \param[in] p        The model parameters.
/// \param[in] x        Particle positions (nx).
/// \param[in] xdot     Particle velocities (nx).
/// \param[in] t        The time.
/// \param[in] q0       The initial guess for q (nq).
/// \param[in] options  Iteration limits and the residual accepted.
/// \return The reduced state at time t.
/// \throws InverseMapError as inverse_map_positions() and inverse_map_velocities().
template <class M>
State<M> inverse_map(const ParamsOf<M>& p, const XVec<M>& x, const XVec<M>& xdot, double t,
                     const QVec<M>& q0, const InverseMapOptions& options = {}) {
  State<M> s;
  s.t = t;
  s.q = inverse_map_positions<M>(p, x, t, q0, options).q;
  s.v = inverse_map_velocities<M>(p, s.q, xdot, t);
  return s;
}

}  // namespace gencoord
