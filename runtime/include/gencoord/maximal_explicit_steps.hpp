// Explicit steps of the maximal model: y = (x, xdot), ydot = (xdot, M^-1 F(x, xdot, t)).
// Each takes one step of size h from s and returns the state at s.t + h. Neither checks for
// divergence (simulate_maximal() does); see maximal_stability.hpp for their step limits.
#pragma once

#include "gencoord/maximal_model.hpp"
#include "gencoord/maximal_state.hpp"

namespace gencoord {

/// Symplectic (semi-implicit) Euler: xdot1 = xdot0 + h M^-1 F(x0, xdot0, t0), x1 = x0 + h xdot1.
/// First order; stable for h <= 2 / omega_max (symplectic_euler_stable_step()).
/// \throws InverseMapError as MaximalModel::force().
template <class M>
MaximalState<M> maximal_symplectic_euler_step(const MaximalModel<M>& model,
                                              const MaximalState<M>& s, double h) {
  MaximalState<M> out;
  out.t = s.t + h;
  out.xdot = s.xdot + h * model.acceleration(s.x, s.xdot, s.t);
  out.x = s.x + h * out.xdot;
  return out;
}

/// Classical fourth-order Runge-Kutta; stable for h <= 2 sqrt(2) / omega_max (rk4_stable_step()).
/// \throws InverseMapError as MaximalModel::force().
template <class M>
MaximalState<M> maximal_rk4_step(const MaximalModel<M>& model, const MaximalState<M>& s,
                                 double h) {
  const double half = 0.5 * h;
  const XVec<M>& k1x = s.xdot;
  const XVec<M> k1v = model.acceleration(s.x, s.xdot, s.t);
  const XVec<M> k2x = s.xdot + half * k1v;
  const XVec<M> k2v = model.acceleration(s.x + half * k1x, k2x, s.t + half);
  const XVec<M> k3x = s.xdot + half * k2v;
  const XVec<M> k3v = model.acceleration(s.x + half * k2x, k3x, s.t + half);
  const XVec<M> k4x = s.xdot + h * k3v;
  const XVec<M> k4v = model.acceleration(s.x + h * k3x, k4x, s.t + h);
  MaximalState<M> out;
  out.t = s.t + h;
  out.x = s.x + (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
  out.xdot = s.xdot + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  return out;
}

}  // namespace gencoord
