// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler's linear solves: the conjugate-gradient stopping rule near rest, and the
// step matrix's pattern and factorization kept between steps (BackwardEulerStepper).
#include "gencoord/deformable/implicit_stepper.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/integrate/backward_euler.hpp"

namespace gencoord::deformable {
namespace {

// Three nodes, two springs: rho = 2, E = 400, damped, pinned at node 0.
MassSpringSystem<1> ShortRod() {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(2), Material{400.0, 2.0, 0.5});
  rod.pinned[0] = 1;
  return rod;
}

// A 1 x 0.25 sheet pinned on its left edge under gravity; springs in it break at 0.5 % strain
// (set fracture_strain to keep them).
MassSpringSystem<2> HangingSheet() {
  MassSpringSystem<2> s =
      make_mass_spring(rectangle_mesh(1.0, 0.25, 8, 2), Material{2e3, 1.0, 1.0});
  pin_nodes_where(s, 0, 0.0);
  s.gravity << 0.0, -9.81;
  return s;
}

// The 3-node rod at dt = 100 s: at rest the right-hand side is rounding noise (under gravity)
// or shrinks by about 1e-6 per step until it is subnormal (without), where a CG test relative
// to it alone fails. Both settle: to the hanging stretch rho g l^2 / (2 E), to the rest length.
TEST(ImplicitStepperTest, ConjugateGradientsSettleAtHugeStepsWithoutThrowing) {
  MassSpringSystem<1> hanging = ShortRod();
  hanging.gravity(0) = 9.81;
  MassSpringSystem<1> released = ShortRod();
  released.x(0, 2) += 0.1;
  MassSpringSystem<1> released_fresh = released;
  BackwardEulerStepper<1> hanging_stepper, released_stepper;
  for (int k = 0; k < 200; ++k) {
    ASSERT_NO_THROW(hanging_stepper.step(hanging, 100.0)) << "step " << k;
    ASSERT_NO_THROW(released_stepper.step(released, 100.0)) << "step " << k;
    ASSERT_NO_THROW(backward_euler_step(released_fresh, 100.0)) << "step " << k;
  }
  EXPECT_NEAR(hanging.x(0, 2) - 1.0, 2.0 * 9.81 / (2.0 * 400.0), 1e-12);
  EXPECT_NEAR(released.x(0, 2), 1.0, 1e-12);
  EXPECT_NEAR(released_fresh.x(0, 2), 1.0, 1e-12);
  EXPECT_LT(released.v.cwiseAbs().maxCoeff(), 1e-100);
}

TEST(ImplicitStepperTest, ZeroRightHandSideTakesNoIteration) {
  MassSpringSystem<2> s = HangingSheet();
  s.gravity.setZero();  // at rest at its rest shape: f = 0 and v = 0, so b = 0 exactly
  const auto x0 = s.x;
  BackwardEulerStepper<2> stepper;
  for (int k = 0; k < 3; ++k) {
    const ImplicitStats stats = stepper.step(s, 0.1);
    EXPECT_EQ(stats.iterations, 0);
    EXPECT_EQ(stats.residual, 0.0);
    EXPECT_GT(stats.unknowns, 0);
  }
  EXPECT_EQ(s.x, x0);
  EXPECT_TRUE(s.v.isZero(0.0));
}

// The kept symbolic analysis, refactorized each step, gives the fresh factorization's result
// step after step, also across the steps where springs break and the pattern changes; and
// the pattern is analysed again exactly once after each step that broke springs.
TEST(ImplicitStepperTest, KeptFactorizationMatchesAFreshOneAcrossFracture) {
  MassSpringSystem<2> kept = HangingSheet();
  kept.inelastic.fracture_strain = 0.005;
  MassSpringSystem<2> fresh = kept;
  ImplicitOptions cholesky;
  cholesky.solver = LinearSolver::kSparseCholesky;
  BackwardEulerStepper<2> stepper(cholesky);
  long steps_with_fracture = 0;
  ImplicitStats stats;
  for (int k = 0; k < 100; ++k) {
    const std::size_t broken_before = kept.fractures.size();
    stats = stepper.step(kept, 0.01);
    backward_euler_step(fresh, 0.01, cholesky);
    if (kept.fractures.size() > broken_before && k + 1 < 100) ++steps_with_fracture;
    ASSERT_EQ(kept.fractures.size(), fresh.fractures.size()) << "step " << k;
    const double scale = 1.0 + fresh.x.cwiseAbs().maxCoeff();
    ASSERT_LE((kept.x - fresh.x).cwiseAbs().maxCoeff(), 1e-13 * scale) << "step " << k;
    ASSERT_LE((kept.v - fresh.v).cwiseAbs().maxCoeff(), 1e-11 * (1.0 + fresh.v.norm()))
        << "step " << k;
  }
  ASSERT_GT(steps_with_fracture, 1) << "no spring broke: the pattern never changed";
  EXPECT_GT(kept.fractures.size(), 0u);
  // the one analysis before the first step, and one after each step that broke springs but
  // the last (the step after it rebuilds)
  EXPECT_EQ(stats.pattern_analyses, 1 + steps_with_fracture);
}

// Without fracture the pattern is analysed once, also while ground contacts start and end
// (their diagonal entries are always in the pattern).
TEST(ImplicitStepperTest, PatternIsAnalysedOnceWithoutFracture) {
  for (LinearSolver solver : {LinearSolver::kConjugateGradient, LinearSolver::kSparseCholesky}) {
    MassSpringSystem<2> s =
        make_mass_spring(rectangle_mesh(0.5, 0.1, 6, 2), Material{2e3, 1.0, 1.0});
    s.x.row(1).array() += 0.02;
    s.v.row(1).setConstant(-1.0);
    s.gravity << 0.0, -9.81;
    with_ground(s, 0.0, 0.5);
    ImplicitOptions options;
    options.solver = solver;
    BackwardEulerStepper<2> stepper(options);
    ImplicitStats stats;
    double lowest = 1.0, rising = -1.0;
    for (int k = 0; k < 100; ++k) {
      stats = stepper.step(s, 2e-3);
      lowest = std::min(lowest, s.x.row(1).minCoeff());
      rising = std::max(rising, s.v.row(1).maxCoeff());
    }
    EXPECT_LT(lowest, 0.0) << "the sheet never touched the ground";
    EXPECT_GT(rising, 0.0) << "the sheet never bounced";
    EXPECT_EQ(stats.pattern_analyses, 1);
  }
}

// The stepper's linearized step (no Newton iterations for contacts that begin inside a step)
// is the runtime's linearized backward Euler on MassSpringIntegration (K v, the moving pinned
// nodes, the ground penalty), to rounding.
TEST(ImplicitStepperTest, StepperMatchesTheRuntimesLinearizedBackwardEuler) {
  MassSpringSystem<2> s = make_mass_spring(rectangle_mesh(0.5, 0.1, 5, 2), Material{2e3, 1.0, 1.0});
  pin_nodes_where(s, 0, 0.0);
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.pinned[n]) s.v.col(n) << 0.3, -0.2;
  }
  s.x.row(1).array() -= 0.01;  // the bottom row starts in ground contact
  s.v(0, 3) = 0.4;
  s.gravity << 0.0, -9.81;
  with_ground(s, 0.0, 0.3);
  ImplicitOptions cholesky;
  cholesky.solver = LinearSolver::kSparseCholesky;
  cholesky.max_contact_iterations = 0;
  const double dt = 5e-3;
  MassSpringSystem<2> runtime = s;
  BackwardEulerStepper<2> stepper(cholesky);
  for (int k = 0; k < 20; ++k) {
    const MassSpringIntegration<2> system(runtime, cholesky);
    NewtonOptions linearized;
    linearized.linearized = true;
    finish_step<2>(gencoord::backward_euler_step(system, system.state(), dt, linearized), dt,
                   &runtime);
    stepper.step(s, dt);
    ASSERT_LE((s.v - runtime.v).cwiseAbs().maxCoeff(), 1e-11) << "step " << k;
    ASSERT_LE((s.x - runtime.x).cwiseAbs().maxCoeff(), 1e-13) << "step " << k;
  }
}

}  // namespace
}  // namespace gencoord::deformable
