// SPDX-License-Identifier: BSD-3-Clause
// The maximal model's pieces: consistent initial states, energy, generalized forces mapped to
// x-space, the manifold spring, and the errors it reports.
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/maximal/stability.hpp"
#include "test_models.hpp"

namespace gencoord {
namespace {

using crosscheck_testing::random_state;
using crosscheck_testing::random_vector;

template <class M>
class MaximalModelTest : public ::testing::Test {};

using Models =
    ::testing::Types<models::Pendulum, models::Pendulum3d, models::DoublePendulum,
                     models::SpringPendulum, models::CartPole, models::BeadOnRotatingHoop,
                     models::NLinkChain5, models::BeadOnParabola>;
TYPED_TEST_SUITE(MaximalModelTest, Models);

// x = X(q), xdot = J v + X_t: on the manifold (no violation) and with the reduced energy
TYPED_TEST(MaximalModelTest, ConsistentStateHasTheReducedEnergyAndNoViolation) {
  using M = TypeParam;
  const ParamsOf<M> p;
  const MaximalModel<M> model(p, 1e5);
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const State<M> s = random_state<M>(rng);
    const MaximalState<M> xs = to_maximal<M>(p, s);
    EXPECT_LT(model.max_constraint_violation(xs.q, xs.t), 1e-12) << M::name;
    const double e = M::energy(s.q, s.v, s.t, p);
    EXPECT_NEAR(model.energy(xs), e, 1e-11 * (1.0 + std::abs(e))) << M::name;
  }
}

// on the manifold the penalty forces vanish: the maximal force is the external one (plus the
// mapped generalized forces)
TYPED_TEST(MaximalModelTest, PenaltyForcesVanishOnTheManifold) {
  using M = TypeParam;
  const ParamsOf<M> p;
  const MaximalModel<M> model(p, 1e5);
  std::mt19937 rng(2);
  const State<M> s = random_state<M>(rng);
  const MaximalState<M> xs = to_maximal<M>(p, s);
  XVec<M> expected = MaximalOf<M>::external_forces(xs.q, xs.v, xs.t, p);
  if constexpr (MaximalOf<M>::has_generalized_forces) {
    const XJac<M> J = M::jacobian(s.q, s.t, p);
    const XVec<M> m = coordinate_masses<M>(p);
    expected +=
        m.asDiagonal() *
        (J * M::mass_matrix(s.q, s.t, p).llt().solve(M::generalized_forces(s.q, s.v, s.t, p)));
  }
  const XVec<M> f = model.force(xs.q, xs.v, xs.t);
  for (int i = 0; i < M::nx; ++i)
    EXPECT_NEAR(f[i], expected[i], 1e-9 * (1.0 + expected.cwiseAbs().maxCoeff())) << M::name;
}

// F = M J Mt^-1 Q projects back to Q: J^T F = Q (cart force, bead friction)
template <class M>
void expect_generalized_forces_mapped(const ParamsOf<M>& p) {
  static_assert(MaximalOf<M>::has_generalized_forces);
  const MaximalModel<M> with(p, 1e5);
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const State<M> s = random_state<M>(rng);
    const MaximalState<M> xs = to_maximal<M>(p, s);
    const XVec<M> mapped = with.force(xs.q, xs.v, xs.t) -
                           MaximalOf<M>::external_forces(xs.q, xs.v, xs.t, p) -
                           MaximalOf<M>::penalty_forces(xs.q, xs.v, xs.t, 1e5, 0.0, p);
    const QVec<M> Q = M::generalized_forces(s.q, s.v, s.t, p);
    const QVec<M> projected = M::jacobian(s.q, s.t, p).transpose() * mapped;
    ASSERT_GT(Q.norm(), 0.0);
    for (int i = 0; i < M::nq; ++i) EXPECT_NEAR(projected[i], Q[i], 1e-9) << M::name;
  }
}

