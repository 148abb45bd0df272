// SPDX-License-Identifier: BSD-3-Clause
// The generated robot models against MuJoCo on the same URDF: the mass matrix (mj_fullM), the
// bias forces (qfrc_bias), the accelerations (qacc of mj_forward) and inverse dynamics (mj_rne)
// at random states, and a 2 s RK4 trajectory at the same step.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "gencoord/gencoord.hpp"
#include "generated/iiwa14.hpp"
#include "generated/quadruped.hpp"
#include "generated/ur5e.hpp"
#include "kernel_comparison.hpp"
#include "mujoco_model.hpp"
#include "test_files.hpp"

namespace gencoord {
namespace {

using robot_testing::MujocoReference;
using robot_testing::relative;

template <class M>
struct Robot;
// `kernels` bounds the relative differences of the mass matrix and the bias forces, `solved`
// those of qddot, inverse dynamics and the trajectory. The iiwa's inertias are diagonal, which
// MuJoCo stores exactly. The quadruped's are not: MuJoCo keeps principal moments and a
// quaternion from its own 3x3 eigensolver, which gives back the URDF's tensor only to about
// 1e-8 relative (a thigh's izz 0.001367788 becomes 0.00136778799457), and qddot multiplies
// that by the conditioning of Mt.
template <>
struct Robot<models::Iiwa14> {
  static std::string urdf() { return robot_testing::source_file("models/iiwa14.urdf"); }
  static constexpr double kernels = 1e-9, solved = 1e-9, trajectory = 1e-8;
};
template <>
struct Robot<models::Ur5e> {  // diagonal inertias too
  static std::string urdf() { return robot_testing::source_file("models/ur5e.urdf"); }
  static constexpr double kernels = 1e-9, solved = 1e-9, trajectory = 1e-8;
};
template <>
struct Robot<models::Quadruped> {
  static std::string urdf() { return robot_testing::source_file("models/quadruped.urdf"); }
  static constexpr double kernels = 1e-8, solved = 1e-6, trajectory = 1e-6;
};

template <class M>
class MujocoReferenceTest : public ::testing::Test {};
using MujocoRobots = ::testing::Types<models::Iiwa14, models::Ur5e, models::Quadruped>;
TYPED_TEST_SUITE(MujocoReferenceTest, MujocoRobots);

/// q anywhere in (-pi, pi), v in (-2, 2) rad/s.
template <class M>
State<M> random_mujoco_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-2.0, 2.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = angle(rng);
    s.v[i] = rate(rng);
  }
  return s;
}

TYPED_TEST(MujocoReferenceTest, KernelsMatchAtRandomStates) {
  using M = TypeParam;
  MujocoReference<M> mujoco(Robot<M>::urdf());
  const typename M::Params p;
  std::mt19937 rng(20261123);
  robot_testing::WorstDifferences worst;
  for (int k = 0; k < 100; ++k) {
    const State<M> s = random_mujoco_state<M>(rng);
    mujoco.forward(s.q, s.v);
    worst.mass_matrix =
        std::max(worst.mass_matrix, relative(M::mass_matrix(s.q, s.t, p), mujoco.mass_matrix()));
    const auto f = M::forces(s.q, s.v, s.t, p);
    worst.bias = std::max(worst.bias, relative(f, -mujoco.bias()));
    const auto qdd = M::qddot(s.q, s.v, s.t, p);
    worst.qddot = std::max(worst.qddot, relative(qdd, mujoco.qacc()));
    worst.inverse_dynamics = std::max(
        worst.inverse_dynamics,
        relative(M::inverse_dynamics(s.q, s.v, qdd, s.t, p), mujoco.inverse_dynamics(qdd)));
  }
  worst.check(M::name, Robot<M>::kernels, Robot<M>::solved);
}

TYPED_TEST(MujocoReferenceTest, RK4TrajectoryFollowsMujoco) {
  using M = TypeParam;
  MujocoReference<M> mujoco(Robot<M>::urdf());
  const typename M::Params p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-1.0, 1.0), rate(-0.5, 0.5);
  State<M> initial;
  for (int i = 0; i < M::nq; ++i) {
    initial.q[i] = angle(rng);
    initial.v[i] = rate(rng);
  }
  const double dt = 1e-3, duration = 2.0;
  mujoco.set(initial.q, initial.v);
  mujoco.model()->opt.timestep = dt;
  double worst = 0.0;
  int step = 0;
  simulate(robot_testing::without_limits<M>(p), initial,
           SimulateOptions(Integrator::RK4, dt, duration), [&](const State<M>& s) {
             if (step++ > 0) mj_step(mujoco.model(), mujoco.data());
             worst = std::max(worst, (s.q - mujoco.q()).template lpNorm<Eigen::Infinity>());
           });
  EXPECT_EQ(step, 2001);
  EXPECT_LT(worst, Robot<M>::trajectory);
  std::printf("%s: largest |q - q_MuJoCo| over 2 s of RK4 at dt = 1 ms: %.2g rad\n", M::name,
              worst);
}

}  // namespace
}  // namespace gencoord
