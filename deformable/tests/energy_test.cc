// SPDX-License-Identifier: BSD-3-Clause
// Energy behaviour: bounded for undamped symplectic Euler, monotonically decreasing with
// damping.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "test_helpers.hpp"

namespace gencoord::deformable {
namespace {

using testing::kPi;

// A free rod on a non-uniform mesh, set vibrating in its first two modes.
MassSpringSystem<1> VibratingRod(double damping) {
  const std::vector<double> p = jittered_rod_nodes(30, 0.5, 21);
  MassSpringSystem<1> rod = make_rod(p, Material{1.0, 1.0, damping});
  for (int i = 0; i < rod.num_nodes(); ++i) {
    rod.x(0, i) += 0.01 * std::cos(kPi * p[i]);
    rod.v(0, i) = 0.02 * std::cos(2 * kPi * p[i]);
  }
  return rod;
}

TEST(EnergyTest, UndampedSymplecticEulerKeepsEnergyBoundedOver1e5Steps) {
  MassSpringSystem<1> rod = VibratingRod(0.0);
  const double e0 = total_energy(rod);
  const double dt = 0.9 * cfl_limit(rod);
  double worst = 0.0, early_mean = 0.0, late_mean = 0.0;
  const int steps = 100000, window = 10000;
  for (int k = 0; k < steps; ++k) {
    symplectic_euler_step(rod, dt);
    const double e = total_energy(rod);
    worst = std::max(worst, std::abs(e - e0) / e0);
    if (k < window) early_mean += e / window;
    if (k >= steps - window) late_mean += e / window;
  }
  // the energy oscillates (by O(dt omega)) about a constant but does not drift
  EXPECT_LT(worst, 0.05) << "largest relative energy error " << worst;
  EXPECT_NEAR(late_mean, early_mean, 1e-3 * e0)
      << "mean energy drifted from " << early_mean << " (first 1e4 steps) to " << late_mean
      << " (last 1e4 steps)";
  std::printf(
      "[ energy ] undamped, 1e5 steps at 0.9 CFL: max |E - E0| / E0 = %.3g, "
      "mean E / E0 first 1e4 steps %.6f, last 1e4 steps %.6f\n",
      worst, early_mean / e0, late_mean / e0);
}

TEST(EnergyTest, DampedEnergyDecreasesMonotonically) {
  for (bool implicit : {false, true}) {
    MassSpringSystem<1> rod = VibratingRod(0.02);
    const double e0 = total_energy(rod);
    const double dt = (implicit ? 5.0 : 0.5) * cfl_limit(rod);
    double previous = e0;
    for (int k = 0; k < 4000; ++k) {
      if (implicit) {
        backward_euler_step(rod, dt);
      } else {
        symplectic_euler_step(rod, dt);
      }
      const double e = total_energy(rod);
      ASSERT_LE(e, previous * (1 + 1e-12))
          << (implicit ? "backward" : "symplectic") << " Euler: energy rose from " << previous
          << " to " << e << " at step " << k;
      previous = e;
    }
    EXPECT_LT(previous, 0.2 * e0) << "damping removed too little energy";
    std::printf("[ energy ] damped %s Euler: E / E0 after 4000 steps = %.3g\n",
                implicit ? "backward" : "symplectic", previous / e0);
  }
}

}  // namespace
}  // namespace gencoord::deformable
