// SPDX-License-Identifier: BSD-3-Clause
// The implicit integrators: the composed trapezoidal and midpoint steps against independent
// direct implementations, and Newton's convergence, failure and counters.
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandOscillator;
using test_models::HandPendulum;
using ::testing::HasSubstr;

// The driven damped oscillator is linear: ydot = A y + b(t), with y = (q, v),
// A = [[0, 1], [-k/m, -c/m]], b(t) = (0, F0 cos(Omega t) / m).
struct LinearOscillator {
  HandOscillator::Params p;
  double b(double t) const { return p.F0 * std::cos(p.Omega * t) / p.m; }

  // solves (I - h/2 A) y1 = (I + h/2 A) y0 + h (0, forcing) by Cramer's rule
  Eigen::Vector2d solve(const Eigen::Vector2d& y0, double h, double forcing) const {
    const double a10 = -p.k / p.m, a11 = -p.c / p.m;
    // right-hand side (I + h/2 A) y0 + h (0, forcing)
    const double r0 = y0[0] + 0.5 * h * y0[1];
    const double r1 = y0[1] + 0.5 * h * (a10 * y0[0] + a11 * y0[1]) + h * forcing;
    // lhs matrix [[1, -h/2], [-h/2 a10, 1 - h/2 a11]]
    const double m00 = 1.0, m01 = -0.5 * h, m10 = -0.5 * h * a10, m11 = 1.0 - 0.5 * h * a11;
    const double det = m00 * m11 - m01 * m10;
    return {(r0 * m11 - m01 * r1) / det, (m00 * r1 - m10 * r0) / det};
  }
  // y1 = y0 + h/2 (f(y0, t0) + f(y1, t0 + h))
  Eigen::Vector2d trapezoidal(const Eigen::Vector2d& y0, double t0, double h) const {
    return solve(y0, h, 0.5 * (b(t0) + b(t0 + h)));
  }
  // y1 = y0 + h f((y0 + y1) / 2, t0 + h/2)
  Eigen::Vector2d midpoint(const Eigen::Vector2d& y0, double t0, double h) const {
    return solve(y0, h, b(t0 + 0.5 * h));
  }
};

LinearOscillator driven_oscillator() {
  LinearOscillator osc;
  osc.p.m = 1.5;
  osc.p.k = 6.0;
  osc.p.c = 0.3;
  osc.p.F0 = 2.0;
  osc.p.Omega = 3.0;  // time dependence separates trapezoidal from midpoint
  return osc;
}

State<HandOscillator> oscillator_state(double t, double q, double v) {
  State<HandOscillator> s;
  s.t = t;
  s.q[0] = q;
  s.v[0] = v;
  return s;
}

TEST(ImplicitSteps, TrapezoidalEqualsDirectTrapezoidalRule) {
  const LinearOscillator osc = driven_oscillator();
  for (const double t0 : {0.0, 0.37, 2.0})
    for (const double h : {0.01, 0.1, 0.5}) {
      const State<HandOscillator> s = oscillator_state(t0, 0.8, -1.3);
      const State<HandOscillator> out =
          trapezoidal_step(ReducedSystem<HandOscillator>(osc.p), s, h);
      const Eigen::Vector2d expected = osc.trapezoidal({s.q[0], s.v[0]}, t0, h);
      EXPECT_NEAR(out.q[0], expected[0], 1e-12) << "t0 = " << t0 << ", h = " << h;
      EXPECT_NEAR(out.v[0], expected[1], 1e-12) << "t0 = " << t0 << ", h = " << h;
      EXPECT_DOUBLE_EQ(out.t, t0 + h);
    }
}

