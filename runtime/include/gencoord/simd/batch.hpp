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

/// a[k] = M::qddot(q[k], v[k], t[k]) for k < N, all N in one call of the generated qddot
/// instantiated with Pack<N>. No lane is checked: a lane is NaN or infinite where the scalar
/// kernel's is, and a model whose qddot solves Mt a = f by its LDL^T gives the whole pack
/// NaN when one lane's pivot is not positive. Plain arrays, not Eigen vectors, so that
/// translation units built for different instruction sets (where Eigen aligns fixed-size
/// vectors differently) can share it.
/// \param[in]  q       N arrays of M::nq coordinates.
/// \param[in]  v       N arrays of nv_of_v<M> velocities or speeds.
/// \param[in]  t       N times.
/// \param[in]  params  The parameters of every lane.
/// \param[out] a       N arrays of nv_of_v<M> accelerations.
template <class M, int N = kSimdLanes>
void qddot_lanes(const double* const* q, const double* const* v, const double* t,
                 const ParamsOf<M>& params, double* const* a) {
  static_assert(assert_model_v<M>);
  static_assert(!has_kinematic_constraints_v<M>,
                "gencoord: qddot_lanes() takes no model with kinematic constraints");
  constexpr int nv = nv_of_v<M>;
  using P = Pack<N>;
  typename M::template QVector<P> qs;
  typename M::template VVector<P> vs;
  for (int j = 0; j < M::nq; ++j) qs[j] = P::generate([&](int k) { return q[k][j]; });
  for (int j = 0; j < nv; ++j) vs[j] = P::generate([&](int k) { return v[k][j]; });
  const typename M::template VVector<P> packed = M::qddot(qs, vs, P::load(t), params);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < nv; ++j) a[k][j] = packed[j][k];
}

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
  detail::check_batch_threads(threads);
  out->resize(states.size());
  detail::parallel_chunks(states.size(), threads, [&](std::size_t begin, std::size_t end) {
    std::size_t i = begin;
    for (; i + N <= end; i += N) {
      const double *q[N], *v[N];
      double t[N], *a[N];
      for (std::size_t k = 0; k < N; ++k) {
        q[k] = states[i + k].q.data();
        v[k] = states[i + k].v.data();
        t[k] = states[i + k].t;
        a[k] = (*out)[i + k].data();
      }
      qddot_lanes<M, N>(q, v, t, params, a);
      for (std::size_t k = i; k < i + N; ++k)
        if (!(*out)[k].allFinite()) (*out)[k] = acceleration<M>(params, states[k]);
    }
    for (; i < end; ++i) (*out)[i] = acceleration<M>(params, states[i]);
  });
}

}  // namespace gencoord
