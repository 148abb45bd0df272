// SPDX-License-Identifier: BSD-3-Clause
// linearize_constrained against closed forms and a published benchmark:
//  - the rolling disk (models/rolling_disk.py): upright straight rolling, the eigenvalues of
//    lean, yaw rate and lean rate and the critical spin rate in closed form;
//  - the Whipple bicycle (models/whipple_bicycle.py), linearized from the generated nonlinear
//    model, against the linear equations of Meijaard et al. (2007) built from the same 25
//    parameters (whipple_benchmark.hpp): eigenvalues from 0 to 10 m/s, the weave and capsize
//    speeds; and simulated, self-stable at 5 m/s and falling at 3 m/s.
#include <algorithm>
#include <cmath>
#include <complex>

#include <gtest/gtest.h>

#include "bicycle_stability.hpp"
#include "figures.hpp"
#include "gencoord/control/constrained_linearization.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/four_bar.hpp"
#include "generated/rolling_disk.hpp"
#include "whipple_benchmark.hpp"

namespace gencoord::testing {
namespace {

using models::RollingDisk;

// the disk's eigenvalues: 0 and +-sqrt((m g r - (C + m r^2) C Omega^2 / A) / (A + m r^2))
std::complex<double> disk_root(const RollingDisk::Params& p, double spin) {
  const double A = p.m * p.r * p.r / 4 + p.m * p.h * p.h / 12, C = p.m * p.r * p.r / 2;
  const double mr2 = p.m * p.r * p.r;
  return std::sqrt(
      std::complex<double>((p.m * p.g * p.r - (C + mr2) * C * spin * spin / A) / (A + mr2)));
}

TEST(RollingDisk, UprightRollingEigenvaluesAreTheClosedForm) {
  const RollingDisk::Params p;
  CoordinateSplit split;
  split.independent_q = {3};     // lean
  split.independent_v = {2, 3};  // yaw rate, lean rate
  split.dependent_v = {0, 1};    // x', y' from rolling
  for (const double spin : {1.0, 3.0, 6.0, 12.0}) {
    State<RollingDisk> upright;
    upright.q.setZero();
    upright.v.setZero();
    upright.v[4] = spin;
    const auto linear = linearize_constrained<RollingDisk>(p, upright, split);
    const Eigen::EigenSolver<Eigen::Matrix3d> solver(linear.A, false);
    const std::complex<double> expected = disk_root(p, spin);
    double closest_zero = 1e300, closest_root = 1e300;
    for (int k = 0; k < 3; ++k) {
      const std::complex<double> value = solver.eigenvalues()[k];
      closest_zero = std::min(closest_zero, std::abs(value));
      closest_root =
          std::min(closest_root, std::min(std::abs(value - expected), std::abs(value + expected)));
    }
    EXPECT_LT(closest_zero, 1e-9) << "spin " << spin;
    EXPECT_LT(closest_root, 1e-9 * std::abs(expected)) << "spin " << spin;
    EXPECT_LT(linear.zdot.norm(), 1e-12) << "upright rolling is a steady motion";
  }
}

TEST(WhippleBicycle, EigenvaluesAreTheBenchmarksFrom0To10MetresPerSecond) {
  const bicycle::Bicycle::Params p;
  const whipple::BenchmarkParameters benchmark;
  double worst = 0;
  for (int k = 0; k <= 40; ++k) {
    const double speed = 0.25 * k;
    const auto ours = bicycle::eigenvalues(p, speed);
    const auto theirs = whipple::eigenvalues(benchmark, speed);
    for (const auto& value : theirs) {
      double closest = 1e300;
      for (const auto& candidate : ours) closest = std::min(closest, std::abs(candidate - value));
      worst = std::max(worst, closest / std::max(1.0, std::abs(value)));
    }
  }
  RecordProperty("worst_relative_difference", scientific(worst));
  EXPECT_LT(worst, 1e-9);
}

TEST(WhippleBicycle, WeaveAndCapsizeSpeedsAreTheBenchmarks) {
  const bicycle::Bicycle::Params p;
  const double weave = bicycle::weave_speed(p);
  const double capsize = bicycle::capsize_speed(p, weave);
  RecordProperty("weave_speed_error", scientific(weave - 4.292382536341));
  RecordProperty("capsize_speed_error", scientific(capsize - 6.024262015388));
  EXPECT_NEAR(weave, 4.292382536341, 1e-9);
  EXPECT_NEAR(capsize, 6.024262015388, 1e-9);
}

// The nonlinear bicycle, simulated: between the weave and capsize speeds a push on the
// roll dies out, below the weave speed it grows; the rolling constraints hold and no energy
// is lost (rolling without slipping does no work).
double roll_after_push(double speed, double push, double seconds, double* drift,
                       double* energy_change) {
  const bicycle::Bicycle::Params p;
  const ReducedSystem<bicycle::Bicycle> system(p);
  State<bicycle::Bicycle> s = bicycle::upright(p, speed, push);
  const double e0 = bicycle::Bicycle::energy(s.q, s.v, s.t, p);
  *drift = 0;
  double late_roll = 0;
  const int steps = static_cast<int>(seconds * 1000);
  for (int k = 0; k < steps; ++k) {
    s = step(system, Integrator::RK4, s, 1e-3);
    *drift = std::max(*drift, constraint_residual<bicycle::Bicycle>(p, s));
    if (k >= steps - 1000) late_roll = std::max(late_roll, std::abs(s.q[bicycle::kRoll]));
  }
  *energy_change = std::abs(bicycle::Bicycle::energy(s.q, s.v, s.t, p) - e0) / e0;
  return late_roll;
}

TEST(WhippleBicycle, SelfStableAt5MetresPerSecondAndFallingAt3) {
  double drift = 0, energy_change = 0;
  // 100 s of RK4 at dt = 1e-3, projected after each step: the drift stays at round-off
  const double stable = roll_after_push(5.0, 0.5, 100.0, &drift, &energy_change);
  RecordProperty("drift_at_5_m_per_s", scientific(drift));
  RecordProperty("energy_change_at_5_m_per_s", scientific(energy_change));
  EXPECT_LT(stable, 0.01);  // e^(-0.32 t) of the capsize mode: the push has died out
  EXPECT_LT(drift, 1e-10);
  EXPECT_LT(energy_change, 1e-9);
  // a push of 0.05 rad/s leans it by about 0.02 rad; the weave (real part +1.7 /s) grows
  // that thirtyfold in 2 s
  const double falling = roll_after_push(3.0, 0.05, 2.0, &drift, &energy_change);
  EXPECT_GT(falling, 0.1);
}

TEST(ConstrainedLinearization, AWrongSplitIsRefused) {
  CoordinateSplit split;  // the four-bar has two holonomic constraints
  split.independent_q = {0};
  split.dependent_q = {1};
  split.independent_v = {0};
  split.dependent_v = {1, 2};
  State<models::FourBar> s;
  s.q.setZero();
  s.v.setZero();
  EXPECT_THROW(linearize_constrained<models::FourBar>({}, s, split), std::invalid_argument);
}

}  // namespace
}  // namespace gencoord::testing
