// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler through contacts that begin inside a step: a cube dropped on the ground, a
// cube dropped on a sphere, a soft cube of continuum elements thrown onto the ground (none
// inverted at the end) and a sheet that folds onto itself on the ground, at 10 times the CFL
// step, never end a step with more energy than they started with (the ground at height 0, so
// that the energy is the drop's), and do not pass through what they hit; without the Newton
// iterations the cube on the ground gains energy.
#include <gtest/gtest.h>

#include <cstdio>

#include "figures.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "long_run_checks.hpp"

namespace gencoord::deformable {
namespace {

using validation::Drop;
using validation::DropOutcome;
using validation::implicit_drop;

// the drops of long_run_checks.hpp at 10 times the CFL step; deformable_long_tests repeats
// them at 1 and 5 times it, which take ten and two times the steps through the same code
TEST(ImplicitContact, DropsNeverGainEnergyAtTenTimesTheCflStep) {
  ExpectDropsNeverGainEnergy(10.0);
}

// Without the Newton iterations (the linearized step only) the cube on the ground gains energy
// at 10 x CFL: the contacts that begin inside a step are what the iterations are for
TEST(ImplicitContactWithoutNewton, GainsEnergyWhereContactsBeginInsideAStep) {
  ImplicitOptions linearized;
  linearized.max_contact_iterations = 0;
  const DropOutcome got = implicit_drop(Drop::kCubeOnGround, 10.0, linearized);
  std::printf(
      "[ implicit contact ] linearized only, cube on the ground at 10 x CFL: highest (E - "
      "E0) / E0 %+.2e\n",
      got.highest);
  EXPECT_GT(got.highest, 0.1);
  EXPECT_EQ(got.newton, 0);
}

}  // namespace
}  // namespace gencoord::deformable
