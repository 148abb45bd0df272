// SPDX-License-Identifier: BSD-3-Clause
// The conditioning monitor on the spherical pendulum, whose coordinates are singular at the
// poles: launched to pass over the pole, the monitor reports it; away from it, it is quiet.
#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/conditioning.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/spherical_pendulum.hpp"

namespace gencoord::testing {
namespace {

using models::SphericalPendulum;

/// A swing in a vertical plane through the lower pole (phi fixed, no azimuthal motion):
/// with enough energy theta passes 0, where sin(theta) = 0 and Mt = diag(l^2, l^2 sin^2).
State<SphericalPendulum> over_the_pole() {
  State<SphericalPendulum> s;
  s.q << 0.3, 0.5;
  s.v << -3.0, 0.0;
  return s;
}

TEST(ConditioningMonitor, StopPolicyThrowsNearThePole) {
  const SphericalPendulum::Params p;
  ConditioningMonitor<SphericalPendulum> monitor(p, ConditioningPolicy::Stop, 1e6);
  EXPECT_THROW((simulate(ReducedSystem<SphericalPendulum>(p), over_the_pole(),
                         {Integrator::RK4, 1e-4, 0.5}, monitor)),
               SingularityError);
  EXPECT_GT(monitor.worst(), 1e6);
}

TEST(ConditioningMonitor, WarnPolicyWarnsOnceAndRecords) {
  const SphericalPendulum::Params p;
  ConditioningMonitor<SphericalPendulum> monitor(p, ConditioningPolicy::WarnOnce, 1e6);
  try {
    simulate(ReducedSystem<SphericalPendulum>(p), over_the_pole(), {Integrator::RK4, 1e-4, 0.5},
             monitor);
  } catch (const std::exception&) {
    // the dynamics may fail at the pole itself; the monitor must have warned before that
  }
  EXPECT_TRUE(monitor.warned());
  EXPECT_GT(monitor.worst(), 1e6);
}

TEST(ConditioningMonitor, QuietAwayFromThePoles) {
  const SphericalPendulum::Params p;
  State<SphericalPendulum> s;
  s.q << 1.0, 0.0;
  s.v << 0.0, 3.0;  // a conical swing, theta stays near 1
  ConditioningMonitor<SphericalPendulum> monitor(p, ConditioningPolicy::Stop, 1e6);
  EXPECT_NO_THROW(
      (simulate(ReducedSystem<SphericalPendulum>(p), s, {Integrator::RK4, 1e-3, 5.0}, monitor)));
  EXPECT_LT(monitor.worst(), 100.0);
  EXPECT_FALSE(monitor.warned());
}

}  // namespace
}  // namespace gencoord::testing
