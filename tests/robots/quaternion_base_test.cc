// SPDX-License-Identifier: BSD-3-Clause
// A floating robot whose base is a free joint (unit quaternion, body twist) against MuJoCo's
// free joint on the same URDF (quaternion_base.hpp maps one onto the other): at random states
// the mass matrix, the bias forces, the speeds' rates and the inverse dynamics; a 1 s RK4
// trajectory of the falling robot at MuJoCo's step; and the quaternion's norm over 10 s. On
// the quadruped's URDF with diagonal inertias MuJoCo stores every number exactly, and the two
// agree to round-off; on the original, to MuJoCo's storage of the inertias. shipped_leg.urdf
// has a massless floating base and a point-mass IMU, as robots ship their files.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "gencoord/gencoord.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/floating_quadruped_diagonal.hpp"
#include "generated/shipped_leg.hpp"
#include "kernel_comparison.hpp"
#include "quaternion_base.hpp"
#include "test_files.hpp"

namespace gencoord {
namespace {

using robot_testing::QuaternionBaseReference;
using robot_testing::record;
using robot_testing::relative;

/// Each robot's URDF and bounds: `kernels` for the mass matrix and the bias forces, `solved`
/// for the speeds' rates, the inverse dynamics and the trajectory (mujoco_reference_test.cc
/// says why the original's are not 1e-12).
template <class M>
struct Robot;
template <>
struct Robot<models::FloatingQuadruped> {
  static std::string urdf() { return robot_testing::source_file("models/floating_quadruped.urdf"); }
  static constexpr double kernels = 1e-8, solved = 1e-6;
};
template <>
struct Robot<models::FloatingQuadrupedDiagonal> {
  static std::string urdf() {
    return robot_testing::build_file("floating_quadruped_diagonal.urdf");
  }
  static constexpr double kernels = 1e-12, solved = 1e-12;
};
// a massless floating base and a point mass welded to the trunk: both sides fold the point
// mass into the trunk, whose inertia is then no longer diagonal, and MuJoCo keeps it as
// principal moments and a rotation again (measured: 7e-13 mass matrix, 2e-11 qddot)
template <>
struct Robot<models::ShippedLeg> {
  static std::string urdf() { return robot_testing::source_file("tests/robots/shipped_leg.urdf"); }
  static constexpr double kernels = 1e-11, solved = 1e-9;
};

/// The base within 1 m of the origin at up to 2 m/s in any orientation, turning at up to
/// 2 rad/s; the joints in (-pi, pi) at up to 2 rad/s.
template <class M>
State<M> random_quaternion_base_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) s.q[i] = (i < 3 ? 1.0 : M_PI) * unit(rng);
  s.q.template segment<4>(3).normalize();
  for (int i = 0; i < M::nv; ++i) s.v[i] = 2.0 * unit(rng);
  return s;
}

template <class M>
class QuaternionBaseMujoco : public ::testing::Test {};

using QuaternionRobots = ::testing::Types<models::FloatingQuadruped,
                                          models::FloatingQuadrupedDiagonal, models::ShippedLeg>;
TYPED_TEST_SUITE(QuaternionBaseMujoco, QuaternionRobots);

TYPED_TEST(QuaternionBaseMujoco, KernelsMatchAtRandomStates) {
  using M = TypeParam;
  QuaternionBaseReference<M> mujoco(Robot<M>::urdf());
  const typename M::Params p;
  std::mt19937 rng(20261127);
  robot_testing::WorstDifferences worst;
  for (int k = 0; k < 100; ++k) {
    const State<M> s = random_quaternion_base_state<M>(rng);
    mujoco.forward(s.q, s.v);
    worst.mass_matrix =
        std::max(worst.mass_matrix, relative(M::mass_matrix(s.q, s.t, p), mujoco.mass_matrix()));
    // MuJoCo's qacc first: inverse_dynamics() overwrites it
    const auto vdot = M::qddot(s.q, s.v, s.t, p);
    worst.qddot = std::max(worst.qddot, relative(mujoco.qacc_from(vdot), mujoco.qacc()));
    // Ft + Fi is the force that holds v' at zero, with the sign turned: -r(q, v, 0)
    const auto zero = M::template VVector<double>::Zero().eval();
    worst.bias =
        std::max(worst.bias, relative(M::forces(s.q, s.v, s.t, p), -mujoco.inverse_dynamics(zero)));
    worst.inverse_dynamics = std::max(
        worst.inverse_dynamics,
        relative(M::inverse_dynamics(s.q, s.v, vdot, s.t, p), mujoco.inverse_dynamics(vdot)));
  }
  worst.check((std::string(M::name) + " (quaternion base)").c_str(), Robot<M>::kernels,
              Robot<M>::solved);
}

TYPED_TEST(QuaternionBaseMujoco, RK4TrajectoryFollowsMujoco) {
  // compared through mj_differentiatePos: the base's displacement (m), its rotation (rad) and
  // the joints' differences (rad); MuJoCo's RK4 turns the quaternion by the exponential map,
  // gencoord's adds q' and normalizes, so the two differ at the methods' truncation error
  using M = TypeParam;
  QuaternionBaseReference<M> mujoco(Robot<M>::urdf());
  const typename M::Params p;
  std::mt19937 rng(7);
  State<M> initial = random_quaternion_base_state<M>(rng);
  initial.v *= 0.25;
  const double dt = 1e-3, duration = 1.0;
  mujoco.forward(initial.q, initial.v);
  mujoco.model()->opt.timestep = dt;
  double worst = 0.0;
  int step = 0;
  simulate(robot_testing::without_limits<M>(p), initial,
           SimulateOptions(Integrator::RK4, dt, duration), [&](const State<M>& s) {
             if (step++ > 0) mj_step(mujoco.model(), mujoco.data());
             const auto gap = mujoco.difference(
                 mujoco.qpos(s.q),
                 Eigen::Map<const typename M::template QVector<double>>(mujoco.data()->qpos));
             worst = std::max(worst, gap.template lpNorm<Eigen::Infinity>());
           });
  EXPECT_EQ(step, 1001);
  EXPECT_LT(worst, 1e-6);
  record("trajectory", worst);
  std::printf("%s (quaternion base): largest |q - q_MuJoCo| over 1 s of RK4 at dt = 1 ms: %.2g\n",
              M::name, worst);
}

TYPED_TEST(QuaternionBaseMujoco, QuaternionStaysUnitOver10Seconds) {
  using M = TypeParam;
  const typename M::Params p;
  std::mt19937 rng(11);
  const State<M> initial = random_quaternion_base_state<M>(rng);
  double drift = 0.0;
  simulate(ReducedSystem<M>(p), initial, SimulateOptions(Integrator::RK4, 1e-3, 10.0),
           [&](const State<M>& s) {
             drift = std::max(drift, std::abs(s.q.template segment<4>(3).norm() - 1.0));
           });
  record("quaternion_norm_drift", drift);
  EXPECT_LT(drift, 1e-12);
  std::printf("%s (quaternion base): largest | |quaternion| - 1 | over 10 s of RK4: %.2g\n",
              M::name, drift);
}

}  // namespace
}  // namespace gencoord
