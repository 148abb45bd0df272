// SPDX-License-Identifier: BSD-3-Clause
// Forward dynamics with kinematic constraints (closed loops, rolling): the generated model
// gives Mt, the forces f = Ft + Fi, the constraint Jacobian A (m x nv, every constraint at
// the velocity level A v + b = 0) and the bias gamma (A v' + gamma = 0). The acceleration
// and the multipliers lambda solve
//
//   Mt v' = f + A^T lambda,   A v' = -gamma,
//
// by the range-space method: with Y = Mt^-1 A^T and the Schur complement S = A Y (SPD when A
// has full row rank), lambda = -S^-1 (gamma + A Mt^-1 f) and v' = Mt^-1 f + Y lambda. A^T
// lambda is the constraint force in generalized coordinates; lambda itself is in the
// constraint's units (a loop closure x_b - x_a = 0: the force on b, in newtons).
//
// project_onto_constraints() puts a state back on the constraints after a step: Gauss-Newton
// steps of least change on C(q, t) = 0, then the velocity change of least kinetic energy onto
// A v + b = 0. Baumgarte's stabilization is the alternative that changes the dynamics instead
// of the state: it asks A v' + gamma = -2 alpha (A v + b) - beta^2 C, so that drift decays
// like a damped oscillator rather than growing.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gencoord/errors.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/model/tangent_space.hpp"

