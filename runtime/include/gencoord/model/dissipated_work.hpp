// SPDX-License-Identifier: BSD-3-Clause
// The work W(t) of the forces that vanish at rest (dampers, friction) along a trajectory: for
// a model whose energy changes by nothing else (M::dissipative), E(t) - E(0) = W(t) exactly,
// so E(t) - E(0) - W(t) is the integrator's error where E(t) - E(0) alone is not.
//
// Their power is P = v . (Ft(q, v, t) - Ft(q, 0, t)): at rest the applied forces are the
// potential's -dV/dq (M::forces_have_potential), what is left vanishes at rest, and the
// inertial forces' power, -v . (dMt/dt v - dT/dq), is what makes d(T)/dt = v . Ft. W sums P
// over the states a simulation visits by the 4-step Adams-Moulton rule,
//   W(t_k+1) = W(t_k) + h (9 P_k+1 + 19 P_k - 5 P_k-1 + P_k-2) / 24,
// whose error is O(h^4) like RK4's (the trapezoidal rule's O(h^2) would hide RK4's energy
// error behind its own). The first two steps have only the trapezoidal and the 3-step rule,
// whose O(h^3) error stays in W at those two states alone: at the fourth state Simpson's 3/8
// rule, 3h (P0 + 3 P1 + 3 P2 + P3) / 8, sums the first three steps again. A step of another
// size than the ones before it (a shorter last step) uses the rules of the points there are.
#pragma once

#include <array>
#include <cmath>

#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

namespace detail {
template <class M>
using dissipative_op = decltype(M::dissipative);

template <class M>
constexpr bool dissipative_flag() {
  if constexpr (detected_v<M, dissipative_op>) {
    return M::dissipative;
  } else {
    return false;
  }
}
}  // namespace detail

/// Whether model M says its energy changes only by the work of forces that vanish at rest
/// (false for a model without the flag, such as a hand-written one).
template <class M>
inline constexpr bool is_dissipative_v = detail::dissipative_flag<M>();

/// P = v . (Ft(q, v, t) - Ft(q, 0, t)), the power of the forces that vanish at rest (W).
template <class M>
double dissipative_power(const State<M>& s, const ParamsOf<M>& p) {
  const VVec<M> rest = VVec<M>::Zero();
  return s.v.dot(M::applied_forces(s.q, s.v, s.t, p) - M::applied_forces(s.q, rest, s.t, p));
}

/// W(t) over the states of one simulation, given in order from its start.
template <class M>
class DissipatedWork {
 public:
  explicit DissipatedWork(const ParamsOf<M>& p) : p_(p) {}

  /// W at state s, the next state of the simulation (the first gives 0).
  double operator()(const State<M>& s) {
    const double power = dissipative_power<M>(s, p_);
    if (count_ > 0) {
      const double h = s.t - t_[0];
      int same = 1;  // earlier steps of this step's size, up to 3
      while (same < count_ && same < 3 && std::abs((t_[same - 1] - t_[same]) - h) <= 1e-9 * h) {
        ++same;
      }
      if (same >= 3 && count_ == 3) {  // the fourth state: the first three steps again
        work_ = 3 * h * (power_[2] + 3 * power_[1] + 3 * power_[0] + power) / 8;
      } else if (same >= 3) {
        work_ += h * (9 * power + 19 * power_[0] - 5 * power_[1] + power_[2]) / 24;
      } else if (same == 2) {
        work_ += h * (5 * power + 8 * power_[0] - power_[1]) / 12;
      } else {
        work_ += h * (power + power_[0]) / 2;
      }
    }
    for (int k = 3; k > 0; --k) {
      t_[k] = t_[k - 1];
      power_[k] = power_[k - 1];
    }
    t_[0] = s.t;
    power_[0] = power;
    if (count_ < 4) ++count_;
    return work_;
  }

  double work() const { return work_; }

 private:
  ParamsOf<M> p_;
  double work_ = 0.0;
  int count_ = 0;                  // states seen, up to 4
  std::array<double, 4> t_{};      // the last states' times, latest first
  std::array<double, 4> power_{};  // and their powers
};

}  // namespace gencoord