TEST(MaximalGeneralizedForces, CartForceProjectsBack) {
  models::CartPole::Params p;
  p.u = 1.3;
  expect_generalized_forces_mapped<models::CartPole>(p);
}

TEST(MaximalGeneralizedForces, HoopFrictionProjectsBack) {
  models::BeadOnRotatingHoop::Params p;
  p.c = 0.4;
  expect_generalized_forces_mapped<models::BeadOnRotatingHoop>(p);
}

// the bead on a parabola declares no constraint: a zero-length spring kappa pulls it back to
// its closest point on the wire
TEST(MaximalManifoldSpring, PullsToTheClosestPoint) {
  using M = models::BeadOnParabola;
  const ParamsOf<M> p;
  const double kappa = 1e4;
  const MaximalModel<M> model(p, kappa);
  // above the vertex: the closest point is the vertex itself
  const Eigen::Vector2d x(0.0, 0.3), xdot(0.0, 0.0);
  model.set_warm_start(QVec<M>::Constant(0.1));
  const XVec<M> f = model.force(x, xdot, 0.0);
  EXPECT_NEAR(f[0], 0.0, 1e-9);
  EXPECT_NEAR(f[1], -p.m * p.g - kappa * 0.3, 1e-6);
  EXPECT_NEAR(model.max_constraint_violation(x, 0.0), 0.3, 1e-12);
  EXPECT_NEAR(model.energy({0.0, x, xdot}), p.m * p.g * 0.3 + 0.5 * kappa * 0.09, 1e-9);
  EXPECT_NEAR(model.warm_start()[0], 0.0, 1e-12);
}

TEST(MaximalModelErrors, RejectsNegativeKappaAndDamping) {
  EXPECT_THROW(MaximalModel<models::Pendulum>({}, -1.0), std::invalid_argument);
  EXPECT_THROW(MaximalModel<models::Pendulum>({}, 1.0, -0.1), std::invalid_argument);
  EXPECT_THROW(MaximalModel<models::Pendulum>({}, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
}

TEST(MaximalModelErrors, RejectsAMasslessParticle) {
  models::Pendulum3d::Params p;
  p.m_pivot = 0.0;
  EXPECT_THROW(MaximalModel<models::Pendulum3d>(p, 1e3), std::invalid_argument);
}

TEST(MaximalModelErrors, UnknownIntegratorName) {
  EXPECT_THROW(parse_integrator("leapfrog"), std::invalid_argument);
  EXPECT_EQ(parse_integrator("backward_euler"), Integrator::BackwardEuler);
}

TEST(MaximalModelErrors, BackwardEulerReportsNewtonFailure) {
  using M = models::DoublePendulum;
  const ParamsOf<M> p;
  const MaximalModel<M> model(p, 1e8);
  State<M> s;
  s.q = initial_q_of<M>();
  NewtonOptions one_iteration;
  one_iteration.max_iterations = 1;
  one_iteration.tolerance = 1e-14;
  try {
    backward_euler_step(model, to_maximal<M>(p, s), 0.05, one_iteration);
    FAIL() << "no NewtonError";
  } catch (const NewtonError& e) {
    EXPECT_NE(std::string(e.what()).find("double_pendulum (maximal)"), std::string::npos)
        << e.what();
    EXPECT_EQ(e.iterations(), 1);
  }
}

TEST(MaximalModelErrors, ExplicitDivergenceIsReported) {
  using M = models::Pendulum;
  const ParamsOf<M> p;
  const MaximalModel<M> model(p, 1e8);  // omega 1e4: dt = 1e-3 is 5x the limit
  State<M> s;
  s.q = initial_q_of<M>();
  EXPECT_THROW((simulate(model, to_maximal<M>(p, s), {Integrator::SymplecticEuler, 1e-3, 2.0},
                         [](const MaximalState<M>&) {})),
               MaximalDivergedError);
}

}  // namespace
}  // namespace gencoord