namespace gencoord {

template <class M>
using CVec = typename M::template CVector<double>;  // (num_constraints)
template <class M>
using CJac = typename M::template CJacobian<double>;  // (num_constraints x nv)

namespace detail {

// Whether an SPD factorization of a Gram matrix (A Mt^-1 A^T, C_q C_q^T) succeeded with no
// pivot below round-off of the largest diagonal entry: a row of A that is a combination of
// the others gives a pivot at the rounding level, which LLT accepts as positive.
template <class Gram, class LLT>
bool independent_rows(const Gram& gram, const LLT& llt) {
  if (llt.info() != Eigen::Success) return false;
  const double largest = gram.diagonal().maxCoeff();
  const auto pivots = llt.matrixLLT().diagonal();
  return (pivots.array() * pivots.array()).minCoeff() >
         64 * std::numeric_limits<double>::epsilon() * largest;
}

template <class M>
using ConstraintGram = Eigen::Matrix<double, M::num_constraints, M::num_constraints>;
template <class M>
using MinvAT = Eigen::Matrix<double, nv_of_v<M>, M::num_constraints>;

// Mt^-1 A^T and the Schur complement S = A Mt^-1 A^T, factored: what the constrained
// acceleration and the velocity projection both solve with. `ok` is false where Mt is not
// positive definite or A's rows are dependent (mass_ok tells which).
template <class M>
struct RangeSpace {
  RangeSpace(const VMat<M>& Mt, const CJac<M>& A) : mass(Mt) {
    mass_ok = mass.info() == Eigen::Success;
    if (!mass_ok) return;
    Y = mass.solve(A.transpose());
    const ConstraintGram<M> S = A * Y;
    schur.compute(S);
    ok = independent_rows(S, schur);
  }
  Eigen::LLT<PlainOf<VMat<M>>> mass;
  MinvAT<M> Y;
  Eigen::LLT<ConstraintGram<M>> schur;
  bool mass_ok = false, ok = false;
};

}  // namespace detail

/// The largest constraint residual at s: max |C| and |A v + b| (drift from the constraints).
template <class M>
double constraint_residual(const ParamsOf<M>& p, const State<M>& s) {
  static_assert(has_kinematic_constraints_v<M>);
  double largest = M::constraint_velocities(s.q, s.v, s.t, p).cwiseAbs().maxCoeff();
  if constexpr (has_holonomic_constraints_v<M>)
    largest = std::max(largest, M::holonomic_constraints(s.q, s.t, p).cwiseAbs().maxCoeff());
  return largest;
}

/// Baumgarte's stabilization: the rates (1/s) of the feedback on the drift, -2 alpha (A v + b)
/// on every constraint and -beta^2 C on the holonomic ones (the first rows). alpha = beta is
/// critically damped; zero (the default) keeps the exact constraint A v' + gamma = 0. Drift
/// then decays in a few 1/alpha instead of growing; it is not removed to round-off, as
/// project_onto_constraints() removes it, and too large a rate makes the system stiff.
struct Baumgarte {
  double alpha = 0.0;
  double beta = 0.0;
  bool active() const { return alpha != 0.0 || beta != 0.0; }
};

/// How a constrained model stays on its constraints during a simulation: each step's end
/// state projected (the default), Baumgarte's feedback in the acceleration, or both.
struct ConstraintStabilization {
  bool project = true;
  Baumgarte baumgarte;
};

/// The constrained generalized acceleration v' of model M, and optionally the multipliers.
/// \param[in]  p         The model parameters.
/// \param[in]  q, v, t   The state (q: nq, v: nv).
/// \param[out] lambda    The multipliers (num_constraints), or nullptr.
/// \param[in]  baumgarte Feedback on the drift (none by default).
/// \throws DynamicsError if Mt is not positive definite, the constraints are dependent at q
///         (kDependentConstraints), or Mt, the forces, A, gamma or the result are not finite.
template <class M>
VVec<M> constrained_acceleration(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v, double t,
                                 CVec<M>* lambda = nullptr, const Baumgarte& baumgarte = {}) {
  static_assert(has_kinematic_constraints_v<M>);
  using Reason = DynamicsError::Reason;
  VMat<M> Mt;
  VVec<M> f;
  M::dynamics(q, v, t, p, &Mt, &f);
  const CJac<M> A = M::constraint_jacobian(q, t, p);
  CVec<M> gamma = M::constraint_bias(q, v, t, p);
  if (baumgarte.active()) {
    gamma += 2 * baumgarte.alpha * M::constraint_velocities(q, v, t, p);
    if constexpr (has_holonomic_constraints_v<M>) {
      gamma.template head<M::num_holonomic_constraints>() +=
          baumgarte.beta * baumgarte.beta * M::holonomic_constraints(q, t, p);
    }
  }
  const detail::RangeSpace<M> solver(Mt, A);
  Reason reason = solver.mass_ok ? Reason::kDependentConstraints : Reason::kNotPositiveDefinite;
  if (solver.ok) {
    VVec<M> a = solver.mass.solve(f);
    const CVec<M> multipliers = solver.schur.solve(-(gamma + A * a));
    a += solver.Y * multipliers;
    if (a.allFinite() && multipliers.allFinite()) {
      if (lambda) *lambda = multipliers;
      return a;
    }
    reason = Reason::kNonFiniteAcceleration;
  }
  // diagnosis, off the hot path
  if (!Mt.allFinite()) reason = Reason::kNonFiniteMassMatrix;
  else if (!f.allFinite()) reason = Reason::kNonFiniteForces;
  else if (!A.allFinite() || !gamma.allFinite()) reason = Reason::kNonFiniteConstraints;
  detail::throw_dynamics_error(M::name, reason, t, q.data(), v.data(), M::nq, nv_of_v<M>);
}

/// The multipliers lambda of the constraints at a state (see constrained_acceleration):
/// A^T lambda is the constraint force on the coordinates.
/// \throws DynamicsError as constrained_acceleration().
template <class M>
CVec<M> constraint_forces(const ParamsOf<M>& p, const State<M>& s) {
  CVec<M> lambda;
  constrained_acceleration<M>(p, s.q, s.v, s.t, &lambda);
  return lambda;
}

/// Puts s back on the constraints: Gauss-Newton steps dq = -C_q^T (C_q C_q^T)^-1 C on the
/// holonomic ones until a step is at round-off (at most `max_steps`), then
/// v -= Y S^-1 (A v + b), the velocity change of least kinetic energy that satisfies every
/// constraint. A state within the integrator's error of the constraints needs one or two
/// steps. Leaves s unchanged where Mt or the constraint Gram matrices are singular (the
/// dynamics report that on the next evaluation).
template <class M>
void project_onto_constraints(const ParamsOf<M>& p, State<M>* s, int max_steps = 8) {
  static_assert(has_kinematic_constraints_v<M>);
  constexpr double eps = std::numeric_limits<double>::epsilon();
  if constexpr (has_holonomic_constraints_v<M>) {
    using Gram = Eigen::Matrix<double, M::num_holonomic_constraints, M::num_holonomic_constraints>;
    for (int step = 0; step < max_steps; ++step) {
      const auto C = M::holonomic_constraints(s->q, s->t, p);
      const auto C_q = M::holonomic_jacobian(s->q, s->t, p);
      const Gram product = C_q * C_q.transpose();
      const Eigen::LLT<Gram> gram(product);
      if (!detail::independent_rows(product, gram)) break;
      const QVec<M> dq = -C_q.transpose() * gram.solve(C);
      if (!dq.allFinite()) break;
      s->q += dq;
      detail::normalize_quaternions<M>(&s->q);
      if (dq.template lpNorm<Eigen::Infinity>() <=
          4 * eps * (1 + s->q.template lpNorm<Eigen::Infinity>()))
        break;
    }
  }
  const detail::RangeSpace<M> solver(M::mass_matrix(s->q, s->t, p),
                                     M::constraint_jacobian(s->q, s->t, p));
  if (!solver.ok) return;
  const VVec<M> dv = -solver.Y * solver.schur.solve(M::constraint_velocities(s->q, s->v, s->t, p));
  if (dv.allFinite()) s->v += dv;
}

}  // namespace gencoord
