// SPDX-License-Identifier: BSD-3-Clause
// The 1D rod: lumped masses, mesh-independent static response, hanging under gravity.
#include "gencoord/deformable/rod.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {
namespace {

TEST(RodTest, LumpedMassesCoverHalfOfEachAdjacentInterval) {
  const std::vector<double> p = {0.0, 0.1, 0.4, 1.0};
  const MassSpringSystem<1> rod = make_rod(p, Material{3.0, 2.0, 0.0});
  // rho (p_{i+1} - p_{i-1}) / 2, half intervals at the ends, computed by hand
  const double expected[] = {2.0 * 0.1 / 2, 2.0 * 0.4 / 2, 2.0 * 0.9 / 2, 2.0 * 0.6 / 2};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(rod.mass(i), expected[i], 1e-15) << "node " << i;
  ASSERT_EQ(rod.springs.size(), 3u);
  EXPECT_NEAR(rod.springs[2].params.rest_length, 0.6, 1e-15);
  EXPECT_EQ(rod.springs[1].params.stiffness, 3.0);  // k = E
}

// x_i = alpha p_i: every spring has strain alpha - 1, so interior forces cancel exactly on any
// mesh because k = E is the same for every spring (why the stiffness is Young's modulus).
TEST(RodTest, UniformStretchGivesZeroNetForceOnInteriorNodesOfNonUniformMesh) {
  const std::vector<double> p = jittered_rod_nodes(25, 0.6, 7);
  MassSpringSystem<1> rod = make_rod(p, Material{5.0, 1.0, 0.0});
  const double alpha = 1.3;
  rod.x *= alpha;
  Eigen::Matrix<double, 1, Eigen::Dynamic> f =
      Eigen::Matrix<double, 1, Eigen::Dynamic>::Zero(1, rod.num_nodes());
  accumulate_forces(rod, f);
  for (int i = 1; i + 1 < rod.num_nodes(); ++i) {
    EXPECT_NEAR(f(0, i), 0.0, 1e-12) << "interior node " << i;
  }
  // the ends carry the tension E (alpha - 1) (what the end constraints supply)
  EXPECT_NEAR(f(0, 0), 5.0 * (alpha - 1.0), 1e-12);
  EXPECT_NEAR(f(0, rod.num_nodes() - 1), -5.0 * (alpha - 1.0), 1e-12);
}

// The same stretch with k proportional to the rest length (a common
// mistake) is not in equilibrium: this test would fail if the rod used such springs.
TEST(RodTest, RestLengthScaledSpringsWouldNotBeInEquilibrium) {
  const std::vector<double> p = jittered_rod_nodes(25, 0.6, 7);
  MassSpringSystem<1> rod = make_rod(p, Material{5.0, 1.0, 0.0});
  for (Spring& sp : rod.springs) sp.params.stiffness *= sp.params.rest_length * 25;
  rod.x *= 1.3;
  Eigen::Matrix<double, 1, Eigen::Dynamic> f =
      Eigen::Matrix<double, 1, Eigen::Dynamic>::Zero(1, rod.num_nodes());
  accumulate_forces(rod, f);
  double worst = 0.0;
  for (int i = 1; i + 1 < rod.num_nodes(); ++i) worst = std::max(worst, std::abs(f(0, i)));
  EXPECT_GT(worst, 0.1);
}

// Hanging from p = 0 under its own weight, a rod stretches by rho g l^2 / (2 E).
double HangingElongation(const std::vector<double>& p, double rho, double youngs, double g) {
  MassSpringSystem<1> rod = make_rod(p, Material{youngs, rho, 0.5});
  rod.pinned[0] = 1;
  rod.gravity(0) = g;  // gravity along +p: the rod hangs down from node 0
  // backward Euler with large steps (3 to 60 times the CFL limit here) and some damping
  // settles to the static state: the fundamental period 4 l / c is 0.28 s
  const double dt = 0.02;
  for (int k = 0; k < 300; ++k) backward_euler_step(rod, dt);
  return rod.x(0, rod.num_nodes() - 1) - p.back();
}

TEST(RodTest, HangingRodStretchesByRhoGLSquaredOverTwoE) {
  const double rho = 2.0, youngs = 400.0, g = 9.81, l = 1.0;
  const double expected = rho * g * l * l / (2.0 * youngs);
  const std::vector<std::pair<const char*, std::vector<double>>> meshes = {
      {"uniform 10", uniform_rod_nodes(10)},
      {"jittered 37", jittered_rod_nodes(37, 0.7, 11)},
      {"graded 50 (ratio 1.05)", graded_rod_nodes(50, 1.05)},
  };
  for (const auto& [name, p] : meshes) {
    const double measured = HangingElongation(p, rho, youngs, g);
    EXPECT_NEAR(measured, expected, 0.01 * expected)
        << name << ": elongation " << measured << " m, expected rho g l^2 / (2E) = " << expected;
    std::printf("[ hanging rod ] %s: elongation %.6f m, rho g l^2 / (2E) = %.6f m\n", name,
                measured, expected);
  }
}

}  // namespace
}  // namespace gencoord::deformable
