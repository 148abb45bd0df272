// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/model/dynamics.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandCoupled;
using test_models::HandOscillator;
using test_models::HandPendulum;
using ::testing::HasSubstr;

TEST(Acceleration, PendulumMatchesClosedForm) {
  HandPendulum::Params p;
  p.l = 2.0;
  for (const double theta : {-2.0, -0.3, 0.0, 0.7, 3.0}) {
    const QVec<HandPendulum> a =
        acceleration<HandPendulum>(p, QVec<HandPendulum>(theta), QVec<HandPendulum>(1.5), 0.0);
    EXPECT_NEAR(a[0], -p.g / p.l * std::sin(theta), 1e-14) << "theta = " << theta;
  }
}

TEST(Acceleration, CoupledMatchesDenseSolve) {
  const HandCoupled::Params p;
  State<HandCoupled> s;
  s.q << 0.3, -0.8;
  s.v << 1.0, 2.0;
  const QVec<HandCoupled> a = acceleration<HandCoupled>(p, s);
  const QVec<HandCoupled> expected =
      HandCoupled::mass_matrix(s.q, s.t, p).inverse() * HandCoupled::forces(s.q, s.v, s.t, p);
  EXPECT_LT((a - expected).norm(), 1e-14);
}

// runs acceleration() and returns the DynamicsError it throws
DynamicsError dynamics_error(const HandCoupled::Params& p) {
  State<HandCoupled> s;
  s.t = 0.25;
  s.q << 0.125, -2.5;
  try {
    acceleration<HandCoupled>(p, s);
  } catch (const DynamicsError& e) {
    return e;
  }
  ADD_FAILURE() << "no DynamicsError thrown";
  return DynamicsError("none", DynamicsError::Reason::kNotPositiveDefinite, 0, {}, {});
}

TEST(Acceleration, IndefiniteMassMatrixThrows) {
  HandCoupled::Params p;
  p.c = 2.0;  // c^2 > m1 m2
  const DynamicsError e = dynamics_error(p);
  EXPECT_EQ(e.reason(), DynamicsError::Reason::kNotPositiveDefinite);
  EXPECT_EQ(e.model(), "hand_coupled");
  EXPECT_EQ(e.time(), 0.25);
  EXPECT_EQ(e.q(), (std::vector<double>{0.125, -2.5}));
  const std::string what = e.what();
  EXPECT_THAT(what, HasSubstr("hand_coupled"));
  EXPECT_THAT(what, HasSubstr("positive definite"));
  EXPECT_THAT(what, HasSubstr("t = 0.25"));
  EXPECT_THAT(what, HasSubstr("q = [0.125, -2.5]"));
}

TEST(Acceleration, SingularMassMatrixThrows) {
  HandCoupled::Params p;
  p.c = std::sqrt(p.m1 * p.m2);  // det Mt = 0 (up to rounding)
  p.c = std::nextafter(p.c, 10.0);
  EXPECT_EQ(dynamics_error(p).reason(), DynamicsError::Reason::kNotPositiveDefinite);
}

TEST(Acceleration, NaNMassMatrixThrows) {
  HandCoupled::Params p;
  p.m2 = std::numeric_limits<double>::quiet_NaN();
  const DynamicsError e = dynamics_error(p);
  EXPECT_EQ(e.reason(), DynamicsError::Reason::kNonFiniteMassMatrix);
  EXPECT_THAT(e.what(), HasSubstr("hand_coupled"));
  EXPECT_THAT(e.what(), HasSubstr("NaN"));
}

TEST(Acceleration, InfiniteMassMatrixThrows) {
  HandCoupled::Params p;
  p.m1 = std::numeric_limits<double>::infinity();
  EXPECT_EQ(dynamics_error(p).reason(), DynamicsError::Reason::kNonFiniteMassMatrix);
}

TEST(Acceleration, NaNForcesThrow) {
  HandCoupled::Params p;
  p.f_bias = std::numeric_limits<double>::quiet_NaN();
  const DynamicsError e = dynamics_error(p);
  EXPECT_EQ(e.reason(), DynamicsError::Reason::kNonFiniteForces);
  EXPECT_THAT(e.what(), HasSubstr("NaN"));
}

TEST(Acceleration, ErrorsPropagateThroughEveryIntegrator) {
  HandCoupled::Params p;
  p.c = 2.0;
  const State<HandCoupled> s;
  for (const Integrator i :
       {Integrator::ForwardEuler, Integrator::SymplecticEuler, Integrator::RK4,
        Integrator::BackwardEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    EXPECT_THROW(step(ReducedSystem<HandCoupled>(p), i, s, 0.01), DynamicsError) << to_string(i);
  }
}

TEST(AccelerationJacobians, FiniteDifferencesMatchAnalytic) {
  // pendulum: da/dq = -(g/l) cos q, da/dv = 0
  const HandPendulum::Params pp;
  for (const double theta : {-2.0, 0.0, 0.4, 25.0}) {
    QMat<HandPendulum> a_D_q, a_D_v;
    acceleration_jacobians<HandPendulum>(pp, QVec<HandPendulum>(theta), QVec<HandPendulum>(3.0),
                                         0.0, &a_D_q, &a_D_v);
    // the FD step grows with |q|, and the truncation error with its square
    const double tol = 1e-8 * (1.0 + theta * theta);
    EXPECT_NEAR(a_D_q(0, 0), -pp.g / pp.l * std::cos(theta), tol) << "theta = " << theta;
    EXPECT_NEAR(a_D_v(0, 0), 0.0, 1e-8);
  }
  // coupled, linear: a = Mt^-1 (-k q + f), so da/dq = -k Mt^-1, da/dv = 0
  const HandCoupled::Params pc;
  State<HandCoupled> s;
  s.q << 0.3, -40.0;
  s.v << 1.0, 2.0;
  QMat<HandCoupled> a_D_q, a_D_v;
  acceleration_jacobians<HandCoupled>(pc, s.q, s.v, s.t, &a_D_q, &a_D_v);
  const QMat<HandCoupled> expected = -pc.k * HandCoupled::mass_matrix(s.q, s.t, pc).inverse();
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(a_D_q(r, c), expected(r, c), 1e-8)
          << "a_D_q mismatch at (" << r << ", " << c << ")";
      EXPECT_NEAR(a_D_v(r, c), 0.0, 1e-8) << "a_D_v mismatch at (" << r << ", " << c << ")";
    }
  // damped oscillator: da/dv = -c/m
  HandOscillator::Params po;
  po.c = 0.7;
  QMat<HandOscillator> o_D_q, o_D_v;
  acceleration_jacobians<HandOscillator>(po, QVec<HandOscillator>(0.1), QVec<HandOscillator>(-0.2),
                                         0.0, &o_D_q, &o_D_v);
  EXPECT_NEAR(o_D_q(0, 0), -po.k / po.m, 1e-8);
  EXPECT_NEAR(o_D_v(0, 0), -po.c / po.m, 1e-8);
}

}  // namespace
}  // namespace gencoord
