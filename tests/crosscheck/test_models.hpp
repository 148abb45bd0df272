// SPDX-License-Identifier: BSD-3-Clause
// The models the cross-check tests run on, and seeded random states for them.
#pragma once

#include <random>

#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/state.hpp"
#include "generated/bead_on_parabola.hpp"
#include "generated/bead_on_rotating_hoop.hpp"
#include "generated/cart_pole.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_5.hpp"
#include "generated/pendulum.hpp"
#include "generated/pendulum_3d.hpp"
#include "generated/spring_pendulum.hpp"

namespace gencoord::crosscheck_testing {

/// Random state near the model's initial state: q = initial_q + U(-0.4, 0.4) (so every q stays
/// on the initial state's side of coordinate singularities), v in U(-1, 1), t in U(0, 2).
template <class M>
State<M> random_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> offset(-0.4, 0.4), rate(-1.0, 1.0), time(0.0, 2.0);
  State<M> s;
  s.q = initial_q_of<M>();
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] += offset(rng);
    s.v[i] = rate(rng);
  }
  s.t = time(rng);
  return s;
}

/// Random vector with entries in U(-1, 1).
template <class Vector>
Vector random_vector(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector out;
  for (int i = 0; i < out.size(); ++i) out[i] = u(rng);
  return out;
}

}  // namespace gencoord::crosscheck_testing
