// SPDX-License-Identifier: BSD-3-Clause
// ExplicitStepper (explicit_stepper.hpp): the same steps as symplectic_euler_step() and the
// runtime's symplectic Euler on the object, bit for bit, through fracture; and what changes
// between steps is still checked.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/explicit_stepper.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/integrate/explicit_rk.hpp"

namespace gencoord::deformable {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// a damped strip pinned at its left end, sagging under gravity onto the ground, brittle
MassSpringSystem<2> brittle_strip() {
  MassSpringSystem<2> s =
      make_mass_spring(rectangle_mesh(1.0, 0.1, 20, 2), Material{2e3, 1.0, 0.5});
  pin_nodes_where(s, 0, 0.0);
  s.gravity << 0.0, -30.0;
  with_ground(s, -0.15, 0.3);
  s.inelastic.fracture_strain = 0.01;
  return s;
}

TEST(ExplicitStepper, TakesTheRuntimesStepsBitForBitThroughFracture) {
  MassSpringSystem<2> kept = brittle_strip(), plain = kept, runtime = kept;
  ExplicitStepper<2> stepper;
  const double dt = 0.5 * cfl_limit(kept);
  for (int k = 0; k < 2000; ++k) {
    stepper.step(kept, dt);
    symplectic_euler_step(plain, dt);
    const MassSpringIntegration<2> system(runtime);
    finish_step<2>(gencoord::symplectic_euler_step(system, system.state(), dt), dt, &runtime);
    ASSERT_EQ((kept.x - plain.x).cwiseAbs().maxCoeff(), 0.0) << "step " << k;
    ASSERT_EQ((kept.v - runtime.v).cwiseAbs().maxCoeff(), 0.0) << "step " << k;
    ASSERT_EQ((kept.x - runtime.x).cwiseAbs().maxCoeff(), 0.0) << "step " << k;
  }
  EXPECT_GT(kept.fractures.size(), 0u) << "the strip should have broken";
  EXPECT_EQ(kept.fractures.size(), runtime.fractures.size());
  // stable_step_limit() as computed after the last fracture: at least the CFL limit
  EXPECT_GE(stepper.cfl_limit(), cfl_limit(kept));
}

TEST(ExplicitStepper, ChecksWhatChangesBetweenSteps) {
  MassSpringSystem<2> s = brittle_strip();
  s.inelastic.fracture_strain = std::numeric_limits<double>::infinity();
  ExplicitStepper<2> stepper;
  const double dt = 0.5 * cfl_limit(s);
  stepper.step(s, dt);
  EXPECT_THROW(stepper.step(s, 1.01 * stepper.cfl_limit()), CflViolation);
  MassSpringSystem<2> bad = s;
  bad.wave_speed = std::nan("");
  EXPECT_THAT([&] { stepper.step(bad, dt); }, ThrowsMessage<ObjectError>(HasSubstr("wave speed")));
  bad = s;
  bad.gravity(1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(stepper.step(bad, dt), ObjectError);
  // a value changed in place is caught by the step's result, and named by the validation
  stepper.step(s, dt);
  const MassSpringSystem<2> before = s;
  s.springs[7].params.stiffness = std::nan("");
  EXPECT_THAT([&] { stepper.step(s, dt); }, ThrowsMessage<ObjectError>(HasSubstr("spring 7")));
  EXPECT_EQ((s.x - before.x).cwiseAbs().maxCoeff(), 0.0) << "a refused step changed the object";
  EXPECT_EQ(s.steps, before.steps);
  // after invalidate() a change in place is validated before the step
  s.springs[7].params.stiffness = -1.0;
  stepper.invalidate();
  EXPECT_THAT([&] { stepper.step(s, dt); }, ThrowsMessage<ObjectError>(HasSubstr("spring 7")));
  EXPECT_EQ(s.steps, before.steps);
}

}  // namespace
}  // namespace gencoord::deformable
