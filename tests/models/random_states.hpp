// SPDX-License-Identifier: BSD-3-Clause
// Seeded random states and parameters for model tests: reproducible, away from coordinate
// singularities.
#pragma once

#include <random>

#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord::testing {

/// Random state with every q in [0.3, 1.3], v in [-1, 1] and t in [0, 2]. Positive q away
/// from 0 and pi keeps the spherical pendulum off its poles and the spring pendulum's
/// radius off zero, where those parameterizations are singular.
template <class M>
State<M> random_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(0.3, 1.3), rate(-1.0, 1.0), time(0.0, 2.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = angle(rng);
    s.v[i] = rate(rng);
  }
  s.t = time(rng);
  return s;
}

/// The model's default parameters, each scaled by a factor in [0.5, 2] (a zero default
/// becomes 0.1 to 1): what a check that must hold for every parameter value samples.
template <class M>
ParamsOf<M> sampled_params(std::mt19937& rng) {
  std::uniform_real_distribution<double> factor(0.5, 2.0), small(0.1, 1.0);
  ParamsOf<M> p;
  for (const char* name : M::parameter_names) {
    double* value = p.find(name);
    *value = *value != 0 ? *value * factor(rng) : small(rng);
  }
  return p;
}

}  // namespace gencoord::testing
