// Explicit one-step integrators of y = (q, v), ydot = (v, a(q, v, t)).
// Each takes one step of size h from s (at time s.t) and returns the state at s.t + h.
#pragma once

#include "gencoord/dynamics.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

/// Forward Euler: y1 = y0 + h f(y0, t0). First order.
/// \throws DynamicsError if the dynamics fail at s.
template <class M>
State<M> forward_euler_step(const ParamsOf<M>& p, const State<M>& s, double h) {
  const QVec<M> a = acceleration<M>(p, s.q, s.v, s.t);
  State<M> out;
  out.t = s.t + h;
  out.q = s.q + h * s.v;
  out.v = s.v + h * a;
  return out;
}

/// Symplectic (semi-implicit) Euler: v1 = v0 + h a(q0, v0, t0), then q1 = q0 + h v1.
/// First order; symplectic when a does not depend on v.
/// \throws DynamicsError if the dynamics fail at s.
template <class M>
State<M> symplectic_euler_step(const ParamsOf<M>& p, const State<M>& s, double h) {
  State<M> out;
  out.t = s.t + h;
  out.v = s.v + h * acceleration<M>(p, s.q, s.v, s.t);
  out.q = s.q + h * out.v;
  return out;
}

/// Classical fourth-order Runge-Kutta.
/// \throws DynamicsError if the dynamics fail at any stage.
template <class M>
State<M> rk4_step(const ParamsOf<M>& p, const State<M>& s, double h) {
  const double half = 0.5 * h;
  // stages: k_q = velocity, k_v = acceleration
  const QVec<M>& k1q = s.v;
  const QVec<M> k1v = acceleration<M>(p, s.q, s.v, s.t);
  const QVec<M> k2q = s.v + half * k1v;
  const QVec<M> k2v = acceleration<M>(p, s.q + half * k1q, k2q, s.t + half);
  const QVec<M> k3q = s.v + half * k2v;
  const QVec<M> k3v = acceleration<M>(p, s.q + half * k2q, k3q, s.t + half);
  const QVec<M> k4q = s.v + h * k3v;
  const QVec<M> k4v = acceleration<M>(p, s.q + h * k3q, k4q, s.t + h);
  State<M> out;
  out.t = s.t + h;
  out.q = s.q + (h / 6.0) * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
  out.v = s.v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  return out;
}

}  // namespace gencoord
