// SPDX-License-Identifier: BSD-3-Clause
// A model's control inputs as a vector: they live in its Params (one field each, in the
// order of M::input_names), so every kernel reads them like parameters; and the generalized
// force they apply at each joint limit, which the limit's effort rating rates.
#pragma once

#include <array>
#include <cstddef>

#include "gencoord/model/joint_limits.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

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

/// The generalized force the control inputs that p holds apply at each limit's speed,
/// (B u)[limited_speeds[i]] with B = input_matrix(q, v, t, p): what effort_limits[i] rates,
/// such as a motor's torque at its joint. All zero for a model without control inputs.
template <class M>
std::array<double, M::num_limits> input_efforts(const State<M>& s, const ParamsOf<M>& p) {
  static_assert(has_joint_limits_v<M>, "gencoord: input_efforts needs a model with joint limits");
  std::array<double, M::num_limits> efforts{};
  if constexpr (has_inputs_v<M>) {
    const VVec<M> applied = M::input_matrix(s.q, s.v, s.t, p) * inputs_of<M>(p);
    for (int i = 0; i < M::num_limits; ++i)
      efforts[static_cast<std::size_t>(i)] = applied[M::limited_speeds[i]];
  } else {
    (void)s;
    (void)p;
  }
  return efforts;
}

}  // namespace gencoord
