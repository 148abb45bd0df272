// SPDX-License-Identifier: BSD-3-Clause
// The model file's initial state of a generated model, for the C++ tests.
#pragma once

#include "gencoord/model/state.hpp"

namespace gencoord::testing {

template <class M>
State<M> initial_state() {
  State<M> s;
  for (int i = 0; i < M::nq; ++i) s.q[i] = M::initial_q[i];
  for (int i = 0; i < nv_of_v<M>; ++i) s.v[i] = M::initial_v[i];
  return s;
}

}  // namespace gencoord::testing
