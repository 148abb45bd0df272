// Every integrator with scripted coordinates (ScriptedModel): the free coordinates are
// integrated, the scripted ones are set from the script at each stage time.
//
// Explicit steps: the same formulas as explicit_steps.hpp on the full state, with the scripted
// q and v overwritten by the script at every stage and at the end (the stage accelerations
// carry the script's a_s, so nothing else changes).
// Backward Euler: Newton over the free end velocities only,
//   g(v1_f) = v1_f - v0_f - h a_f(q1, v1, t1),  q1_f = q0_f + h v1_f,  (q1_s, v1_s) = script(t1),
//   dg/dv1_f = I - h (h da_f/dq_f + da_f/dv_f)   (free-free blocks, ScriptedModel).
// Trapezoidal and implicit midpoint are built from the half steps as in implicit_steps.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "gencoord/errors.hpp"
#include "gencoord/implicit_steps.hpp"
#include "gencoord/integrators.hpp"
#include "gencoord/scripted_dynamics.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

namespace detail {

// |x|_inf by a plain loop, inf if an entry is NaN or inf (Eigen's vectorized reduction over a
// fixed-capacity dynamic vector trips a false -Warray-bounds in GCC 12)
template <class Vector>
double max_abs(const Vector& x) {
  double m = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) return std::numeric_limits<double>::infinity();
    m = std::max(m, std::abs(x[i]));
  }
  return m;
}

}  // namespace detail

/// Forward Euler with scripted coordinates. The input's scripted entries are ignored (taken
/// from the script at s.t); the output's are the script's at s.t + h.
/// \throws DynamicsError if the dynamics fail; what the script throws.
template <class M>
State<M> scripted_forward_euler_step(const ScriptedModel<M>& sm, const State<M>& s, double h) {
  const State<M> s0 = sm.imposed(s);
  const QVec<M> a = sm.acceleration(s0.q, s0.v, s0.t);
  State<M> out;
  out.t = s.t + h;
  out.q = s0.q + h * s0.v;
  out.v = s0.v + h * a;
  return sm.imposed(out);
}

/// Symplectic Euler with scripted coordinates: v1 = v0 + h a(q0, v0), q1 = q0 + h v1 (free),
/// scripted entries from the script. \throws as scripted_forward_euler_step().
template <class M>
State<M> scripted_symplectic_euler_step(const ScriptedModel<M>& sm, const State<M>& s,
                                        double h) {
  const State<M> s0 = sm.imposed(s);
  State<M> out;
  out.t = s.t + h;
  out.v = s0.v + h * sm.acceleration(s0.q, s0.v, s0.t);
  out.q = s0.q + h * out.v;
  return sm.imposed(out);
}

/// Classical RK4 with scripted coordinates: each stage state has its scripted entries set
/// from the script at the stage time. \throws as scripted_forward_euler_step().
template <class M>
State<M> scripted_rk4_step(const ScriptedModel<M>& sm, const State<M>& s, double h) {
  const double half = 0.5 * h;
  const State<M> s0 = sm.imposed(s);
  // stage states (q, v), scripted entries imposed at the stage time
  auto stage = [&sm](const QVec<M>& q, const QVec<M>& v, double t) {
    State<M> y;
    y.t = t;
    y.q = q;
    y.v = v;
    return sm.imposed(y);
  };
  const QVec<M> k1v = sm.acceleration(s0.q, s0.v, s0.t);
  const State<M> y2 = stage(s0.q + half * s0.v, s0.v + half * k1v, s0.t + half);
  const QVec<M> k2v = sm.acceleration(y2.q, y2.v, y2.t);
  const State<M> y3 = stage(s0.q + half * y2.v, s0.v + half * k2v, s0.t + half);
  const QVec<M> k3v = sm.acceleration(y3.q, y3.v, y3.t);
  const State<M> y4 = stage(s0.q + h * y3.v, s0.v + h * k3v, s0.t + h);
  const QVec<M> k4v = sm.acceleration(y4.q, y4.v, y4.t);
  State<M> out;
  out.t = s.t + h;
  out.q = s0.q + (h / 6.0) * (s0.v + 2.0 * y2.v + 2.0 * y3.v + y4.v);
  out.v = s0.v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  return sm.imposed(out);
}

