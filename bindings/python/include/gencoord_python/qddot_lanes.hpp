// SPDX-License-Identifier: BSD-3-Clause
// qddot of kSimdLanes states in one call of the generated kernel instantiated with
// Pack<kSimdLanes> (gencoord/simd/). Defined in bindings/python/qddot_lanes.cpp, the module's one
// translation unit built with the SIMD flags (-mavx2 -mfma where the machine has them): the
// rest of the module keeps the baseline instruction set, so its scalar kernels stay those of
// the C++ runtime bit for bit.
#pragma once

#include "gencoord/model/model_traits.hpp"

namespace gencoord::python {

/// a[k] = M::qddot(q[k], v[k], t[k]) for k < kSimdLanes: qddot_lanes<M, kSimdLanes>().
template <class M>
void simd_qddot_lanes(const double* const* q, const double* const* v, const double* t,
                      const ParamsOf<M>& params, double* const* a);

}  // namespace gencoord::python
