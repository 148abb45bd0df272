// SPDX-License-Identifier: BSD-3-Clause
// The state of a reduced-coordinate model: time, generalized coordinates and velocities.
#pragma once

#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// State of model M at time t: q (M::nq) and v (nv_of_v<M>): v = q' for most models, the
/// generalized speeds with q' = M::coordinate_rates(q, v, t, p) for models that have them.
/// Fixed-size Eigen members: no heap allocation; C++17 aligned new makes it safe in containers.
template <class Model>
struct State {
  double t = 0.0;                       // time (s)
  QVec<Model> q = QVec<Model>::Zero();  // generalized coordinates (nq)
  VVec<Model> v = VVec<Model>::Zero();  // generalized velocities or speeds (nv)
};

}  // namespace gencoord