TEST(ImplicitSteps, ImplicitMidpointEqualsDirectMidpointRule) {
  const LinearOscillator osc = driven_oscillator();
  for (const double t0 : {0.0, 0.37, 2.0})
    for (const double h : {0.01, 0.1, 0.5}) {
      const State<HandOscillator> s = oscillator_state(t0, 0.8, -1.3);
      const State<HandOscillator> out =
          implicit_midpoint_step(ReducedSystem<HandOscillator>(osc.p), s, h);
      const Eigen::Vector2d expected = osc.midpoint({s.q[0], s.v[0]}, t0, h);
      EXPECT_NEAR(out.q[0], expected[0], 1e-12) << "t0 = " << t0 << ", h = " << h;
      EXPECT_NEAR(out.v[0], expected[1], 1e-12) << "t0 = " << t0 << ", h = " << h;
      EXPECT_DOUBLE_EQ(out.t, t0 + h);
    }
}

TEST(ImplicitSteps, TrapezoidalAndMidpointDifferOnTheDrivenOscillator) {
  // guards the two tests above: with time-dependent forcing the rules are not the same
  const LinearOscillator osc = driven_oscillator();
  const Eigen::Vector2d y0(0.8, -1.3);
  EXPECT_GT((osc.trapezoidal(y0, 0.37, 0.5) - osc.midpoint(y0, 0.37, 0.5)).norm(), 1e-3);
}

TEST(ImplicitSteps, BackwardEulerSatisfiesItsEquation) {
  // pendulum, large step: v1 = v0 + h a(q0 + h v1, v1, t0 + h)
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.t = 0.5;
  s.q[0] = 2.5;
  s.v[0] = 3.0;
  const double h = 0.2;
  const State<HandPendulum> out = backward_euler_step(ReducedSystem<HandPendulum>(p), s, h);
  const QVec<HandPendulum> a = acceleration<HandPendulum>(p, out.q, out.v, s.t + h);
  EXPECT_NEAR(out.v[0], s.v[0] + h * a[0], 1e-12);
  EXPECT_NEAR(out.q[0], s.q[0] + h * out.v[0], 1e-15);
  EXPECT_DOUBLE_EQ(out.t, s.t + h);
}

TEST(Newton, ThrowsWhenIterationsRunOut) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 2.5;
  s.v[0] = 3.0;
  NewtonOptions tight;
  tight.max_iterations = 1;
  tight.tolerance = 1e-14;
  for (const Integrator i :
       {Integrator::BackwardEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    try {
      step(ReducedSystem<HandPendulum>(p), i, s, 0.2, tight);
      ADD_FAILURE() << to_string(i) << ": no NewtonError thrown";
    } catch (const NewtonError& e) {
      EXPECT_EQ(e.iterations(), 1) << to_string(i);
      EXPECT_EQ(e.model(), "hand_pendulum");
      EXPECT_EQ(e.tolerance(), 1e-14);
      EXPECT_GT(e.update_norm(), 1e-14);
      EXPECT_THAT(e.what(), HasSubstr("did not converge"));
      EXPECT_THAT(e.what(), HasSubstr("hand_pendulum"));
      EXPECT_THAT(e.what(), HasSubstr("1 iterations"));
    }
  }
  // the same steps converge with the default budget
  StepStats stats;
  EXPECT_NO_THROW(
      step(ReducedSystem<HandPendulum>(p), Integrator::BackwardEuler, s, 0.2, {}, &stats));
  EXPECT_GT(stats.newton_iterations, 1);
}

// |g| / scale of backward Euler's equation g = v1 - v0 - h a(t1, q1, v1) at a returned step,
// evaluated independently of the solver (NewtonOptions::residual_tolerance's scale)
double scaled_residual(const State<HandPendulum>& s0, const State<HandPendulum>& s1, double h) {
  const HandPendulum::Params p;
  const double a = acceleration<HandPendulum>(p, s1)[0];
  const double g = s1.v[0] - s0.v[0] - h * a;
  return std::abs(g) / (1.0 + std::abs(s0.v[0]) + std::abs(s1.v[0]) + h * std::abs(a));
}

