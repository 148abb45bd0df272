// SPDX-License-Identifier: BSD-3-Clause
// Measured order of accuracy of every integrator: error at t = 1 against the exact solution
// of a damped harmonic oscillator, for halving step sizes; the fitted log-log slope must be
// the nominal order within 0.15.
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandOscillator;
using test_models::oscillator_exact;

// least-squares slope of log(err) against log(dt)
double loglog_slope(const std::vector<double>& dts, const std::vector<double>& errs) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(dts.size());
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double x = std::log(dts[i]), y = std::log(errs[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

struct OrderCase {
  Integrator integrator;
  int coarsest_steps;  // steps to t = 1 at the largest dt; each further dt halves it
};

void PrintTo(const OrderCase& c, std::ostream* os) {
  *os << to_string(c.integrator) << " from " << c.coarsest_steps << " steps";
}

class OrderOfAccuracy : public ::testing::TestWithParam<OrderCase> {};

TEST_P(OrderOfAccuracy, SlopeMatchesNominalOrder) {
  const OrderCase c = GetParam();
  HandOscillator::Params p;
  p.m = 1.0;
  p.k = 4.0;  // omega0 = 2 rad/s
  p.c = 0.4;  // damping ratio 0.1, so the velocity dependence of a is exercised
  const double q0 = 1.0, v0 = 0.5, duration = 1.0;
  const Eigen::Vector2d exact = oscillator_exact(p, q0, v0, duration);

  std::vector<double> dts, errs;
  for (int level = 0, steps = c.coarsest_steps; level < 5; ++level, steps *= 2) {
    const double dt = duration / steps;
    State<HandOscillator> s;
    s.q[0] = q0;
    s.v[0] = v0;
    const State<HandOscillator> end = simulate(ReducedSystem<HandOscillator>(p), s,
                                               {c.integrator, dt, duration}, [](const auto&) {});
    dts.push_back(dt);
    errs.push_back(std::hypot(end.q[0] - exact[0], end.v[0] - exact[1]));
  }
  const double slope = loglog_slope(dts, errs);
  std::cout << "[ order    ] " << to_string(c.integrator) << ": slope " << slope << " (nominal "
            << order(c.integrator) << "), errors " << errs.front() << " .. " << errs.back() << '\n';
  EXPECT_NEAR(slope, order(c.integrator), 0.15) << to_string(c.integrator);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, OrderOfAccuracy,
                         ::testing::Values(OrderCase{Integrator::ForwardEuler, 100},
                                           OrderCase{Integrator::SymplecticEuler, 100},
                                           OrderCase{Integrator::BackwardEuler, 100},
                                           OrderCase{Integrator::Trapezoidal, 25},
                                           OrderCase{Integrator::ImplicitMidpoint, 25},
                                           OrderCase{Integrator::RK4, 10}),
                         [](const ::testing::TestParamInfo<OrderCase>& info) {
                           return std::string(to_string(info.param.integrator));
                         });

// the nominal orders themselves, so a wrong order() cannot make the test above pass
TEST(OrderOfAccuracy, NominalOrders) {
  EXPECT_EQ(order(Integrator::ForwardEuler), 1);
  EXPECT_EQ(order(Integrator::SymplecticEuler), 1);
  EXPECT_EQ(order(Integrator::BackwardEuler), 1);
  EXPECT_EQ(order(Integrator::Trapezoidal), 2);
  EXPECT_EQ(order(Integrator::ImplicitMidpoint), 2);
  EXPECT_EQ(order(Integrator::RK4), 4);
}

}  // namespace
}  // namespace gencoord