/// Backward Euler with scripted coordinates: Newton over the free end velocities (see the
/// file comment), Jacobians from options.jacobian, convergence test as backward_euler_step()
/// on the free update.
/// \throws NewtonError if Newton does not converge in options.max_iterations updates;
///         DynamicsError if the dynamics fail at an iterate; std::invalid_argument for bad
///         options (as backward_euler_step()); what the script throws.
template <class M>
State<M> scripted_backward_euler_step(const ScriptedModel<M>& sm, const State<M>& s, double h,
                                      const NewtonOptions& options = {},
                                      StepStats* stats = nullptr) {
  using FreeVector = typename ScriptedModel<M>::FreeVector;
  using FreeMatrix = typename ScriptedModel<M>::FreeMatrix;
  const State<M> s0 = sm.imposed(s);
  const double t1 = s.t + h;
  const ScriptSample at1 = sm.sample(t1);
  // initial guess v1 = v0 on the free entries, the script's v_s(t1) on the scripted ones
  QVec<M> v1 = s0.v;
  sm.impose(at1, nullptr, &v1);
  QVec<M> q1, a;
  FreeMatrix af_D_qf, af_D_vf;
  const bool nothing_to_solve = sm.num_free() == 0;
  detail::newton_iterate(M::name, s.t, h, options, stats, nothing_to_solve, [&] {
    q1 = s0.q + h * v1;
    sm.impose(at1, &q1, nullptr);
    sm.acceleration_and_jacobians(q1, v1, t1, at1, options.jacobian, &a, &af_D_qf, &af_D_vf);
    const FreeVector g = sm.free_part(v1 - s0.v - h * a);
    FreeMatrix g_D_v = -h * (h * af_D_qf + af_D_vf);
    g_D_v.diagonal().array() += 1.0;
    const FreeVector dv = -g_D_v.partialPivLu().solve(g);
    NewtonUpdate norms{detail::max_abs(g), detail::max_abs(dv), 0.0};
    if (std::isfinite(norms.update_norm)) sm.add_to_free(dv, &v1);
    norms.velocity_norm = v1.template lpNorm<Eigen::Infinity>();
    return norms;
  });
  State<M> out;
  out.t = t1;
  out.q = s0.q + h * v1;
  out.v = v1;
  sm.impose(at1, &out.q, nullptr);
  return out;
}

/// Trapezoidal rule with scripted coordinates: scripted forward-Euler half step, then
/// scripted backward-Euler half step. \throws as scripted_backward_euler_step().
template <class M>
State<M> scripted_trapezoidal_step(const ScriptedModel<M>& sm, const State<M>& s, double h,
                                   const NewtonOptions& options = {},
                                   StepStats* stats = nullptr) {
  const State<M> half = scripted_forward_euler_step<M>(sm, s, 0.5 * h);
  State<M> out = scripted_backward_euler_step<M>(sm, half, 0.5 * h, options, stats);
  out.t = s.t + h;
  return sm.imposed(out);
}

/// Implicit midpoint with scripted coordinates: scripted backward-Euler half step, then
/// scripted forward-Euler half step. \throws as scripted_backward_euler_step().
template <class M>
State<M> scripted_implicit_midpoint_step(const ScriptedModel<M>& sm, const State<M>& s,
                                         double h, const NewtonOptions& options = {},
                                         StepStats* stats = nullptr) {
  const State<M> mid = scripted_backward_euler_step<M>(sm, s, 0.5 * h, options, stats);
  State<M> out = scripted_forward_euler_step<M>(sm, mid, 0.5 * h);
  out.t = s.t + h;
  return sm.imposed(out);
}

/// One step of size dt of `integrator` with scripted coordinates; the returned state's
/// scripted entries are the script's at s.t + dt.
/// \param[in]     integrator  Which integrator.
/// \param[in]     sm          The model with its script.
/// \param[in]     s           The state at the start (its scripted entries are ignored).
/// \param[in]     dt          The step size; positive and finite.
/// \param[in]     newton      Newton settings (implicit integrators only).
/// \param[in,out] stats       Work counters, incremented; may be null.
/// \throws StepSizeError if dt is not positive and finite; DynamicsError, NewtonError,
///         std::invalid_argument as the steps; what the script throws.
template <class M>
State<M> scripted_step(Integrator integrator, const ScriptedModel<M>& sm, const State<M>& s,
                       double dt, const NewtonOptions& newton = {},
                       StepStats* stats = nullptr) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw StepSizeError("gencoord: step size must be positive and finite, got dt = " +
                        std::to_string(dt));
  if (stats) ++stats->steps;
  switch (integrator) {
    case Integrator::ForwardEuler:
      return scripted_forward_euler_step<M>(sm, s, dt);
    case Integrator::SymplecticEuler:
      return scripted_symplectic_euler_step<M>(sm, s, dt);
    case Integrator::RK4:
      return scripted_rk4_step<M>(sm, s, dt);
    case Integrator::BackwardEuler:
      return scripted_backward_euler_step<M>(sm, s, dt, newton, stats);
    case Integrator::Trapezoidal:
      return scripted_trapezoidal_step<M>(sm, s, dt, newton, stats);
    case Integrator::ImplicitMidpoint:
      return scripted_implicit_midpoint_step<M>(sm, s, dt, newton, stats);
  }
  throw std::invalid_argument("gencoord: invalid Integrator value " +
                              std::to_string(static_cast<int>(integrator)));
}

}  // namespace gencoord
