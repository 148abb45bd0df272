// SPDX-License-Identifier: BSD-3-Clause
// The spherical pendulum launched to pass close to the poles of its pole_down chart
// (theta, phi): with the two-chart atlas the simulation switches to the pole_x chart and
// back, conserves energy as well as away from the poles, and follows a Cartesian reference;
// in the single chart the same run loses accuracy and the monitor says why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "figures.hpp"
#include "gencoord/atlas/atlas.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/conditioning.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/spherical_pendulum.hpp"

namespace gencoord::testing {
namespace {

using models::SphericalPendulum;
using models::SphericalPendulumAtlas;
using Vec3 = Eigen::Vector3d;

constexpr double kDt = 1e-3;
constexpr double kDuration = 6.0;

/// A nearly planar swing through the bottom: theta goes from 0.8 through a minimum of about
/// 0.01 rad, where phi turns by almost pi within a few milliseconds.
State<SphericalPendulum> near_the_pole() {
  State<SphericalPendulum> s;
  s.q << 0.8, 0.3;
  s.v << -3.0, 0.03;
  return s;
}

/// The same pendulum in Cartesian coordinates, x'' = g + mu x with the rod tension mu from
/// d2/dt2 |x|^2 = 0, integrated by RK4 at a fine step: an independent reference.
class CartesianPendulum {
 public:
  CartesianPendulum(Vec3 x, Vec3 xdot, double g) : x_(x), xdot_(xdot), g_(0, 0, -g) {}
  void advance(double duration, int steps) {
    const double h = duration / steps;
    for (int k = 0; k < steps; ++k) {
      const Vec3 a1 = accel(x_, xdot_);
      const Vec3 x2 = x_ + 0.5 * h * xdot_, v2 = xdot_ + 0.5 * h * a1;
      const Vec3 a2 = accel(x2, v2);
      const Vec3 x3 = x_ + 0.5 * h * v2, v3 = xdot_ + 0.5 * h * a2;
      const Vec3 a3 = accel(x3, v3);
      const Vec3 x4 = x_ + h * v3, v4 = xdot_ + h * a3;
      const Vec3 a4 = accel(x4, v4);
      x_ += h / 6.0 * (xdot_ + 2.0 * v2 + 2.0 * v3 + v4);
      xdot_ += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    }
  }
  const Vec3& x() const { return x_; }