// A small update is not enough: at h >> the period the Jacobian's h^2 term makes every update
// tiny while the equation is not satisfied at all. Every step either solves its equation (an
// independent residual check) or throws NewtonError with the residual and the step size.
TEST(Newton, ReturnsOnlySolutionsOfTheImplicitEquation) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 1.0;
  int refused = 0;
  for (double v0 : {0.0, 0.5}) {
    s.v[0] = v0;
    for (double h : {1e-3, 0.1, 1.0, 1e2, 1e4, 1e5, 1e8, 1e12, 1e100, 1e154, 1e200, 1e300}) {
      try {
        const State<HandPendulum> end =
            backward_euler_step(ReducedSystem<HandPendulum>(p), s, h, NewtonOptions{});
        EXPECT_LE(scaled_residual(s, end, h), 1e-6) << "v0 = " << v0 << ", h = " << h;
        EXPECT_TRUE(std::isfinite(end.q[0]) && std::isfinite(end.v[0])) << h;
      } catch (const NewtonError& e) {
        ++refused;
        EXPECT_EQ(e.step_size(), h);
        EXPECT_EQ(e.residual_tolerance(), 1e-6);
        EXPECT_TRUE(!(e.scaled_residual() <= 1e-6) || !std::isfinite(e.update_norm())) << e.what();
        EXPECT_THAT(e.what(), HasSubstr("residual norm"));
        EXPECT_THAT(e.what(), HasSubstr("of its scale"));
        EXPECT_THAT(e.what(), HasSubstr("residual_tolerance"));
      }
    }
  }
  EXPECT_GE(refused, 4);  // the huge steps from v0 = 0.5 at least
}

TEST(Newton, RefusesAHugeStepThatOnlyLooksConverged) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 1.0;
  s.v[0] = 0.5;
  for (double h : {1e12, 1e154}) {
    try {
      backward_euler_step(ReducedSystem<HandPendulum>(p), s, h, NewtonOptions{});
      ADD_FAILURE() << "h = " << h << ": no NewtonError thrown";
    } catch (const NewtonError& e) {
      EXPECT_GE(e.iterations(), 1);
      EXPECT_TRUE(e.scaled_residual() > 1e-3 || !std::isfinite(e.update_norm())) << e.what();
    }
  }
}

TEST(Newton, RejectsANegativeResidualTolerance) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 1.0;
  s.v[0] = 0.5;
  NewtonOptions bad;
  bad.residual_tolerance = -1.0;
  EXPECT_THROW(backward_euler_step(ReducedSystem<HandPendulum>(p), s, 0.1, bad),
               std::invalid_argument);
}

TEST(Newton, RejectsInvalidOptions) {
  const HandPendulum::Params p;
  NewtonOptions none;
  none.max_iterations = 0;
  EXPECT_THROW(
      backward_euler_step(ReducedSystem<HandPendulum>(p), State<HandPendulum>{}, 0.1, none),
      std::invalid_argument);
}

TEST(Newton, ConvergesFastOnALinearProblem) {
  const LinearOscillator osc = driven_oscillator();
  StepStats stats;
  State<HandOscillator> s = oscillator_state(0.0, 1.0, 0.0);
  for (int k = 0; k < 100; ++k)
    s = step(ReducedSystem<HandOscillator>(osc.p), Integrator::BackwardEuler, s, 0.05, {}, &stats);
  EXPECT_EQ(stats.steps, 100);
  EXPECT_EQ(stats.newton_solves, 100);
  // one update solves a linear problem; the next confirms it (FD Jacobian is not exact)
  EXPECT_LE(stats.max_newton_iterations, 3);
  EXPECT_GE(stats.newton_iterations, 200);
}

TEST(Newton, StatsCountOneSolvePerImplicitStepAndNoneForExplicit) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 1.0;
  for (const Integrator i :
       {Integrator::ForwardEuler, Integrator::SymplecticEuler, Integrator::RK4,
        Integrator::BackwardEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    StepStats stats;
    step(ReducedSystem<HandPendulum>(p), i, s, 0.01, {}, &stats);
    EXPECT_EQ(stats.steps, 1) << to_string(i);
    EXPECT_EQ(stats.newton_solves, is_implicit(i) ? 1 : 0) << to_string(i);
  }
}

}  // namespace
}  // namespace gencoord
