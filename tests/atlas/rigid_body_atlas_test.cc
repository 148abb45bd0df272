// SPDX-License-Identifier: BSD-3-Clause
// A free rigid body tumbling through gimbal lock: in Z-Y-X Euler angles alone the pitch
// reaches pi/2 and the mass matrix degenerates; with the two-order atlas (zyx, yzx) the
// simulation changes order near each lock and conserves energy and angular momentum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "figures.hpp"
#include "gencoord/atlas/atlas.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/conditioning.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/rigid_body_euler.hpp"

namespace gencoord::testing {
namespace {

using models::RigidBodyEuler;
using models::RigidBodyEulerAtlas;

/// Pitching fast from 1.5 rad, 0.07 rad short of gimbal lock: the body's x axis swings
/// past the vertical.
State<RigidBodyEuler> tumbling() {
  State<RigidBodyEuler> s;
  s.q << 0.0, 0.0, 0.0, 0.1, 1.5, 0.2;
  s.v << 0.0, 0.0, 0.0, 0.2, 2.5, 0.3;
  return s;
}

TEST(RigidBodyAtlas, SingleChartRunsIntoGimbalLock) {
  const RigidBodyEuler::Params p;
  ConditioningMonitor<RigidBodyEuler> monitor(p, ConditioningPolicy::Stop, 1e6);
  EXPECT_THROW((simulate(ReducedSystem<RigidBodyEuler>(p), tumbling(),
                         {Integrator::RK4, 1e-3, 10.0}, monitor)),
               SingularityError);
}

TEST(RigidBodyAtlas, TumblesThroughGimbalLockConservingEnergyAndMomentum) {
  const RigidBodyEuler::Params p;
  AtlasSimulation<RigidBodyEulerAtlas> atlas(p, tumbling());
  // cond(Mt) ~ 20 away from gimbal lock (masses vs inertias): the threshold is 4 times that
  EXPECT_GT(atlas.threshold(), 60.0);
  EXPECT_LT(atlas.threshold(), 100.0);
  const double e0 = atlas.energy();
  const Eigen::Vector3d l0 = atlas.angular_momentum();
  double energy_error = 0.0, momentum_error = 0.0, worst_condition = 0.0;
  atlas.simulate(Integrator::RK4, 1e-3, 10.0, [&](const auto& a) {
    energy_error = std::max(energy_error, std::abs(a.energy() - e0) / e0);
    momentum_error = std::max(momentum_error, (a.angular_momentum() - l0).norm() / l0.norm());
    worst_condition = std::max(worst_condition, a.condition());
  });
  RecordProperty("switches", static_cast<int>(atlas.switches().size()));
  RecordProperty("energy_error", scientific(energy_error));
  RecordProperty("momentum_error", scientific(momentum_error));
  ASSERT_GE(atlas.switches().size(), 2u);
  EXPECT_EQ(atlas.switches()[0].t, 0.0);  // it starts past the threshold: yzx at once
  for (const ChartSwitch& s : atlas.switches()) EXPECT_LT(s.estimate_to, atlas.threshold());
  EXPECT_LT(worst_condition, 1.2 * atlas.threshold());
  EXPECT_LT(energy_error, 1e-9);
  EXPECT_LT(momentum_error, 1e-9);
}

}  // namespace
}  // namespace gencoord::testing
