// SPDX-License-Identifier: BSD-3-Clause
// The maximal model of a model with generalized speeds (tests/python_module/floating_arm.py:
// a free trunk, a ball-jointed arm and a motorized hand; nq = 12, nv = 10): the inverse map
// steps along the speeds and keeps quaternions unit, recovers random states from X(q),
// J v + X_t, finds the closest point of a point off the manifold (J^T (x - X(q)) = 0), and
// the hand's motor torque maps to an x-space force whose J^T-projection is the torque.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "gencoord/maximal/inverse_map.hpp"
#include "gencoord/maximal/model.hpp"
#include "gencoord/maximal/state.hpp"
#include "gencoord/model/tangent_space.hpp"
#include "generated/floating_arm.hpp"

namespace gencoord {
namespace {

using M = models::FloatingArm;
static_assert(has_generalized_speeds_v<M> && M::nq == 12 && nv_of_v<M> == 10);
static_assert(MaximalOf<M>::has_generalized_forces && MaximalOf<M>::num_constraints > 0);

// the initial pose turned and moved by a random deviation (unit quaternions), random speeds
State<M> random_turned_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> turn(-1.0, 1.0), speed(-2.0, 2.0), time(0.0, 2.0);
  const ParamsOf<M> p;
  VVec<M> delta, v;
  for (int j = 0; j < nv_of_v<M>; ++j) {
    delta[j] = turn(rng);
    v[j] = speed(rng);
  }
  State<M> s;
  s.q = retract<M>(p, initial_q_of<M>(), delta);
  s.v = v;
  s.t = time(rng);
  return s;
}

// |q_k| of each quaternion
void expect_unit_quaternions(const QVec<M>& q) {
  for (const int start : M::quaternion_starts)
    EXPECT_NEAR(q.segment<4>(start).norm(), 1.0, 1e-14) << "quaternion at " << start;
}

TEST(SpeedsInverseMap, RecoversRandomStates) {
  const ParamsOf<M> p;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> nudge(-0.15, 0.15);
  for (int trial = 0; trial < 100; ++trial) {
    const State<M> s = random_turned_state(rng);
    const MaximalState<M> xs = to_maximal<M>(p, s);
    VVec<M> off;
    for (int j = 0; j < nv_of_v<M>; ++j) off[j] = nudge(rng);
    const QVec<M> guess = retract<M>(p, s.q, off);
    const State<M> r = inverse_map<M>(p, xs.q, xs.v, s.t, guess);
    expect_unit_quaternions(r.q);
    // the same configuration (a quaternion's sign aside): no deviation between them
    const VVec<M> between = local_coordinates<M>(p, s.q, r.q);
    EXPECT_LT(between.cwiseAbs().maxCoeff(), 1e-10) << "trial " << trial;
    EXPECT_LT((r.v - s.v).cwiseAbs().maxCoeff(), 1e-10) << "trial " << trial;
  }
}

// off the manifold the closest point is a stationary point of |x - X(q)|^2 along every speed,
// J^T (x - X(q)) = 0, and no farther than the configuration the point was moved from
TEST(SpeedsInverseMap, FindsTheClosestPointOffTheManifold) {
  const ParamsOf<M> p;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> push(-0.05, 0.05);
  InverseMapOptions anywhere;
  anywhere.max_residual = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 20; ++trial) {
    const State<M> s = random_turned_state(rng);
    XVec<M> offset;
    for (int i = 0; i < M::nx; ++i) offset[i] = push(rng);
    const XVec<M> x = M::positions(s.q, s.t, p) + offset;
    const auto closest = inverse_map_positions<M>(p, x, s.t, s.q, anywhere);
    expect_unit_quaternions(closest.q);
    const XVec<M> r = x - M::positions(closest.q, s.t, p);
    const VVec<M> gradient = M::jacobian(closest.q, s.t, p).transpose() * r;
    EXPECT_LT(gradient.cwiseAbs().maxCoeff(), 1e-10) << "trial " << trial;
    EXPECT_NEAR(closest.residual, r.norm(), 1e-14);
    EXPECT_LE(closest.residual, offset.norm() + 1e-12) << "trial " << trial;
    EXPECT_GT(closest.residual, 0.1 * offset.norm()) << "trial " << trial;
  }
}

// the hand's motor torque, mapped as F = M J Mt^-1 Q, projects back: J^T F = Q
TEST(SpeedsMaximalModel, MotorTorqueProjectsBack) {
  ParamsOf<M> p;
  p.u = 0.4;
  const double kappa = 1e5;
  const MaximalModel<M> model(p, kappa);
  std::mt19937 rng(13);
  for (int trial = 0; trial < 20; ++trial) {
    const State<M> s = random_turned_state(rng);
    const MaximalState<M> xs = to_maximal<M>(p, s);
    model.set_warm_start(s.q);
    const XVec<M> mapped = model.force(xs.q, xs.v, xs.t) -
                           MaximalOf<M>::external_forces(xs.q, xs.v, xs.t, p) -
                           MaximalOf<M>::penalty_forces(xs.q, xs.v, xs.t, kappa, 0.0, p);
    const VVec<M> Q = M::generalized_forces(s.q, s.v, s.t, p);
    ASSERT_GT(Q.norm(), 0.0);
    const VVec<M> projected = M::jacobian(s.q, s.t, p).transpose() * mapped;
    EXPECT_LT((projected - Q).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
  }
}

// x = X(q), xdot = J v + X_t: on the manifold, with the reduced energy
TEST(SpeedsMaximalModel, ConsistentStateHasTheReducedEnergyAndNoViolation) {
  const ParamsOf<M> p;
  const MaximalModel<M> model(p, 1e5);
  std::mt19937 rng(14);
  for (int trial = 0; trial < 20; ++trial) {
    const State<M> s = random_turned_state(rng);
    const MaximalState<M> xs = to_maximal<M>(p, s);
    model.set_warm_start(s.q);
    EXPECT_LT(model.max_constraint_violation(xs.q, xs.t), 1e-12);
    const double e = M::energy(s.q, s.v, s.t, p);
    EXPECT_NEAR(model.energy(xs), e, 1e-11 * (1.0 + std::abs(e)));
  }
}

}  // namespace
}  // namespace gencoord
