// SPDX-License-Identifier: BSD-3-Clause
// The runs of long_run_checks.hpp at the settings that take longest, through code the
// deformable suite runs at quicker settings (under the sanitizers too): the cube of quadratic
// elements in explicit steps and the linear tetrahedra that tile it in implicit ones, the
// implicit contact drops at the CFL step itself and at 5 times it (ten and two times the steps
// of the suite's 10 x drops), and the brittle bar four cells thick.
#include <gtest/gtest.h>

#include "long_run_checks.hpp"

namespace gencoord::deformable {
namespace {

TEST(QuadraticElement, CubeDroppedOnABlockStaysOnItInExplicitSteps) {
  ExpectCubeStaysOnTheBlock(false, true);
}

TEST(QuadraticElement, LinearTilesOfTheCubeStayOnTheBlock) {
  ExpectCubeStaysOnTheBlock(true, false);
}

TEST(ImplicitContact, DropsNeverGainEnergyAtOneAndFiveTimesTheCflStep) {
  for (const double multiple : {1.0, 5.0}) ExpectDropsNeverGainEnergy(multiple);
}

TEST(ContinuumMaterial, FractureSeparatesABarFourCellsThick) {
  ExpectBarSeparatesAtTheFractureStrain(4);
}

}  // namespace
}  // namespace gencoord::deformable
