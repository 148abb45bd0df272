// SPDX-License-Identifier: BSD-3-Clause
// Moving a state between charts: the particles' positions and velocities, hence the energy,
// are the same before and after, and the new chart is the better-conditioned one.
#include <gtest/gtest.h>

#include <cmath>

#include "gencoord/atlas/atlas.hpp"
#include "gencoord/atlas/chart_transfer.hpp"
#include "generated/rigid_body_euler.hpp"
#include "generated/spherical_pendulum.hpp"

namespace gencoord::testing {
namespace {

using models::SphericalPendulum;
using models::SphericalPendulumPoleX;

TEST(ChartTransfer, KeepsPositionsVelocitiesAndEnergy) {
  const SphericalPendulum::Params p;
  State<SphericalPendulum> s;
  s.t = 0.7;
  s.q << 0.05, 1.2;  // near the lower pole: badly conditioned in pole_down
  s.v << -1.5, 4.0;
  const auto mapped = transfer_state<SphericalPendulum, SphericalPendulumPoleX>(
      p, s, chart_guesses<SphericalPendulumPoleX>(std::nullopt, 16));
  ASSERT_TRUE(mapped.has_value());
  EXPECT_EQ(mapped->t, s.t);
  EXPECT_LT((SphericalPendulumPoleX::positions(mapped->q, mapped->t, p) -
             SphericalPendulum::positions(s.q, s.t, p))
                .norm(),
            1e-13);
  EXPECT_LT((SphericalPendulumPoleX::velocities(mapped->q, mapped->v, mapped->t, p) -
             SphericalPendulum::velocities(s.q, s.v, s.t, p))
                .norm(),
            1e-12);
  EXPECT_NEAR(SphericalPendulumPoleX::energy(mapped->q, mapped->v, mapped->t, p),
              SphericalPendulum::energy(s.q, s.v, s.t, p), 1e-12);
  EXPECT_GT(chart_condition<SphericalPendulum>(p, s.q, s.t), 300.0);
  EXPECT_LT(chart_condition<SphericalPendulumPoleX>(p, mapped->q, mapped->t), 1.1);
}

TEST(ChartTransfer, FindsTheRigidBodyOrientationFromAnyGuess) {
  using Zyx = models::RigidBodyEuler;
  using Yzx = models::RigidBodyEulerYzx;
  const Zyx::Params p;
  State<Zyx> s;
  s.q << 0.3, -0.2, 1.0, 2.5, 1.55, -2.0;  // pitch near pi/2: gimbal lock close
  s.v << 0.1, 0.2, -0.3, 0.4, 1.0, -0.7;
  // the initial guess of yzx (all zero) is far from the answer; the spread finds it
  const auto mapped = transfer_state<Zyx, Yzx>(p, s, chart_guesses<Yzx>(std::nullopt, 64));
  ASSERT_TRUE(mapped.has_value());
  EXPECT_LT((Yzx::positions(mapped->q, s.t, p) - Zyx::positions(s.q, s.t, p)).norm(), 1e-12);
  EXPECT_LT(
      (Yzx::velocities(mapped->q, mapped->v, s.t, p) - Zyx::velocities(s.q, s.v, s.t, p)).norm(),
      1e-11);
  EXPECT_LT(chart_condition<Yzx>(p, mapped->q, s.t) * 100.0, chart_condition<Zyx>(p, s.q, s.t));
}

TEST(ChartTransfer, RequestedSwitchIsRecordedAndExact) {
  const SphericalPendulum::Params p;
  State<SphericalPendulum> s;
  s.q << 1.0, 0.3;
  s.v << 0.5, 2.0;
  AtlasSimulation<models::SphericalPendulumAtlas> atlas(p, s);
  const auto x = atlas.positions();
  const auto xdot = atlas.velocities();
  atlas.switch_to(1);
  EXPECT_EQ(atlas.chart(), 1);
  EXPECT_STREQ(atlas.chart_name(), "pole_x");
  ASSERT_EQ(atlas.switches().size(), 1u);
  EXPECT_TRUE(atlas.switches()[0].requested);
  EXPECT_EQ(atlas.switches()[0].from, 0);
  EXPECT_LT((atlas.positions() - x).norm(), 1e-13);
  EXPECT_LT((atlas.velocities() - xdot).norm(), 1e-12);
  EXPECT_THROW(atlas.state<0>(), std::logic_error);
  EXPECT_NO_THROW(atlas.state<1>());
}

}  // namespace
}  // namespace gencoord::testing
