// SPDX-License-Identifier: BSD-3-Clause
// Joint limits: a model whose header lists them (num_limits, limited_coordinates,
// limited_speeds, lower_limits, upper_limits, velocity_limits, effort_limits, limit_names) keeps
// those coordinates in their ranges; the speed and effort ratings are for reports (limit_side,
// input_efforts in gencoord/control/inputs.hpp, simulate).
// enforce_joint_limits() acts on a step's end state: a coordinate past a limit is put back on it,
// and the speeds into the limits are stopped by one inelastic impulse through the mass matrix, Mt
// (v+ - v-) = sum_i mu_i e_k(i) (k(i) the limit's speed). That is Moreau's impact law with zero
// restitution: every limit the impulse holds pushes (mu_i >= 0 at a lower end, <= 0 at an upper
// end), no limit it leaves out is entered, and the kinetic energy can only fall. The set of held
// limits is found by adding the entered ones and dropping the pulling ones until neither is left.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

namespace detail {
template <class M, class = void>
struct has_joint_limits : std::false_type {};
template <class M>
struct has_joint_limits<M, std::void_t<decltype(M::num_limits), decltype(M::limited_coordinates),
                                       decltype(M::limited_speeds), decltype(M::lower_limits),
                                       decltype(M::upper_limits), decltype(M::velocity_limits),
                                       decltype(M::effort_limits), decltype(M::limit_names)>>
    : std::true_type {};
}  // namespace detail

/// Whether model M declares joint limits.
template <class M>
inline constexpr bool has_joint_limits_v = detail::has_joint_limits<M>::value;

/// Where limit i's coordinate is in q: -1 on or below its lower end, +1 on or above its upper
/// end, 0 inside its range.
template <class M>
int limit_side(const QVec<M>& q, int i) {
  const double value = q[M::limited_coordinates[i]];
  return value <= M::lower_limits[i] ? -1 : value >= M::upper_limits[i] ? 1 : 0;
}

/// What enforce_joint_limits() found and did at one state.
struct LimitContacts {
  int on_limit = 0;  // limited coordinates on an end of their range afterwards
  int stopped = 0;   // limits whose speeds the impulse stopped
};

namespace detail {

// Which end of its range limit i's coordinate is on: +1 the lower, -1 the upper, 0 neither;
// a locked coordinate (equal ends) is held either way.
enum LimitSide : int { kInside = 0, kAtLower = 1, kAtUpper = -1, kLocked = 2 };

// whether speed w moves the coordinate into its limit, beyond a round-off of `tolerance`
inline bool enters(int side, double w, double tolerance) {
  if (side == kLocked) return std::abs(w) > tolerance;
  return side * w < -tolerance;
}

// whether impulse mu pulls the coordinate onto its limit instead of pushing it away
inline bool pulls(int side, double mu, double tolerance) {
  return side != kLocked && side * mu < -tolerance;
}

}  // namespace detail

/// Puts each limited coordinate of s that is past its range back on the nearest end, and stops
/// the speeds into the limits by one inelastic impulse through Mt(q) (see the top of this file).
/// The speeds that no limit holds change as the impulse moves them. A state already inside
/// every range is left as it is.
/// \param[in]     p  The model's parameters (the mass matrix depends on them).
/// \param[in,out] s  The state, changed in place.
/// \returns How many coordinates are on a limit, and how many limits the impulse held.
/// A mass matrix that is not positive definite leaves v as it is.
template <class M>
LimitContacts enforce_joint_limits(const ParamsOf<M>& p, State<M>* s) {
  static_assert(has_joint_limits_v<M>,
                "gencoord: enforce_joint_limits needs a model with "
                "joint limits (a URDF <limit>, or model.limit(...))");
  using detail::enters;
  using detail::pulls;
  constexpr int n = M::num_limits;
  std::array<int, n> side{};
  LimitContacts contacts;
  for (int i = 0; i < n; ++i) {
    double& q = s->q[M::limited_coordinates[i]];
    if (q <= M::lower_limits[i]) {
      q = M::lower_limits[i];
      side[i] = detail::kAtLower;
    } else if (q >= M::upper_limits[i]) {
      q = M::upper_limits[i];
      side[i] = detail::kAtUpper;
    }
    if (side[i] != detail::kInside && M::lower_limits[i] == M::upper_limits[i])
      side[i] = detail::kLocked;
    if (side[i] != detail::kInside) ++contacts.on_limit;
  }
  const double speed_tolerance = 1e-13 * (1.0 + s->v.template lpNorm<Eigen::Infinity>());
  std::vector<int> held;
  for (int i = 0; i < n; ++i)
    if (side[i] != detail::kInside && enters(side[i], s->v[M::limited_speeds[i]], 0.0))
      held.push_back(i);
  if (held.empty()) return contacts;

  const Eigen::MatrixXd mass = M::mass_matrix(s->q, s->t, p);
  const Eigen::LDLT<Eigen::MatrixXd> mass_ldlt(mass);
  if (mass_ldlt.info() != Eigen::Success) return contacts;
  const Eigen::VectorXd v_before = s->v;
  Eigen::VectorXd v_after = v_before;
  // Each round solves for the impulses that stop the held speeds; it drops a held limit
  // that pulls, or else adds one the new speeds enter. 2n + 1 rounds suffice unless round-off
  // cycles, and then the last round's speeds stand.
  for (int round = 0; round <= 2 * n && !held.empty(); ++round) {
    const int m = static_cast<int>(held.size());
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(v_before.size(), m);
    for (int j = 0; j < m; ++j) unit(M::limited_speeds[held[j]], j) = 1.0;
    const Eigen::MatrixXd response = mass_ldlt.solve(unit);  // Mt^-1 e_k, one column each
    Eigen::MatrixXd gram(m, m);
    Eigen::VectorXd stop(m);
    for (int j = 0; j < m; ++j) {
      gram.row(j) = response.row(M::limited_speeds[held[j]]);
      stop[j] = -v_before[M::limited_speeds[held[j]]];
    }
    const Eigen::VectorXd mu = gram.ldlt().solve(stop);
    v_after = v_before + response * mu;
    const double impulse_tolerance = 1e-13 * (1.0 + mu.lpNorm<Eigen::Infinity>());
    std::vector<int> next;
    for (int j = 0; j < m; ++j)
      if (!pulls(side[held[j]], mu[j], impulse_tolerance)) next.push_back(held[j]);
    if (next.size() == held.size()) {
      for (int i = 0; i < n; ++i)
        if (side[i] != detail::kInside && std::find(held.begin(), held.end(), i) == held.end() &&
            enters(side[i], v_after[M::limited_speeds[i]], speed_tolerance))
          next.push_back(i);
      if (next.size() == held.size()) break;  // consistent: nothing pulls, nothing enters
    }
    held = std::move(next);
  }
  if (held.empty()) v_after = v_before;  // every impulse pulled: the speeds leave the limits
  s->v = v_after;
  contacts.stopped = static_cast<int>(held.size());
  return contacts;
}

}  // namespace gencoord
