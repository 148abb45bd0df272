// SPDX-License-Identifier: BSD-3-Clause
// The inverse map (x, xdot) -> (q, v): recovers random states from X(q), J v + X_t to 1e-10
// from a perturbed guess, and reports a point far off the manifold (InverseMapError).
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "gencoord/maximal/inverse_map.hpp"
#include "gencoord/maximal/state.hpp"
#include "test_models.hpp"

namespace gencoord {
namespace {

using crosscheck_testing::random_state;
using crosscheck_testing::random_vector;

template <class M>
class InverseMapTest : public ::testing::Test {};

using InverseMapModels =
    ::testing::Types<models::Pendulum, models::Pendulum3d, models::DoublePendulum,
                     models::SpringPendulum, models::CartPole, models::BeadOnRotatingHoop,
                     models::NLinkChain5, models::BeadOnParabola>;
TYPED_TEST_SUITE(InverseMapTest, InverseMapModels);

TYPED_TEST(InverseMapTest, RecoversRandomStates) {
  using M = TypeParam;
  const ParamsOf<M> p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> nudge(-0.2, 0.2);
  for (int trial = 0; trial < 200; ++trial) {
    const State<M> s = random_state<M>(rng);
    const MaximalState<M> xs = to_maximal<M>(p, s);
    QVec<M> guess = s.q;
    for (int i = 0; i < M::nq; ++i) guess[i] += nudge(rng);
    const State<M> r = inverse_map<M>(p, xs.q, xs.v, s.t, guess);
    for (int i = 0; i < M::nq; ++i) {
      EXPECT_NEAR(r.q[i], s.q[i], 1e-10) << M::name << " trial " << trial << " q(" << i << ")";
      EXPECT_NEAR(r.v[i], s.v[i], 1e-10) << M::name << " trial " << trial << " v(" << i << ")";
    }
    EXPECT_EQ(r.t, s.t);
  }
}

TYPED_TEST(InverseMapTest, NonFiniteInputIsReported) {
  using M = TypeParam;
  const ParamsOf<M> p;
  std::mt19937 rng(3);
  const State<M> s = random_state<M>(rng);
  XVec<M> x = M::positions(s.q, s.t, p);
  x[0] = std::numeric_limits<double>::quiet_NaN();
  try {
    inverse_map_positions<M>(p, x, s.t, s.q);
    FAIL() << M::name << ": no InverseMapError for a NaN position";
  } catch (const InverseMapError& e) {
    EXPECT_EQ(e.reason(), InverseMapError::Reason::kSingular) << e.what();
  }
}

// a point far off the manifold has a closest point, but it is not a reduced state
template <class M>
void expect_off_manifold(const XVec<M>& offset) {
  const ParamsOf<M> p;
  const QVec<M> q = initial_q_of<M>();
  const XVec<M> x = M::positions(q, 0.0, p) + offset;
  try {
    inverse_map_positions<M>(p, x, 0.0, q);
    FAIL() << M::name << ": no InverseMapError for a point " << offset.norm()
           << " off the manifold";
  } catch (const InverseMapError& e) {
    EXPECT_EQ(e.reason(), InverseMapError::Reason::kOffManifold) << e.what();
    EXPECT_GT(e.residual(), 0.1);
    EXPECT_GT(e.iterations(), 0);
    EXPECT_NE(std::string(e.what()).find("residual"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(M::name), std::string::npos) << e.what();
  }
  // with no residual limit the same point maps to its closest point
  InverseMapOptions anywhere;
  anywhere.max_residual = std::numeric_limits<double>::infinity();
  const auto closest = inverse_map_positions<M>(p, x, 0.0, q, anywhere);
  EXPECT_GT(closest.residual, 0.1);
  EXPECT_LE(closest.residual, offset.norm() + 1e-12);  // no farther than X(q) itself
}

TEST(InverseMapOffManifold, PendulumBobFarOutsideItsCircle) {
  expect_off_manifold<models::Pendulum>(Eigen::Vector2d(0.0, -2.0));
}

TEST(InverseMapOffManifold, Pendulum3dPivotMoved) {
  XVec<models::Pendulum3d> offset = XVec<models::Pendulum3d>::Zero();
  offset.head<3>() << 0.3, 0.2, 0.4;  // the pinned pivot displaced
  expect_off_manifold<models::Pendulum3d>(offset);
}

TEST(InverseMapOffManifold, DoublePendulumRodsStretched) {
  XVec<models::DoublePendulum> offset;
  offset << 0.5, -0.5, 0.3, 0.8;
  expect_off_manifold<models::DoublePendulum>(offset);
}

TEST(InverseMapOffManifold, CartPoleCartLifted) {
  XVec<models::CartPole> offset;
  offset << 0.0, 0.5, 0.0, 0.5;  // cart off its track, the whole system lifted
  expect_off_manifold<models::CartPole>(offset);
}

// every x is a state of the spring pendulum (nq = nx): nothing is off its manifold
TEST(InverseMapOffManifold, SpringPendulumHasNoOffManifoldPoints) {
  using M = models::SpringPendulum;
  const ParamsOf<M> p;
  const QVec<M> q = initial_q_of<M>();
  const XVec<M> x = M::positions(q, 0.0, p) + Eigen::Vector2d(0.3, -0.2);
  EXPECT_LT(inverse_map_positions<M>(p, x, 0.0, q).residual, 1e-12);
}

}  // namespace
}  // namespace gencoord
