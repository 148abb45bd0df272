// SPDX-License-Identifier: BSD-3-Clause
// The initial state a driver starts from: the model file's, or the --q and --v a user gave,
// put on the model's manifold. Shared by simulate and crosscheck; errors name the program and
// the option, and the caller exits with status 2.
#pragma once

#include <iostream>
#include <vector>

#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord::drivers {

/// The model file's initial state with --q (nq values) and --v (nv values: the generalized
/// speeds of a model that has them) where given, at t = 0; false, with the error printed,
/// for a list of the wrong length.
template <class M>
bool initial_state(const char* program, const std::vector<double>& q, const std::vector<double>& v,
                   State<M>* s) {
  constexpr int nv = nv_of_v<M>;
  s->q = initial_q_of<M>();
  s->v = initial_v_of<M>();
  if (!q.empty()) {
    if (static_cast<int>(q.size()) != M::nq) {
      std::cerr << program << ": error: model " << M::name << " has " << M::nq
                << " coordinates; --q needs that many values\n";
      return false;
    }
    for (int i = 0; i < M::nq; ++i) s->q[i] = q[i];
  }
  if (!v.empty()) {
    if (static_cast<int>(v.size()) != nv) {
      std::cerr << program << ": error: model " << M::name << " has " << nv
                << (nv == M::nq ? " coordinates" : " generalized speeds")
                << "; --v needs that many values\n";
      return false;
    }
    for (int i = 0; i < nv; ++i) s->v[i] = v[i];
  }
  return true;
}

/// The initial state on the model's manifold: unit quaternions normalized, a constrained
/// model's state projected onto its constraints (false, with the error printed, for a
/// quaternion that is zero or not finite). Templates, so that the members of such a model
/// are looked up only for it.
template <class M>
bool put_on_manifold(const char* program, const ReducedSystem<M>& system, State<M>* s) {
  if constexpr (has_generalized_speeds_v<M>) {
    for (const int start : M::quaternion_starts) {
      const auto quaternion = s->q.segment(start, 4);
      if (!(quaternion.norm() > 0.0) || !quaternion.allFinite()) {
        std::cerr << program << ": error: the quaternion at " << M::coordinate_names[start]
                  << " in --q is zero or not finite; give a rotation (w, x, y, z)\n";
        return false;
      }
    }
  }
  normalize(system, s);
  if constexpr (has_kinematic_constraints_v<M>) {
    // normalize() projects unless Baumgarte's feedback replaces projection; start on them
    if (!system.stabilization().project) project_onto_constraints<M>(system.params(), s);
  }
  return true;
}

}  // namespace gencoord::drivers
