// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler for any system (system.hpp), and the trapezoidal rule and implicit midpoint
// built from its half steps, not as separate solvers.
//
// Newton on the free end velocities v1:
//   g(v1) = m (v1 - v0) - h F(t1, q0 + h v1, v1),    dg/dv1 = m - h (h dF/dq + dF/dv),
// m the system's diagonal mass (1 for a unit-mass system, whose F is the acceleration).
// Prescribed entries of q1 and v1 come from S::impose() at t1.
//
// With generalized speeds (system.hpp, coordinate_rate) the end coordinates solve
// q1 = q0 + h G(q1) v1 for the current v1 by fixed-point iteration, a contraction for
// h |dG/dq v1| < 1. G at q1, not q0: the trapezoidal rule and implicit midpoint are built from
// these half steps, and G(q0) there would leave an O(h^2) local error in q (first order).
// The Newton Jacobian takes dq1/dv1 as h G, with the system's dF/dq already multiplied by G
// at the linearization state (quasi-Newton; its error is O(h) relative, which costs at most
// an iteration).
#pragma once

#include "gencoord/errors.hpp"
#include "gencoord/integrate/explicit_rk.hpp"
#include "gencoord/integrate/newton.hpp"
#include "gencoord/integrate/system.hpp"

namespace gencoord {

namespace detail {

// the most fixed-point iterations for q1 = q0 + h G(q1) v1: at h |dG/dq v1| = 1/2 each gains a
// bit, and a step that needs more is too large for its rotation rate anyway
inline constexpr int kMaxCoordinateIterations = 60;

// s1->q = q0 + h qdot for the end velocity s1->v: qdot = v1, or with generalized speeds
// G(q1) v1 at the end coordinates themselves (fixed point from the current s1->q).
// \throws NewtonError if the fixed-point iteration does not settle.
template <class S>
void end_coordinates(const S& system, const typename S::State& s0, double h,
                     typename S::State* s1) {
  if constexpr (has_coordinate_rate_v<S>) {
    constexpr double tolerance = 8 * std::numeric_limits<double>::epsilon();
    for (int k = 1;; ++k) {
      const auto q1 = (s0.q + h * coordinate_rate(system, *s1)).eval();
      // each entry to 8 ulps of its own size (round-off in G(q) v alone moves it by a few):
      // a base metres from the origin must not loosen its quaternion's test
      double change = 0.0;
      for (Eigen::Index i = 0; i < q1.size(); ++i) {
        const double relative = std::abs(q1[i] - s1->q[i]) / (1.0 + std::abs(q1[i]));
        change = std::isfinite(relative) ? std::max(change, relative)
                                         : std::numeric_limits<double>::infinity();
      }
      s1->q = q1;
      if (change <= tolerance) break;
      if (k == kMaxCoordinateIterations || !std::isfinite(change))
        throw_newton_error(system.name(), s0.t, h, k, change, change, tolerance, 1.0, tolerance);
    }
  } else {
    s1->q = s0.q + h * s1->v;
  }
  system.impose(s1);
}

}  // namespace detail

/// Backward Euler: y1 = y0 + h f(t0 + h, y1). First order, L-stable (damps energy).
/// Newton from v1 = v0 (see the file comment); options.linearized takes one update of the
/// equation linearized about the start state (linearly implicit Euler). q1 = q0 + h v1, or
/// q1 = q0 + h G(q1) v1 for a system with generalized speeds.
/// \param[in]     system   The system.
/// \param[in]     s        The state at the start of the step.
/// \param[in]     h        The step size.
/// \param[in]     options  Newton settings.
/// \param[in,out] stats    Work counters; may be null.
/// \throws NewtonError if Newton does not converge (update and residual tests, NewtonOptions)
///         in options.max_iterations updates, or its Jacobian is singular or not finite;
///         std::invalid_argument for bad options; what the system's linearize() and
///         acceleration() throw (DynamicsError, ...).
template <class S>
typename S::State backward_euler_step(const S& system, const typename S::State& s, double h,
                                      const NewtonOptions& options = {},
                                      StepStats* stats = nullptr) {
  using Unknowns = typename S::Unknowns;
  using Matrix = typename S::Matrix;
  typename S::State s0 = s;
  system.impose(&s0);
  typename S::State s1 = s0;
  s1.t = s.t + h;
  system.impose(&s1);
  Linearization<S> lin;
  const Unknowns v0 = system.free_part(s0.v);
  const bool nothing_to_solve = v0.size() == 0;
  // the terms of the residual's scale that do not change over the iteration: 1 + |v0|
  // (unit mass) or |m| + |m v0|
  double start_scale = 0.0;
  if constexpr (S::unit_mass) {
    start_scale = 1.0 + detail::max_abs(v0);
  } else {
    const Unknowns& m = system.masses();
    start_scale = detail::max_abs(m) + detail::max_abs(m.cwiseProduct(v0).eval());
  }
  // g = m (v1 - v0) - h F and its scale (NewtonOptions::residual_tolerance) at the iterate s1
  auto residual_of = [&](const Unknowns& force, Unknowns* g) {
    const Unknowns v1 = system.free_part(s1.v);
    NewtonResidual r;
    if constexpr (S::unit_mass) {
      *g = v1 - v0 - h * force;
      r.scale = start_scale + detail::max_abs(v1);
    } else {
      const Unknowns& m = system.masses();
      *g = m.cwiseProduct(v1 - v0) - h * force;
      r.scale = start_scale + detail::max_abs(m.cwiseProduct(v1).eval());
    }
    r.scale += std::abs(h) * detail::max_abs(force);
    r.norm = detail::max_abs(*g);
    return r;
  };
  auto update = [&] {
    // residual and its Jacobian at the current iterate
    detail::end_coordinates(system, s0, h, &s1);
    if (options.linearized) {
      // linearly implicit Euler: F(q0 + h v1, v1) taken as F(q0, v1) + h dF/dq v1, so the one
      // update solves (m - h dF/dv - h^2 dF/dq) dv = h (F0 + h dF/dq v0) about the start state,
      // whose prescribed entries are those at t1 (F0 carries their motion over the step)
      typename S::State start = s1;
      start.q = s0.q;
      system.impose(&start);
      system.linearize(start, options.jacobian, &lin);
      lin.force += h * (lin.force_D_q * system.free_part(s1.v));
    } else {
      system.linearize(s1, options.jacobian, &lin);
    }
    Matrix g_D_v = -h * (h * lin.force_D_q + lin.force_D_v);
    if constexpr (S::unit_mass) {
      g_D_v += Unknowns::Ones(v0.size()).asDiagonal();
    } else {
      g_D_v += system.masses().asDiagonal();
    }
    Unknowns g;
    NewtonUpdate norms;
    norms.residual = residual_of(lin.force, &g);
    // Newton update; a singular Jacobian shows up as a non-finite update
    Unknowns dv;
    norms.update_norm = std::numeric_limits<double>::infinity();
    if (system.solve(g_D_v, g, &dv)) {
      dv = -dv;
      norms.update_norm = detail::max_abs(dv);
      if (std::isfinite(norms.update_norm)) system.add_to_free(dv, &s1.v);
    }
    norms.velocity_norm = detail::max_abs(s1.v);
    return norms;
  };
  // the residual test after an update that passed the update test: the force at the new iterate
  auto residual = [&] {
    detail::end_coordinates(system, s0, h, &s1);
    Unknowns force = system.free_part(system.acceleration(s1));
    if constexpr (!S::unit_mass) force = system.masses().cwiseProduct(force);
    Unknowns g;
    return residual_of(force, &g);
  };
  detail::newton_iterate(system.name(), s.t, h, options, stats, nothing_to_solve, update, residual);
  detail::end_coordinates(system, s0, h, &s1);
  return s1;
}

namespace detail {

// A step of h as two half steps, `first` then `second` (each called as (state, h / 2)); it
// ends at exactly s.t + h, not (t0 + h/2) + h/2, which may differ in the last bit.
template <class S, class First, class Second>
typename S::State two_half_steps(const S& system, const typename S::State& s, double h,
                                 First&& first, Second&& second) {
  typename S::State out = second(first(s, 0.5 * h), 0.5 * h);
  out.t = s.t + h;
  system.impose(&out);
  return out;
}

}  // namespace detail

/// Trapezoidal rule y1 = y0 + h/2 (f(t0, y0) + f(t0 + h, y1)), built as a forward-Euler half
/// step (h/2 from t0) followed by a backward-Euler half step (h/2, ending at t0 + h).
/// Second order, A-stable. \throws as backward_euler_step().
template <class S>
typename S::State trapezoidal_step(const S& system, const typename S::State& s, double h,
                                   const NewtonOptions& options = {}, StepStats* stats = nullptr) {
  using State = typename S::State;
  return detail::two_half_steps(
      system, s, h, [&](const State& y, double k) { return forward_euler_step(system, y, k); },
      [&](const State& y, double k) { return backward_euler_step(system, y, k, options, stats); });
}

/// Implicit midpoint y1 = y0 + h f(t0 + h/2, (y0 + y1) / 2), built as a backward-Euler half
/// step (h/2 from t0, giving the midpoint state) followed by a forward-Euler half step (h/2)
/// from the midpoint. Second order, symplectic, A-stable. \throws as backward_euler_step().
template <class S>
typename S::State implicit_midpoint_step(const S& system, const typename S::State& s, double h,
                                         const NewtonOptions& options = {},
                                         StepStats* stats = nullptr) {
  using State = typename S::State;
  return detail::two_half_steps(
      system, s, h,
      [&](const State& y, double k) { return backward_euler_step(system, y, k, options, stats); },
      [&](const State& y, double k) { return forward_euler_step(system, y, k); });
}

}  // namespace gencoord
