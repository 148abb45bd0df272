// SPDX-License-Identifier: BSD-3-Clause
// Kapitza's pendulum: the inverted position theta = pi is stable when the pivot drive
// satisfies a^2 omega^2 > 2 g l, and falls over when the drive is much weaker.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/kapitza_pendulum.hpp"

namespace gencoord {
namespace {

using Kapitza = models::KapitzaPendulum;

// largest |theta - pi| over `duration` from theta = pi - 0.1 at rest, RK4
double max_deviation_from_upright(double omega, double duration) {
  Kapitza::Params p;
  p.a = 0.1;
  p.omega = omega;
  State<Kapitza> s;
  s.q[0] = M_PI - 0.1;
  // at least 100 steps per drive period, a whole number of steps in the run
  const double steps = std::ceil(duration / std::min(1e-3, 2.0 * M_PI / omega / 100.0));
  const double h = duration / steps;
  double worst = 0.0;
  simulate(ReducedSystem<Kapitza>(p), s, {Integrator::RK4, h, duration},
           [&](const State<Kapitza>& x) { worst = std::max(worst, std::abs(x.q[0] - M_PI)); });
  return worst;
}

TEST(Kapitza, InvertedPositionIsStableExactlyWhenTheDriveIsStrongEnough) {
  const Kapitza::Params p;
  const double threshold = 2.0 * p.g * p.l;
  // strong drive: a^2 omega^2 = 100 > 2 g l = 19.62
  const double strong = max_deviation_from_upright(100.0, 20.0);
  // weak drive: a^2 omega^2 = 1 < 19.62
  const double weak = max_deviation_from_upright(10.0, 20.0);
  std::printf(
      "Kapitza (a = 0.1 m, l = 1 m, 2 g l = %.2f m^2/s^2), from theta = pi - 0.1: "
      "omega = 100 (a^2 w^2 = 100): max |theta - pi| over 20 s = %.4f rad; omega = 10 "
      "(a^2 w^2 = 1): %.4f rad\n",
      threshold, strong, weak);
  EXPECT_LT(strong, 0.2);
  EXPECT_GT(weak, 1.0);  // fell over
}

}  // namespace
}  // namespace gencoord
