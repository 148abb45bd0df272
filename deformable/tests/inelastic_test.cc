// SPDX-License-Identifier: BSD-3-Clause
// Fracture happens on the step where a spring's strain first passes the threshold; plasticity
// leaves the permanent set documented in InelasticParams.
#include "gencoord/deformable/inelastic.hpp"

#include <gtest/gtest.h>

#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {
namespace {

// A chain of unit springs along x whose nodes are all pinned and driven at constant
// velocities, so every strain is known in closed form: spring s has strain (v_{s+1} - v_s) t.
MassSpringSystem<1> DrivenChain(const std::vector<double>& velocities) {
  const int n = static_cast<int>(velocities.size());
  std::vector<double> p(n);
  for (int i = 0; i < n; ++i) p[i] = i;
  MassSpringSystem<1> s = make_rod(p, Material{1.0, 1.0, 0.0});
  for (int i = 0; i < n; ++i) {
    s.pinned[i] = 1;
    s.v(0, i) = velocities[i];
  }
  return s;
}

TEST(InelasticTest, SpringBreaksOnTheStepWhereStrainFirstPassesTheThreshold) {
  // strains 0.01 t, 0.02 t, 0: with threshold 0.1 and dt = 0.3, spring 1 passes it at
  // t = 5.1 (step 17; t = 4.8 gives 0.096) and spring 0 at t = 10.2 (step 34; 9.9 gives 0.099)
  MassSpringSystem<1> s = DrivenChain({0.0, 0.01, 0.03, 0.03});
  s.inelastic.fracture_strain = 0.1;
  const double dt = 0.3;
  for (int k = 1; k <= 16; ++k) symplectic_euler_step(s, dt);
  EXPECT_FALSE(s.springs[1].broken) << "broke early, strain " << s.fractures.at(0).strain;
  symplectic_euler_step(s, dt);
  ASSERT_TRUE(s.springs[1].broken) << "did not break at strain 0.102";
  ASSERT_EQ(s.fractures.size(), 1u);
  EXPECT_EQ(s.fractures[0].step, 17);
  EXPECT_NEAR(s.fractures[0].strain, 0.102, 1e-12);
  for (int k = 18; k <= 33; ++k) symplectic_euler_step(s, dt);
  EXPECT_FALSE(s.springs[0].broken);
  symplectic_euler_step(s, dt);
  ASSERT_EQ(s.fractures.size(), 2u);
  EXPECT_EQ(s.fractures[1].spring, 0);
  EXPECT_EQ(s.fractures[1].step, 34);
  EXPECT_FALSE(s.springs[2].broken);
  // a broken spring no longer pulls
  Eigen::Matrix<double, 1, Eigen::Dynamic> f = Eigen::Matrix<double, 1, Eigen::Dynamic>::Zero(1, 4);
  accumulate_forces(s, f);
  EXPECT_EQ(f(0, 1), 0.0);
}

// A rod of four springs held at 1.5 times its length, then released and left to settle.
double RestLengthAfterHoldingAndReleasing(double stretch, int hold_steps) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(4), Material{10.0, 1.0, 1.0});
  rod.inelastic.yield_strain = 0.1;
  rod.inelastic.plastic_fraction = 0.5;
  rod.x *= stretch;  // uniform strain: interior nodes are in equilibrium
  rod.pinned[0] = rod.pinned[4] = 1;
  for (int k = 0; k < hold_steps; ++k) backward_euler_step(rod, 0.01);
  rod.pinned[4] = 0;  // unload
  for (int k = 0; k < 2000; ++k) backward_euler_step(rod, 0.01);
  EXPECT_LT(rod.v.cwiseAbs().maxCoeff(), 1e-9) << "rod has not come to rest";
  return rod.x(0, 4) - rod.x(0, 0);
}

TEST(InelasticTest, RestLengthMovesTheGivenFractionTowardTheCurrentLength) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(4), Material{10.0, 1.0, 1.0});
  rod.inelastic.yield_strain = 0.1;
  rod.inelastic.plastic_fraction = 0.5;
  rod.x *= 1.5;
  rod.pinned[0] = rod.pinned[4] = 1;
  const double expected[] = {0.3125, 0.34375, 0.34375};  // 0.25 -> half way to 0.375, twice
  for (double rest : expected) {
    backward_euler_step(rod, 0.01);
    for (const Spring& sp : rod.springs) EXPECT_NEAR(sp.params.rest_length, rest, 1e-12);
  }
}

TEST(InelasticTest, PlasticityLeavesTheDocumentedPermanentSet) {
  // documented in InelasticParams: L = 1 -> 1.25 -> 1.375, then strain 1.5 / 1.375 - 1 =
  // 0.0909 is below the yield 0.1 and the rest length stays; unloaded length 1.375
  const double held = RestLengthAfterHoldingAndReleasing(1.5, 50);
  EXPECT_NEAR(held, 1.375, 1e-6) << "permanent set " << held - 1.0 << ", expected 0.375";
  // below the yield strain the rod is elastic and springs back to its length
  const double elastic = RestLengthAfterHoldingAndReleasing(1.08, 50);
  EXPECT_NEAR(elastic, 1.0, 1e-6) << "elastic loading left a set of " << elastic - 1.0;
}

}  // namespace
}  // namespace gencoord::deformable
