// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandPendulum;
using ::testing::HasSubstr;

constexpr Integrator kAll[] = {Integrator::ForwardEuler, Integrator::SymplecticEuler,
                               Integrator::RK4,          Integrator::BackwardEuler,
                               Integrator::Trapezoidal,  Integrator::ImplicitMidpoint};

TEST(ParseIntegrator, RoundTripsEveryName) {
  for (const Integrator i : kAll) EXPECT_EQ(parse_integrator(to_string(i)), i) << to_string(i);
  EXPECT_STREQ(to_string(Integrator::ImplicitMidpoint), "implicit_midpoint");
  EXPECT_STREQ(to_string(Integrator::RK4), "rk4");
}

TEST(ParseIntegrator, AcceptsCaseAndSeparatorVariants) {
  EXPECT_EQ(parse_integrator("RK4"), Integrator::RK4);
  EXPECT_EQ(parse_integrator("Backward-Euler"), Integrator::BackwardEuler);
  EXPECT_EQ(parse_integrator(std::string("implicit midpoint")), Integrator::ImplicitMidpoint);
}

TEST(ParseIntegrator, UnknownNameListsTheValidNames) {
  EXPECT_THROW(parse_integrator("euler"), std::invalid_argument);
  EXPECT_THROW(parse_integrator(""), std::invalid_argument);
  try {
    parse_integrator("leapfrog");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("'leapfrog'"));
    for (const Integrator i : kAll) EXPECT_THAT(what, HasSubstr(to_string(i)));
  }
}

TEST(Step, RejectsBadStepSizes) {
  const HandPendulum::Params p;
  const State<HandPendulum> s;
  for (const double dt : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity()})
    EXPECT_THROW(step(ReducedSystem<HandPendulum>(p), Integrator::RK4, s, dt), StepSizeError) << dt;
}

TEST(Step, ExplicitStepsMatchTheirDefinitions) {
  // one step by hand on the pendulum: a(q) = -(g/l) sin q
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.t = 1.0;
  s.q[0] = 0.6;
  s.v[0] = -0.4;
  const double h = 0.1, q0 = 0.6, v0 = -0.4;
  auto a = [&](double q) { return -p.g / p.l * std::sin(q); };

  const State<HandPendulum> fe =
      step(ReducedSystem<HandPendulum>(p), Integrator::ForwardEuler, s, h);
  EXPECT_DOUBLE_EQ(fe.q[0], q0 + h * v0);
  EXPECT_DOUBLE_EQ(fe.v[0], v0 + h * a(q0));
  EXPECT_DOUBLE_EQ(fe.t, 1.1);

  const State<HandPendulum> se =
      step(ReducedSystem<HandPendulum>(p), Integrator::SymplecticEuler, s, h);
  const double v1 = v0 + h * a(q0);
  EXPECT_DOUBLE_EQ(se.v[0], v1);
  EXPECT_DOUBLE_EQ(se.q[0], q0 + h * v1);

  const State<HandPendulum> rk = step(ReducedSystem<HandPendulum>(p), Integrator::RK4, s, h);
  const double k1q = v0, k1v = a(q0);
  const double k2q = v0 + h / 2 * k1v, k2v = a(q0 + h / 2 * k1q);
  const double k3q = v0 + h / 2 * k2v, k3v = a(q0 + h / 2 * k2q);
  const double k4q = v0 + h * k3v, k4v = a(q0 + h * k3q);
  EXPECT_NEAR(rk.q[0], q0 + h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q), 1e-15);
  EXPECT_NEAR(rk.v[0], v0 + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v), 1e-15);
}

}  // namespace
}  // namespace gencoord
