// SPDX-License-Identifier: BSD-3-Clause
// Explicit one-step methods on y = (q, v), ydot = (v, a(t, q, v)), for any system
// (system.hpp): the Runge-Kutta methods from their coefficient (Butcher) tables, and
// symplectic Euler, which is a partitioned method and has no such table.
// Stage states get their prescribed entries from S::impose() at the stage time, so the
// stage velocities are the prescribed ones. The stage derivative of q is coordinate_rate() of
// the stage state (its v, unless the system has generalized speeds; system.hpp).
#pragma once

#include <array>
#include <type_traits>
#include <utility>

#include "gencoord/integrate/system.hpp"

namespace gencoord {

/// An explicit Runge-Kutta method of `Stages` stages: c_i = sum_j a_ij, and the weights are
/// b_i / b_denominator (integers over a common denominator keep RK4's sum exact as written).
template <int Stages>
struct ButcherTableau {
  std::array<std::array<double, Stages>, Stages> a;  // strictly lower triangular
  std::array<double, Stages> b;
  double b_denominator;
  std::array<double, Stages> c;
};

/// Forward Euler: y1 = y0 + h f(t0, y0). First order.
inline constexpr ButcherTableau<1> kForwardEulerTableau{{{{0.0}}}, {1.0}, 1.0, {0.0}};

/// Classical fourth-order Runge-Kutta.
inline constexpr ButcherTableau<4> kRK4Tableau{
    {{{0.0, 0.0, 0.0, 0.0}, {0.5, 0.0, 0.0, 0.0}, {0.0, 0.5, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}}},
    {1.0, 2.0, 2.0, 1.0},
    6.0,
    {0.0, 0.5, 0.5, 1.0}};

/// One step of size h of the explicit Runge-Kutta method `tableau` from s.
/// \throws what S::acceleration() and S::impose() throw.
template <class S, int Stages>
typename S::State explicit_rk_step(const S& system, const ButcherTableau<Stages>& tableau,
                                   const typename S::State& s, double h) {
  using State = typename S::State;
  using QVector = std::decay_t<decltype(std::declval<State&>().q)>;
  using VVector = std::decay_t<decltype(std::declval<State&>().v)>;
  State s0 = s;
  system.impose(&s0);
  // stage derivatives: of q (the stage velocity) and of v (the stage acceleration)
  std::array<QVector, Stages> kq;
  std::array<VVector, Stages> kv;
  // stage 0 (c_0 = 0, no a_0j) is s0 itself
  kq[0] = coordinate_rate(system, s0);
  kv[0] = system.acceleration(s0);
  for (int i = 1; i < Stages; ++i) {
    State y = s0;
    y.t = s0.t + tableau.c[i] * h;
    for (int j = 0; j < i; ++j) {
      if (tableau.a[i][j] == 0.0) continue;
      y.q += (tableau.a[i][j] * h) * kq[j];
      y.v += (tableau.a[i][j] * h) * kv[j];
    }
    system.impose(&y);
    kq[i] = coordinate_rate(system, y);
    kv[i] = system.acceleration(y);
  }
  QVector dq = tableau.b[0] * kq[0];
  VVector dv = tableau.b[0] * kv[0];
  for (int i = 1; i < Stages; ++i) {
    dq += tableau.b[i] * kq[i];
    dv += tableau.b[i] * kv[i];
  }
  State out = s0;
  out.t = s.t + h;
  out.q = s0.q + (h / tableau.b_denominator) * dq;
  out.v = s0.v + (h / tableau.b_denominator) * dv;
  system.impose(&out);
  return out;
}

/// Forward Euler. \throws as explicit_rk_step().
template <class S>
typename S::State forward_euler_step(const S& system, const typename S::State& s, double h) {
  return explicit_rk_step(system, kForwardEulerTableau, s, h);
}

/// Classical RK4. \throws as explicit_rk_step().
template <class S>
typename S::State rk4_step(const S& system, const typename S::State& s, double h) {
  return explicit_rk_step(system, kRK4Tableau, s, h);
}

/// Symplectic (semi-implicit) Euler: v1 = v0 + h a(t0, q0, v0), then q1 = q0 + h v1
/// (q1 = q0 + h G(q0) v1 with generalized speeds). First order; symplectic when a does not
/// depend on v (and v = q').
/// \throws as explicit_rk_step().
template <class S>
typename S::State symplectic_euler_step(const S& system, const typename S::State& s, double h) {
  typename S::State s0 = s;
  system.impose(&s0);
  typename S::State out = s0;
  out.t = s.t + h;
  out.v = s0.v + h * system.acceleration(s0);
  out.q = s0.q + h * coordinate_rate(system, out);  // out.q is still q0: G(q0) v1
  system.impose(&out);
  return out;
}

}  // namespace gencoord
