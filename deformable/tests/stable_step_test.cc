// SPDX-License-Identifier: BSD-3-Clause
// The stable explicit step from an estimate of the highest frequency (stable_step_limit(),
// time_step.hpp) against the true limit 2 / omega_max of a dense eigensolve: within 6% and
// below it for springs, volume terms, elements and hinges in 1D, 2D and 3D, where the
// springs' L_min / c is 0.4 to 0.8 of it; ExplicitStepper takes steps up to it, and steps
// far above the true limit diverge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "explicit_stability.hpp"
#include "figures.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/explicit_stepper.hpp"
#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/sheet.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "mesh_files.hpp"

namespace gencoord::deformable {
namespace {

using testing::dense_highest_frequency;

Material springs(double damping = 0.0) { return Material{1e5, 1000.0, damping}; }

Material with(Elasticity elasticity, double nu) {
  Material m = springs();
  m.poisson_ratio = nu;
  m.elasticity = elasticity;
  return m;
}

// stable_step_limit() over the true limit 2 / omega_max (times the damping factor of the
// top mode when damped), printed
template <int Dim>
double over_true_limit(const MassSpringSystem<Dim>& s, const char* name) {
  const validation::StableStepRatios r = validation::stable_step_ratios(s);
  std::printf(
      "[ stable step ] %-28s estimate / true limit %.4f (L_min / c: %.4f), omega_max "
      "estimate / true %.4f\n",
      name, r.stable_step, r.cfl, r.frequency);
  return r.stable_step;
}

TEST(StableStep, EstimateIsBelowTheTrueLimitAndWithinSixPercent) {
  std::vector<double> ratios = {
      over_true_limit(make_rod(uniform_rod_nodes(50), springs()), "uniform rod"),
      over_true_limit(make_rod(jittered_rod_nodes(50, 0.5, 3), springs()), "jittered rod"),
      over_true_limit(make_mass_spring(rectangle_mesh(1.0, 0.2, 20, 4), springs()),
                      "2D strip, springs"),
      over_true_limit(make_mass_spring(read_gmsh<2>(kMeshes + "/strip_h025.msh"), springs()),
                      "Gmsh strip, springs"),
      over_true_limit(
          make_mass_spring(rectangle_mesh(1.0, 0.2, 20, 4), with(Elasticity::kSprings, 0.45)),
          "2D strip, volume terms"),
      over_true_limit(make_mass_spring(box_mesh(0.4, 0.1, 0.1, 8, 2, 2), springs()),
                      "3D bar, springs"),
      over_true_limit(make_mass_spring(read_gmsh<3>(kMeshes + "/block_v41.msh"), springs()),
                      "Gmsh block, springs"),
      over_true_limit(make_mass_spring(read_gmsh<3>(kMeshes + "/block_v41.msh"), springs(20.0)),
                      "Gmsh block, damped springs"),
      over_true_limit(make_mass_spring(read_gmsh<3>(kMeshes + "/block_v41.msh"),
                                       with(Elasticity::kCorotated, 0.3)),
                      "Gmsh block, elements"),
      over_true_limit(make_sheet(rectangle_sheet(1.0, 1.0, 8, 8), Material{100.0, 1.0}, 0.5),
                      "sheet with hinges")};
  for (const double ratio : ratios) {
    EXPECT_LE(ratio, 1.0 + 1e-9);
    EXPECT_GT(ratio, 0.94);  // 1 / 1.05, a little less where damping shrinks it
  }
}

// A block of springs set ringing in all its modes: the stepper takes steps of 0.98 of its
// limit (about 2.4 times L_min / c) and stays bounded over 3000 steps; above its limit it
// refuses; at 1.3 times the true limit the step diverges
TEST(StableStep, ExplicitStepperTakesStepsUpToTheTrueLimit) {
  const MassSpringSystem<3> start =
      testing::ringing(make_mass_spring(read_gmsh<3>(kMeshes + "/block_v41.msh"), springs()));
  MassSpringSystem<3> s = start;
  const double limit = stable_step_limit(s);
  EXPECT_GT(limit, 2.0 * cfl_limit(s));
  ExplicitStepper<3> stepper;
  EXPECT_THROW(stepper.step(s, 1.01 * limit), CflViolation);
  const testing::EnergySwing swing =
      testing::energy_swing(s, [&](MassSpringSystem<3>& o) { stepper.step(o, 0.98 * limit); });
  EXPECT_DOUBLE_EQ(stepper.cfl_limit(), limit);
  EXPECT_LT(swing.first, 3.0);
  EXPECT_LT(swing.last, 1.05 * swing.first);
  const double true_limit = 2.0 / dense_highest_frequency(start);
  EXPECT_TRUE(testing::diverges(start, 1.3 * true_limit));
  std::printf(
      "[ stable step ] springs block: limit %.3e s = %.3f of the true limit, %.2f times "
      "L_min / c; largest energy %.3f E0 in the first 1000 steps, %.3f in the last\n",
      limit, limit / true_limit, limit / cfl_limit(s), swing.first, swing.last);
}

// The ground's penalty lowers the limit (to 2 / sqrt(omega^2 + omega_g^2), a bound for a node
// pressed into it) but not below cfl_limit(); an object with nothing stiff has no limit
TEST(StableStep, GroundLowersTheLimitAndNothingStiffHasNone) {
  MassSpringSystem<3> s = make_mass_spring(read_gmsh<3>(kMeshes + "/block_v41.msh"), springs());
  const double free = stable_step_limit(s);
  with_ground(s, -1.0, 0.0);
  const double grounded = stable_step_limit(s);
  EXPECT_LT(grounded, free);
  EXPECT_GT(grounded, 0.8 * free);
  EXPECT_GE(grounded, cfl_limit(s));
  for (Spring& sp : s.springs) sp.broken = true;
  s.ground.reset();
  EXPECT_EQ(highest_frequency(s), 0.0);
  EXPECT_EQ(stable_step_limit(s), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace gencoord::deformable
