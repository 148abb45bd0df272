// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler through contacts that begin inside a step: a cube dropped on the ground, a
// cube dropped on a sphere, a soft cube of continuum elements thrown onto the ground (none
// inverted at the end) and a sheet that folds onto itself on the ground, at 1, 5 and 10
// times the CFL step, never end a step with more energy than they started with (the ground at
// height 0, so that the energy is the drop's), and do not pass through what they hit.
#include <gtest/gtest.h>

#include <cstdio>

#include "figures.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "test_helpers.hpp"

namespace gencoord::deformable {
namespace {

using validation::Drop;
using validation::DropOutcome;
using validation::implicit_drop;

class ImplicitContact : public ::testing::TestWithParam<double> {};

using testing::kSanitized;

TEST_P(ImplicitContact, DropsNeverGainEnergy) {
  const double multiple = GetParam();
  // the 1 x CFL drops take ten times the steps of the 10 x ones through the same code, two
  // minutes under the sanitizers: they check memory at 5 x and 10 x, the physics at all three
  // in the Release build
  if (kSanitized && multiple < 5.0) GTEST_SKIP() << "run in the Release build";
  for (const Drop drop : validation::kDrops) {
    const DropOutcome got = implicit_drop(drop, multiple);
    std::printf(
        "[ implicit contact ] %-22s at %4.1f x CFL: highest (E - E0) / E0 %+.2e, end E / E0 "
        "%.4f, deepest below the ground %.4f m (shortest edge %.4f m), %ld Newton iterations in "
        "%ld steps\n",
        got.name.c_str(), multiple, got.highest, got.e_end, got.deepest, got.shortest, got.newton,
        got.steps);
    EXPECT_LE(got.highest, 1e-6) << got.name;
    EXPECT_LT(got.e_end, 1.0) << got.name;
    EXPECT_LT(got.deepest, got.shortest) << got.name;
    EXPECT_EQ(got.inverted, 0) << got.name;
  }
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

INSTANTIATE_TEST_SUITE_P(AtMultiplesOfTheCflStep, ImplicitContact,
                         ::testing::Values(1.0, 5.0, 10.0));

}  // namespace
}  // namespace gencoord::deformable
