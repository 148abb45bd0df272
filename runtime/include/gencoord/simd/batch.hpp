// SPDX-License-Identifier: BSD-3-Clause
// qddot of many states, N at a time: the generated qddot instantiated with Pack<N>
// (simd/pack.hpp) evaluates N states in one call, one per lane, on each thread of the batch.
// A lane whose result is not finite is computed again by acceleration(), so a failing state
// throws the DynamicsError the scalar batch would; results equal the scalar kernel's to a few
// ulp (sin and cos from libmvec; a model without a recursive qddot solves Mt a = f by its
// straight-line LDL^T here and by acceleration()'s there).
#pragma once

#include <cstddef>
#include <vector>

#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/parallel/batch.hpp"
#include "gencoord/simd/pack.hpp"

namespace gencoord {

/// (*out)[i] = acceleration<M>(params, states[i]) for every state, N states per kernel call.
/// \param[in]  states   The states (t, q of dim M::nq, v of dim nv_of_v<M>).
/// \param[in]  params   One parameter set for every state (the lanes share the kernel's
///                      parameters; batch_qddot() takes one per state).
/// \param[out] out      Resized to states.size() and filled; not null.
/// \param[in]  threads  Threads to use, at least 1 (the caller's thread counts as one).
/// \throws std::invalid_argument for threads < 1; DynamicsError as acceleration().
template <class M, int N = kSimdLanes>
void batch_qddot_simd(const std::vector<State<M>>& states, const ParamsOf<M>& params,
                      std::vector<VVec<M>>* out, int threads = default_batch_threads()) {
  static_assert(assert_model_v<M>);
  static_assert(!has_kinematic_constraints_v<M>,
                "gencoord: batch_qddot_simd() takes no model with kinematic constraints");
  constexpr int nv = nv_of_v<M>;
  using P = Pack<N>;
  detail::check_batch_threads(threads);
  out->resize(states.size());
  detail::parallel_chunks(states.size(), threads, [&](std::size_t begin, std::size_t end) {
    std::size_t i = begin;
    for (; i + N <= end; i += N) {
      const State<M>* s = &states[i];
      typename M::template QVector<P> q;
      typename M::template VVector<P> v;
      for (int j = 0; j < M::nq; ++j) q[j] = P::generate([&](int k) { return s[k].q[j]; });
      for (int j = 0; j < nv; ++j) v[j] = P::generate([&](int k) { return s[k].v[j]; });
      const P t = P::generate([&](int k) { return s[k].t; });
      const typename M::template VVector<P> a = M::qddot(q, v, t, params);
      for (int k = 0; k < N; ++k) {
        VVec<M>& lane = (*out)[i + k];
        for (int j = 0; j < nv; ++j) lane[j] = a[j][k];
        if (!lane.allFinite()) lane = acceleration<M>(params, states[i + k]);
      }
    }
    for (; i < end; ++i) (*out)[i] = acceleration<M>(params, states[i]);
  });
}

}  // namespace gencoord
