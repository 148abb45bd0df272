// SPDX-License-Identifier: BSD-3-Clause
// A model's control inputs as a vector: they live in its Params (one field each, in the
// order of M::input_names), so every kernel reads them like parameters.
#pragma once

#include <array>
#include <cstddef>

#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// The control inputs that p holds (dim num_inputs_v<M>; empty for a model without inputs).
template <class M>
InputVec<M> inputs_of(const ParamsOf<M>& p) {
  InputVec<M> u;
  if constexpr (has_inputs_v<M>) {
    const auto values = p.inputs();
    for (int k = 0; k < M::num_inputs; ++k) u[k] = values[static_cast<std::size_t>(k)];
  }
  return u;
}

/// p with its control inputs set to u (dim num_inputs_v<M>).
template <class M>
ParamsOf<M> with_inputs(ParamsOf<M> p, const InputVec<M>& u) {
  if constexpr (has_inputs_v<M>) {
    std::array<double, static_cast<std::size_t>(M::num_inputs)> values;
    for (int k = 0; k < M::num_inputs; ++k) values[static_cast<std::size_t>(k)] = u[k];
    p.set_inputs(values);
  } else {
    static_cast<void>(u);
  }
  return p;
}

}  // namespace gencoord
