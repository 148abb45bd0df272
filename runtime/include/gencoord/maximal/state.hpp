// SPDX-License-Identifier: BSD-3-Clause
// The state of a maximal-coordinate (free particle) model, and the consistent maximal state of
// a reduced one.
#pragma once

#include <algorithm>

#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// State of the maximal model of M at time t: its coordinates q are the particle positions x,
/// its velocities v the particle velocities xdot, both stacked (nx = dim * num_particles
/// entries, dim per particle); q and v as in every system the integrators take.
template <class M>
struct MaximalState {
  double t = 0.0;               // time (s)
  XVec<M> q = XVec<M>::Zero();  // particle positions x (nx)
  XVec<M> v = XVec<M>::Zero();  // particle velocities xdot (nx)
};

/// The maximal state consistent with a reduced one: x = X(q, t), xdot = J v + X_t.
/// \param[in] p  The model parameters.
/// \param[in] s  The reduced state (q, v of dims nq, nv).
/// \return The maximal state at s.t (on the constraint manifold, tangent to it).
template <class M>
MaximalState<M> to_maximal(const ParamsOf<M>& p, const State<M>& s) {
  MaximalState<M> out;
  out.t = s.t;
  out.q = M::positions(s.q, s.t, p);
  out.v = M::velocities(s.q, s.v, s.t, p);
  return out;
}

/// Largest distance between corresponding particles of two stacked position vectors (nx).
template <class M>
double max_particle_distance(const XVec<M>& a, const XVec<M>& b) {
  double d = 0.0;
  for (int i = 0; i < M::num_particles; ++i)
    d = std::max(
        d,
        (a.template segment<M::dim>(M::dim * i) - b.template segment<M::dim>(M::dim * i)).norm());
  return d;
}

}  // namespace gencoord
