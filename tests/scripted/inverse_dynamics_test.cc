// SPDX-License-Identifier: BSD-3-Clause
// The runtime's inverse_dynamics(): Mt a - (Ft + Fi) at any acceleration, zero at the forward
// dynamics' acceleration; and the free rows of the scripted residual vanish.
#include "gencoord/model/inverse_dynamics.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gencoord/model/dynamics.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/kapitza_pendulum.hpp"
#include "generated/n_link_chain_10.hpp"
#include "generated/rigid_body_euler.hpp"

namespace gencoord {
namespace {

template <class M>
void check_inverse_dynamics(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const ParamsOf<M> p;
  for (int trial = 0; trial < 50; ++trial) {
    QVec<M> q, v, a;
    for (int i = 0; i < M::nq; ++i) {
      q[i] = u(rng);  // |pitch| < 1: away from the rigid body's gimbal lock
      v[i] = 2.0 * u(rng);
      a[i] = 5.0 * u(rng);
    }
    const double t = 0.37 * trial;
    QMat<M> Mt;
    QVec<M> f;
    M::dynamics(q, v, t, p, &Mt, &f);
    const QVec<M> expected = Mt * a - f;
    const QVec<M> tau = inverse_dynamics<M>(p, q, v, a, t);
    const double scale = 1.0 + expected.cwiseAbs().maxCoeff();
    for (int i = 0; i < M::nq; ++i)
      EXPECT_NEAR(tau[i], expected[i], 1e-12 * scale)
          << M::name << " trial " << trial << " entry " << i;
    // at the forward dynamics' acceleration nothing is needed
    const QVec<M> tau0 = inverse_dynamics<M>(p, q, v, acceleration<M>(p, q, v, t), t);
    EXPECT_LT(tau0.cwiseAbs().maxCoeff(), 1e-11 * (1.0 + f.cwiseAbs().maxCoeff()))
        << M::name << " trial " << trial;
  }
}

TEST(InverseDynamics, EqualsMassMatrixTimesAccelerationMinusForces) {
  check_inverse_dynamics<models::DoublePendulum>(1);
  check_inverse_dynamics<models::NLinkChain10>(2);
  check_inverse_dynamics<models::KapitzaPendulum>(3);  // explicitly time-dependent
  check_inverse_dynamics<models::RigidBodyEuler>(4);
}

TEST(InverseDynamics, IsTheTorqueThatHoldsAPendulumStill) {
  // double pendulum held at rest at (theta1, theta2): tau = gravity torques
  const models::DoublePendulum::Params p;
  QVec<models::DoublePendulum> q(0.4, -0.7), zero = QVec<models::DoublePendulum>::Zero();
  const QVec<models::DoublePendulum> tau =
      inverse_dynamics<models::DoublePendulum>(p, q, zero, zero, 0.0);
  EXPECT_NEAR(tau[0], (p.m1 + p.m2) * p.g * p.l1 * std::sin(q[0]), 1e-12);
  EXPECT_NEAR(tau[1], p.m2 * p.g * p.l2 * std::sin(q[1]), 1e-12);
}

}  // namespace
}  // namespace gencoord
