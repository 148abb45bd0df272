// SPDX-License-Identifier: BSD-3-Clause
// What the robot tests share when they hold generated kernels against MuJoCo: the relative
// difference, the worst of each kernel over many states, its bounds and its report.
#pragma once

#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "gencoord/model/reduced_system.hpp"

namespace gencoord::robot_testing {

/// |a - b| relative to the larger of the two and 1.
template <class A, class B>
double relative(const A& a, const B& b) {
  return (a - b).norm() / std::max(1.0, std::max(a.norm(), b.norm()));
}

/// A figure in the test's XML report (ctest --output-junit, gtest --gtest_output).
inline void record(const char* key, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", value);
  ::testing::Test::RecordProperty(key, text);
}

/// The worst relative differences of the four kernels over the states compared.
struct WorstDifferences {
  double mass_matrix = 0, bias = 0, qddot = 0, inverse_dynamics = 0;

  /// Records them, expects the mass matrix and bias within `kernels` and qddot and the
  /// inverse dynamics within `solved`, and prints them for `robot`.
  void check(const char* robot, double kernels, double solved) const {
    record("mass_matrix", mass_matrix);
    record("bias", bias);
    record("qddot", qddot);
    record("inverse_dynamics", inverse_dynamics);
    EXPECT_LT(mass_matrix, kernels);
    EXPECT_LT(bias, kernels);
    EXPECT_LT(qddot, solved);
    EXPECT_LT(inverse_dynamics, solved);
    std::printf(
        "%s: worst relative difference over 100 states: mass matrix %.2g, bias %.2g, qddot "
        "%.2g, inverse dynamics %.2g\n",
        robot, mass_matrix, bias, qddot, inverse_dynamics);
  }
};

/// The reduced system with its joint limits off: the trajectories are compared with MuJoCo's
/// run with its constraints, limits among them, disabled (mujoco_model.hpp).
template <class M>
ReducedSystem<M> without_limits(const ParamsOf<M>& p) {
  ReducedSystem<M> system(p);
  if constexpr (has_joint_limits_v<M>) system.set_joint_limits(false);
  return system;
}

}  // namespace gencoord::robot_testing
