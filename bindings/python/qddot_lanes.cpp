// SPDX-License-Identifier: BSD-3-Clause
// simd_qddot_lanes() of the module's model (GENCOORD_MODEL_HEADER, GENCOORD_MODEL_CLASS, as
// model_module.cpp). Only Pack code is instantiated here, and only plain arrays cross to the
// rest of the module: Eigen aligns fixed-size vectors differently under -mavx2, and a scalar
// function compiled with the SIMD flags could replace the module's own copy at link time.
#include <stdexcept>

#include "gencoord/simd/batch.hpp"
#include "gencoord_python/qddot_lanes.hpp"

#include GENCOORD_MODEL_HEADER

namespace gencoord::python {

template <class M>
void simd_qddot_lanes(const double* const* q, const double* const* v, const double* t,
                      const ParamsOf<M>& params, double* const* a) {
  if constexpr (has_kinematic_constraints_v<M>) {
    throw std::logic_error("gencoord: qddot_simd takes no model with kinematic constraints");
  } else {
    qddot_lanes<M, kSimdLanes>(q, v, t, params, a);
  }
}

template void simd_qddot_lanes<GENCOORD_MODEL_CLASS>(const double* const*, const double* const*,
                                                     const double*,
                                                     const ParamsOf<GENCOORD_MODEL_CLASS>&,
                                                     double* const*);

}  // namespace gencoord::python
