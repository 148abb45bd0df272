// SPDX-License-Identifier: BSD-3-Clause
// The state of a reduced-coordinate model: time, generalized coordinates and velocities.
#pragma once

#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// State of model M at time t: q and v = qdot, each of size M::nq.
/// Fixed-size Eigen members: no heap allocation; C++17 aligned new makes it safe in containers.
template <class Model>
struct State {
  double t = 0.0;                       // time (s)
  QVec<Model> q = QVec<Model>::Zero();  // generalized coordinates (nq)
  QVec<Model> v = QVec<Model>::Zero();  // generalized velocities (nq)
};

}  // namespace gencoord
