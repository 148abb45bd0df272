// SPDX-License-Identifier: BSD-3-Clause
// Generated models against closed forms that do not come from our code: the small-angle
// pendulum period, the textbook double-pendulum equations, the bead on a rotating hoop's
// equilibria, and energy conservation of the double pendulum.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/bead_on_rotating_hoop.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/pendulum.hpp"

namespace gencoord::testing {
namespace {

using models::BeadOnRotatingHoop;
using models::DoublePendulum;
using models::Pendulum;

TEST(Pendulum, SmallAnglePeriodIsTwoPiSqrtLOverG) {
  Pendulum::Params p;
  p.l = 0.7;
  p.g = 9.81;
  State<Pendulum> s;
  s.q[0] = 1e-3;  // the finite-amplitude correction is theta0^2 / 16 = 6e-8, far below 1e-4
  // period from upward zero crossings of theta, located by linear interpolation
  std::vector<double> crossings;
  double previous_theta = s.q[0], previous_t = 0.0;
  simulate(
      ReducedSystem<Pendulum>(p), s, {Integrator::RK4, 1e-3, 10.0}, [&](const State<Pendulum>& x) {
        if (previous_theta < 0.0 && x.q[0] >= 0.0) {
          crossings.push_back(previous_t +
                              (x.t - previous_t) * (-previous_theta) / (x.q[0] - previous_theta));
        }
        previous_theta = x.q[0];
        previous_t = x.t;
      });
  ASSERT_GE(crossings.size(), 3u);
  const double measured =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double expected = 2.0 * M_PI * std::sqrt(p.l / p.g);
  EXPECT_NEAR(measured / expected, 1.0, 1e-4)
      << "measured " << measured << " s, expected " << expected << " s";
}

TEST(DoublePendulum, MatchesTextbookEquationsOfMotion) {
  // (m1 + m2) l1 a1 + m2 l2 cos(d) a2 + m2 l2 sin(d) w2^2 + (m1 + m2) g sin(theta1) = 0
  // l2 a2 + l1 cos(d) a1 - l1 sin(d) w1^2 + g sin(theta2) = 0,  d = theta1 - theta2
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0), positive(0.5, 2.0);
  for (int k = 0; k < 50; ++k) {
    DoublePendulum::Params p;
    p.l1 = positive(rng);
    p.l2 = positive(rng);
    p.m1 = positive(rng);
    p.m2 = positive(rng);
    State<DoublePendulum> s;
    s.q << u(rng), u(rng);
    s.v << u(rng), u(rng);
    const auto a = acceleration<DoublePendulum>(p, s);
    const double d = s.q[0] - s.q[1];
    const double first = (p.m1 + p.m2) * p.l1 * a[0] + p.m2 * p.l2 * std::cos(d) * a[1] +
                         p.m2 * p.l2 * std::sin(d) * s.v[1] * s.v[1] +
                         (p.m1 + p.m2) * p.g * std::sin(s.q[0]);
    const double second = p.l2 * a[1] + p.l1 * std::cos(d) * a[0] -
                          p.l1 * std::sin(d) * s.v[0] * s.v[0] + p.g * std::sin(s.q[1]);
    EXPECT_NEAR(first, 0.0, 1e-11) << "state " << k;
    EXPECT_NEAR(second, 0.0, 1e-11) << "state " << k;
  }
}

TEST(DoublePendulum, Rk4ConservesEnergyFromHorizontal) {
  const DoublePendulum::Params p;
  State<DoublePendulum> s;
  s.q << M_PI / 2, 0.0;
  const double e0 = DoublePendulum::energy(s.q, s.v, s.t, p);
  const double e_rest = DoublePendulum::energy(QVec<DoublePendulum>::Zero().eval(),
                                               QVec<DoublePendulum>::Zero().eval(), 0.0, p);
  double worst = 0.0;
  simulate(ReducedSystem<DoublePendulum>(p), s, {Integrator::RK4, 1e-3, 10.0}, [&](const auto& x) {
    worst = std::max(worst, std::abs(DoublePendulum::energy(x.q, x.v, x.t, p) - e0));
  });
  EXPECT_LT(worst / (e0 - e_rest), 1e-8) << "max |dE| = " << worst;
}

/// Where the bead settles (theta after a long damped run) for a given hoop rate.
double settled_angle(double omega) {
  BeadOnRotatingHoop::Params p;
  p.omega = omega;
  p.c = 2.0;  // damping relative to the hoop, so the bead settles within the run
  State<BeadOnRotatingHoop> s;
  s.q[0] = 0.3;
  const auto end = simulate(ReducedSystem<BeadOnRotatingHoop>(p), s, {Integrator::RK4, 2e-3, 60.0},
                            [](const auto&) {});
  EXPECT_LT(std::abs(end.v[0]), 1e-6) << "not settled at omega = " << omega;
  return end.q[0];
}

TEST(BeadOnRotatingHoop, SettlesOffCentreAboveTheCriticalRate) {
  const BeadOnRotatingHoop::Params p;
  for (double omega : {4.0, 6.0, 10.0}) {  // omega^2 > g / R = 9.81
    const double theta = settled_angle(omega);
    EXPECT_NEAR(std::cos(theta), p.g / (omega * omega * p.R), 1e-8) << "omega = " << omega;
  }
}

TEST(BeadOnRotatingHoop, SettlesAtTheBottomBelowTheCriticalRate) {
  for (double omega : {1.0, 2.5}) {  // omega^2 < g / R
    EXPECT_NEAR(settled_angle(omega), 0.0, 1e-8) << "omega = " << omega;
  }
}

}  // namespace
}  // namespace gencoord::testing
