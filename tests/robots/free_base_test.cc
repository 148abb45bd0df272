// SPDX-License-Identifier: BSD-3-Clause
// A robot with a free-floating base against MuJoCo on the same URDF: the generated model in
// each Euler chart (zyx and yzx, one model each) and MuJoCo's free joint (position and
// quaternion, the body's angular velocity) mapped onto each other as free_joint.hpp
// describes. At random states: the map against MuJoCo's own mj_differentiatePos, the mass
// matrix, the bias forces, qddot and inverse dynamics; and a 1 s RK4 trajectory of the falling
// robot at the same step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "free_joint.hpp"
#include "gencoord/gencoord.hpp"
#include "generated/floating_leg.hpp"
#include "generated/floating_leg_yzx.hpp"
#include "kernel_comparison.hpp"
#include "test_files.hpp"

namespace gencoord {
namespace {

using robot_testing::euler_chart_of;
using robot_testing::FreeBaseReference;
using robot_testing::record;
using robot_testing::relative;

const std::string kUrdf = robot_testing::source_file("tests/robots/floating_leg.urdf");
// the fixed-base quadruped's bounds (mujoco_reference_test.cc says why they are not 1e-9):
// `kernels` for the mass matrix and the bias forces, `solved` for qddot, inverse dynamics and
// the trajectory
constexpr double kKernels = 1e-8, kSolved = 1e-6;
// the middle angle (q[4]: pitch or attitude) stays this far from pi/2, where its chart is
// singular (gimbal lock)
constexpr double kMiddleAngleLimit = 1.2;

/// The base anywhere within 1 m of the origin moving at up to 2 m/s, the outer and inner
/// angles in (-pi, pi), the middle one in (-1.2, 1.2), the joints in (-pi, pi), angle rates in
/// (-2, 2) rad/s.
template <class M>
State<M> random_free_base_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = (i < 3 ? 1.0 : i == 4 ? kMiddleAngleLimit : M_PI) * unit(rng);
    s.v[i] = 2.0 * unit(rng);
  }
  return s;
}

/// The floating leg in one Euler chart.
template <class M>
class FreeBaseMujoco : public ::testing::Test {};

/// Test names carry the chart: FreeBaseMujoco/zyx, FreeBaseMujoco/yzx.
struct ChartName {
  template <class M>
  static std::string GetName(int) {
    return euler_chart_of<M>().name;
  }
};

using Charts = ::testing::Types<models::FloatingLeg, models::FloatingLegYzx>;
TYPED_TEST_SUITE(FreeBaseMujoco, Charts, ChartName);

TYPED_TEST(FreeBaseMujoco, VelocityMapIsMujocosDerivativeOfThePose) {
  // qvel = T v is what mj_differentiatePos makes of the mapped poses at q -+ h v, and
  // Tdot v is T's central difference along v times v: both to the differences' truncation.
  // This ties E to the chart's own quaternion; the tests below tie the chart to the model's.
  using M = TypeParam;
  using QVec = typename FreeBaseReference<M>::QVec;
  FreeBaseReference<M> mujoco(kUrdf);
  std::mt19937 rng(41);
  const double h = 1e-5;
  double worst_velocity = 0, worst_bias = 0;
  for (int k = 0; k < 100; ++k) {
    const State<M> s = random_free_base_state<M>(rng);
    const QVec qvel = mujoco.velocity_map(s.q) * s.v;
    const QVec secant =
        mujoco.difference(mujoco.qpos(s.q - h * s.v), mujoco.qpos(s.q + h * s.v)) / (2 * h);
    worst_velocity = std::max(worst_velocity, relative(secant, qvel));
    const QVec tdot_v =
        (mujoco.velocity_map(s.q + h * s.v) - mujoco.velocity_map(s.q - h * s.v)) * s.v / (2 * h);
    worst_bias = std::max(worst_bias, relative(tdot_v, mujoco.velocity_map_bias(s.q, s.v)));
  }
  record("velocity_map", worst_velocity);
  record("velocity_map_bias", worst_bias);
  EXPECT_LT(worst_velocity, 1e-8);
  EXPECT_LT(worst_bias, 1e-8);
  std::printf("%s (free base): velocity map against mj_differentiatePos %.2g, its bias %.2g\n",
              M::name, worst_velocity, worst_bias);
}

TYPED_TEST(FreeBaseMujoco, KernelsMatchAtRandomStates) {
  using M = TypeParam;
  using QVec = typename FreeBaseReference<M>::QVec;
  FreeBaseReference<M> mujoco(kUrdf);
  const typename M::Params p;
  std::mt19937 rng(20261123);
  robot_testing::WorstDifferences worst;
  for (int k = 0; k < 100; ++k) {
    const State<M> s = random_free_base_state<M>(rng);
    mujoco.forward(s.q, s.v);
    worst.mass_matrix =
        std::max(worst.mass_matrix, relative(M::mass_matrix(s.q, s.t, p), mujoco.mass_matrix()));
    worst.bias = std::max(worst.bias, relative(M::forces(s.q, s.v, s.t, p), -mujoco.bias()));
    const QVec qdd = M::qddot(s.q, s.v, s.t, p);
    worst.qddot = std::max(worst.qddot, relative(mujoco.qacc_from(qdd), mujoco.qacc()));
    worst.inverse_dynamics = std::max(
        worst.inverse_dynamics,
        relative(M::inverse_dynamics(s.q, s.v, qdd, s.t, p), mujoco.inverse_dynamics(qdd)));
  }
  worst.check((std::string(M::name) + " (free base)").c_str(), kKernels, kSolved);
}

TYPED_TEST(FreeBaseMujoco, RK4TrajectoryFollowsMujoco) {
  // compared through mj_differentiatePos: the base's displacement (m), its rotation (rad) and
  // the joints' differences (rad)
  using M = TypeParam;
  using QVec = typename FreeBaseReference<M>::QVec;
  FreeBaseReference<M> mujoco(kUrdf);
  const typename M::Params p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State<M> initial;
  for (int i = 0; i < M::nq; ++i) {
    initial.q[i] = (i == 4 ? 0.3 : 1.0) * unit(rng);
    initial.v[i] = 0.5 * unit(rng);
  }
  const double dt = 1e-3, duration = 1.0;
  mujoco.set(initial.q, initial.v);
  mujoco.model()->opt.timestep = dt;
  double worst = 0.0, steepest = 0.0;
  int step = 0;
  simulate(robot_testing::without_limits<M>(p), initial,
           SimulateOptions(Integrator::RK4, dt, duration), [&](const State<M>& s) {
             if (step++ > 0) mj_step(mujoco.model(), mujoco.data());
             const QVec gap = mujoco.difference(mujoco.qpos(s.q), mujoco.qpos());
             worst = std::max(worst, gap.template lpNorm<Eigen::Infinity>());
             steepest = std::max(steepest, std::abs(s.q[4]));
           });
  EXPECT_EQ(step, 1001);
  EXPECT_LT(steepest, kMiddleAngleLimit);
  EXPECT_LT(worst, kSolved);
  record("trajectory", worst);
  std::printf(
      "%s (free base): largest |q - q_MuJoCo| over 1 s of RK4 at dt = 1 ms: %.2g (the "
      "middle angle within %.2g rad)\n",
      M::name, worst, steepest);
}

}  // namespace
}  // namespace gencoord