 private:
  Vec3 accel(const Vec3& x, const Vec3& xdot) const {
    const double mu = -(x.dot(g_) + xdot.squaredNorm()) / x.squaredNorm();
    return g_ + mu * x;
  }
  Vec3 x_, xdot_, g_;
};

struct AtlasRun {
  double max_energy_error = 0.0;
  double max_position_error = 0.0;  // against the Cartesian reference
  double max_condition = 0.0;
  std::vector<ChartSwitch> switches;
};

AtlasRun run_with_atlas(const State<SphericalPendulum>& start, const AtlasOptions& options) {
  const SphericalPendulum::Params p;
  AtlasSimulation<SphericalPendulumAtlas> atlas(p, start, options);
  CartesianPendulum reference(atlas.positions(), atlas.velocities(), p.g);
  const double e0 = atlas.energy();
  AtlasRun run;
  double t_reference = start.t;
  atlas.simulate(Integrator::RK4, kDt, kDuration, [&](const auto& a) {
    run.max_energy_error = std::max(run.max_energy_error, std::abs(a.energy() - e0));
    run.max_condition = std::max(run.max_condition, a.condition());
    reference.advance(a.time() - t_reference, 20);
    t_reference = a.time();
    run.max_position_error =
        std::max(run.max_position_error, (Vec3(a.positions()) - reference.x()).norm());
  });
  run.switches = atlas.switches();
  return run;
}

/// Max |E - E0| of an RK4 run in the single pole_down chart (observer also sees states).
template <class Observer>
double single_chart_energy_error(const State<SphericalPendulum>& start, Observer&& extra) {
  const SphericalPendulum::Params p;
  const double e0 = SphericalPendulum::energy(start.q, start.v, start.t, p);
  double worst = 0.0;
  simulate(ReducedSystem<SphericalPendulum>(p), start, {Integrator::RK4, kDt, kDuration},
           [&](const State<SphericalPendulum>& s) {
             worst = std::max(worst, std::abs(SphericalPendulum::energy(s.q, s.v, s.t, p) - e0));
             extra(s);
           });
  return worst;
}

/// Loops over the top in the x-z plane: it passes near both poles of both charts.
State<SphericalPendulum> looping() {
  State<SphericalPendulum> s;
  s.q << 0.8, 0.02;
  s.v << -7.0, 0.03;
  return s;
}

TEST(SphericalPendulumAtlas, LoopsThroughThePolesConservingEnergyAndFollowingTheReference) {
  const AtlasRun run = run_with_atlas(looping(), AtlasOptions{});
  // four poles per loop (about 1.1 s): the charts alternate
  ASSERT_GE(run.switches.size(), 16u);
  for (std::size_t k = 0; k < run.switches.size(); ++k) {
    const ChartSwitch& s = run.switches[k];
    EXPECT_FALSE(s.requested);
    EXPECT_NE(s.from, s.to);
    EXPECT_GT(s.estimate_from, 4.0);  // the default threshold: 4 x the best conditioning (1)
    EXPECT_LT(s.estimate_to, 2.0);
    if (k > 0) {
      EXPECT_GT(s.t, run.switches[k - 1].t);
      EXPECT_EQ(s.from, run.switches[k - 1].to);
    }
  }
  // one step past the threshold at most before the switch
  EXPECT_LT(run.max_condition, 4.5);

  // Away from the poles at the same energy (a fast swing around the vertical from the
  // horizontal, theta stays within [0.5, pi/2]), same integrator and step, one chart:
  const SphericalPendulum::Params p;
  const State<SphericalPendulum> start = looping();
  const double e0 = SphericalPendulum::energy(start.q, start.v, start.t, p);
  State<SphericalPendulum> around;
  around.q << 1.5707963267948966, 0.0;
  around.v << 0.0, std::sqrt(2.0 * e0 / (p.m * p.l * p.l));
  double min_theta = 10.0;
  const double away = single_chart_energy_error(
      around, [&](const auto& s) { min_theta = std::min(min_theta, s.q(0)); });
  EXPECT_GT(min_theta, 0.5);
  const double e_scale = p.m * p.g * p.l;
  RecordProperty("atlas_energy_error", scientific(run.max_energy_error / e_scale));
  RecordProperty("away_energy_error", scientific(away / e_scale));
  RecordProperty("position_error", scientific(run.max_position_error));
  EXPECT_LT(run.max_energy_error, 3.0 * away);    // measured 1.6x
  EXPECT_LT(run.max_position_error, 1e-8 * p.l);  // measured 3.7e-10
}

TEST(SphericalPendulumAtlas, SingleChartIsInaccurateAndTheMonitorSaysWhy) {
  const SphericalPendulum::Params p;
  ConditioningMonitor<SphericalPendulum> monitor(p, ConditioningPolicy::WarnOnce, 1e3);
  const double single = single_chart_energy_error(near_the_pole(), std::ref(monitor));
  const AtlasRun atlas = run_with_atlas(near_the_pole(), AtlasOptions{});
  EXPECT_TRUE(monitor.warned());
  EXPECT_GT(monitor.worst(), 1e3);
  EXPECT_GT(single, 100.0 * atlas.max_energy_error);
}

TEST(SphericalPendulumAtlas, SwitchingBackAndForthAddsNoErrorOfItsOwn) {
  // A conical swing where both charts are well conditioned: one run stays in pole_down,
  // the other changes chart every 10 steps. Both are compared with the Cartesian reference.
  const SphericalPendulum::Params p;
  State<SphericalPendulum> start;
  start.q << 1.0, 0.0;
  start.v << 0.0, 3.0;
  auto error_of = [&](int chart, int switch_every) {
    AtlasOptions never;
    never.switch_threshold = 1e300;
    AtlasSimulation<SphericalPendulumAtlas> atlas(p, start, never);
    atlas.switch_to(chart);
    CartesianPendulum reference(atlas.positions(), atlas.velocities(), p.g);
    const double e0 = atlas.energy();
    double worst = 0.0, worst_energy = 0.0;
    for (int k = 1; k <= 4000; ++k) {
      atlas.step(Integrator::RK4, kDt);
      if (switch_every && k % switch_every == 0) atlas.switch_to(1 - atlas.chart());
      reference.advance(kDt, 20);
      worst = std::max(worst, (Vec3(atlas.positions()) - reference.x()).norm());
      worst_energy = std::max(worst_energy, std::abs(atlas.energy() - e0));
    }
    EXPECT_EQ(atlas.switches().size(),
              std::size_t(chart) + (switch_every ? 4000u / switch_every : 0u));
    return std::pair(worst, worst_energy);
  };
  const auto [stay, stay_energy] = error_of(0, 0);
  const auto [stay_x, stay_x_energy] = error_of(1, 0);
  const auto [flip, flip_energy] = error_of(0, 10);
  RecordProperty("stay_error", scientific(stay));
  RecordProperty("stay_x_error", scientific(stay_x));
  RecordProperty("flip_error", scientific(flip));
  // 400 switches: the error stays the integrator's, between those of the two charts alone
  EXPECT_LT(flip, 2.0 * std::max(stay, stay_x) + 1e-12);
  EXPECT_LT(flip_energy, 2.0 * std::max(stay_energy, stay_x_energy) + 1e-12);
}

}  // namespace
}  // namespace gencoord::testing
