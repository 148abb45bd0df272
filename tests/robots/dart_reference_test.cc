// SPDX-License-Identifier: BSD-3-Clause
// The generated robot models against DART on the same URDF (dart_model.hpp): the mass matrix,
// the bias forces, the accelerations and inverse dynamics at 100 random states, for a
// fixed-base arm and quadruped, the floating quadruped on its free joint, a URDF as robots ship
// it (a massless floating base, a point-mass IMU) and a gripper with two <mimic> joints. DART
// keeps every inertia tensor as the file writes it, so unlike MuJoCo (which stores principal
// moments) it agrees to round-off on inertias that are not diagonal too.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "dart_model.hpp"
#include "gencoord/gencoord.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/iiwa14.hpp"
#include "generated/mimic_gripper.hpp"
#include "generated/quadruped.hpp"
#include "generated/shipped_leg.hpp"
#include "generated/ur5e.hpp"
#include "kernel_comparison.hpp"
#include "test_files.hpp"

namespace gencoord {
namespace {

using robot_testing::DartReference;
using robot_testing::relative;

template <class M>
struct Robot;
template <>
struct Robot<models::Iiwa14> {
  static std::string urdf() { return robot_testing::source_file("models/iiwa14.urdf"); }
};
template <>
struct Robot<models::Ur5e> {
  static std::string urdf() { return robot_testing::source_file("models/ur5e.urdf"); }
};
template <>
struct Robot<models::Quadruped> {
  static std::string urdf() { return robot_testing::source_file("models/quadruped.urdf"); }
};
template <>
struct Robot<models::FloatingQuadruped> {
  static std::string urdf() { return robot_testing::source_file("models/floating_quadruped.urdf"); }
};
template <>
struct Robot<models::ShippedLeg> {
  static std::string urdf() { return robot_testing::source_file("tests/robots/shipped_leg.urdf"); }
};
template <>
struct Robot<models::MimicGripper> {
  static std::string urdf() {
    return robot_testing::source_file("tests/python/tree_models/mimic_gripper.urdf");
  }
};

/// A free joint's position within 1 m of the origin in any orientation, every other
/// coordinate in (-pi, pi); speeds in (-2, 2).
template <class M>
State<M> random_dart_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) s.q[i] = M_PI * unit(rng);
  if constexpr (has_generalized_speeds_v<M>) {
    for (const int start : M::quaternion_starts) {
      for (int i = 1; i <= 3; ++i) s.q[start - i] = unit(rng);  // a free joint's position
      s.q.template segment<4>(start).normalize();
    }
  }
  for (int i = 0; i < nv_of_v<M>; ++i) s.v[i] = 2.0 * unit(rng);
  return s;
}

template <class M>
class DartReferenceTest : public ::testing::Test {};
using DartRobots =
    ::testing::Types<models::Iiwa14, models::Ur5e, models::Quadruped, models::FloatingQuadruped,
                     models::ShippedLeg, models::MimicGripper>;
TYPED_TEST_SUITE(DartReferenceTest, DartRobots);

TYPED_TEST(DartReferenceTest, KernelsMatchAtRandomStates) {
  using M = TypeParam;
  typename M::Params defaults;
  const typename M::Params p = defaults;
  DartReference<M> dart(Robot<M>::urdf(), *defaults.find("g"));
  std::mt19937 rng(20261202);
  robot_testing::WorstDifferences worst;
  double forward = 0.0;  // DART's own forward dynamics, where it has no extra mimic dofs
  const bool square = dart.dofs() == nv_of_v<M>;
  for (int k = 0; k < 100; ++k) {
    const State<M> s = random_dart_state<M>(rng);
    dart.set_state(s.q, s.v);
    worst.mass_matrix =
        std::max(worst.mass_matrix, relative(M::mass_matrix(s.q, s.t, p), dart.mass_matrix()));
    const auto zero = VVec<M>::Zero().eval();
    worst.bias =
        std::max(worst.bias, relative(M::forces(s.q, s.v, s.t, p), -dart.inverse_dynamics(zero)));
    const auto vdot = M::qddot(s.q, s.v, s.t, p);
    worst.qddot = std::max(worst.qddot, relative(vdot, dart.qddot()));
    if (square) forward = std::max(forward, relative(vdot, dart.forward_dynamics()));
    worst.inverse_dynamics = std::max(
        worst.inverse_dynamics,
        relative(M::inverse_dynamics(s.q, s.v, vdot, s.t, p), dart.inverse_dynamics(vdot)));
  }
  worst.check((std::string(M::name) + " against DART").c_str(), 1e-13, 1e-11);
  if (square) {
    robot_testing::record("forward_dynamics", forward);
    EXPECT_LT(forward, 1e-11);
    std::printf("%s: DART's computeForwardDynamics %.2g\n", M::name, forward);
  }
}

TEST(DartReference, MimicJointsAreDartsDegreesOfFreedomEliminated) {
  // the gripper's URDF has four joints, two of them <mimic>: DART keeps four dofs
  DartReference<models::MimicGripper> dart(Robot<models::MimicGripper>::urdf(), 9.81);
  EXPECT_EQ(dart.dofs(), 4);
  EXPECT_EQ(models::MimicGripper::nq, 2);
  // the mirrored finger follows at 1.5 and the thumb at -0.5 times the shoulder
  const Eigen::MatrixXd& S = dart.speed_map();
  EXPECT_EQ(S.sum(), 1.0 + 1.0 + 1.5 - 0.5);
}

}  // namespace
}  // namespace gencoord
