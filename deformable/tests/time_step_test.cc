// SPDX-License-Identifier: BSD-3-Clause
// CFL limit: explicit steps just below it are stable, above it the runtime refuses them (and,
// forced, they blow up); backward Euler is stable at ten times the limit.
#include "gencoord/deformable/time_step.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <random>
#include <string>

#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"

namespace gencoord::deformable {
namespace {

// Random small displacements and velocities: excites every mode, the stiffest included.
template <int Dim>
void Perturb(MassSpringSystem<Dim>& s, double scale, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.pinned[n]) continue;
    for (int a = 0; a < Dim; ++a) {
      s.x(a, n) += scale * u(rng);
      s.v(a, n) += scale * u(rng);
    }
  }
}

// Growth of the energy envelope: the largest energy over the last 1000 of `steps` explicit
// steps divided by the largest over the first 1000. Near the CFL limit the energy measured by
// symplectic Euler oscillates strongly even when stable, so the envelope is what must not grow.
template <int Dim>
double ExplicitEnergyGrowth(MassSpringSystem<Dim> s, double dt, int steps, bool force = false) {
  double early = 0.0, late = 0.0;
  ExplicitOptions options;
  options.allow_cfl_violation = force;
  for (int k = 0; k < steps; ++k) {
    symplectic_euler_step(s, dt, options);
    const double e = total_energy(s);
    if (!std::isfinite(e)) return std::numeric_limits<double>::infinity();
    if (k < 1000) early = std::max(early, e);
    if (k >= steps - 1000) late = std::max(late, e);
  }
  return late / early;
}

TEST(TimeStepTest, CflLimitIsShortestSpringOverWaveSpeed) {
  MassSpringSystem<1> rod = make_rod({0.0, 0.3, 0.35, 1.0}, Material{9.0, 4.0, 0.0});
  EXPECT_NEAR(cfl_limit(rod), 0.05 / 1.5, 1e-15);  // L_min = 0.05, c = sqrt(9 / 4)
  // damping shrinks it by sqrt(1 + zeta^2) - zeta, zeta = (D / E) c / L_min
  MassSpringSystem<1> damped = make_rod({0.0, 0.3, 0.35, 1.0}, Material{9.0, 4.0, 0.03});
  const double zeta = 0.03 / 9.0 * 1.5 / 0.05;
  EXPECT_NEAR(cfl_limit(damped), 0.05 / 1.5 * (std::sqrt(1 + zeta * zeta) - zeta), 1e-15);
}

TEST(TimeStepTest, ExplicitStepsJustBelowTheCflLimitAreStable) {
  MassSpringSystem<1> uniform = make_rod(uniform_rod_nodes(50), Material{1.0, 1.0, 0.0});
  Perturb(uniform, 1e-3, 1);
  const double growth_rod = ExplicitEnergyGrowth(uniform, 0.98 * cfl_limit(uniform), 20000);
  EXPECT_LT(growth_rod, 1.5) << "uniform rod at 0.98 x CFL: energy grew " << growth_rod << "x";

  MassSpringSystem<1> jittered = make_rod(jittered_rod_nodes(50, 0.6, 5), Material{1.0, 1.0, 0.0});
  Perturb(jittered, 1e-3, 2);
  const double growth_jit = ExplicitEnergyGrowth(jittered, 0.98 * cfl_limit(jittered), 20000);
  EXPECT_LT(growth_jit, 1.5) << "non-uniform rod at 0.98 x CFL: energy grew " << growth_jit << "x";

  MassSpringSystem<2> disk = make_mass_spring(disk_mesh(0.5, 6, {0, 0}), Material{1.0, 1.0, 0.0});
  Perturb(disk, 1e-3, 3);
  const double growth_disk = ExplicitEnergyGrowth(disk, 0.98 * cfl_limit(disk), 5000);
  EXPECT_LT(growth_disk, 1.5) << "disk at 0.98 x CFL: energy grew " << growth_disk << "x";

  MassSpringSystem<3> box =
      make_mass_spring(box_mesh(0.4, 0.3, 0.3, 4, 3, 3), Material{1.0, 1.0, 0.0});
  Perturb(box, 1e-3, 4);
  const double growth_box = ExplicitEnergyGrowth(box, 0.98 * cfl_limit(box), 5000);
  EXPECT_LT(growth_box, 1.5) << "box at 0.98 x CFL: energy grew " << growth_box << "x";
}

TEST(TimeStepTest, RuntimeRefusesStepsAboveTheCflLimit) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(50), Material{1.0, 1.0, 0.0});
  const double limit = cfl_limit(rod);  // 0.02 s
  try {
    symplectic_euler_step(rod, 1.01 * limit);
    FAIL() << "a step of 1.01 x the CFL limit was accepted";
  } catch (const CflViolation& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("CFL limit 0.02 s"), std::string::npos) << what;
  }
  EXPECT_EQ(rod.steps, 0);  // the refused step changed nothing
}

// The limit is sharp for a uniform rod: just above it (forced), the stiffest mode explodes.
TEST(TimeStepTest, ForcedStepsJustAboveTheCflLimitBlowUp) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(50), Material{1.0, 1.0, 0.0});
  Perturb(rod, 1e-3, 1);
  const double growth = ExplicitEnergyGrowth(rod, 1.05 * cfl_limit(rod), 3000, /*force=*/true);
  EXPECT_GT(growth, 1e6) << "at 1.05 x CFL the energy envelope only grew " << growth << "x";
}

TEST(TimeStepTest, BackwardEulerIsStableAtTenTimesTheCflLimit) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(50), Material{1.0, 1.0, 0.0});
  Perturb(rod, 1e-3, 1);
  MassSpringSystem<2> disk = make_mass_spring(disk_mesh(0.5, 6, {0, 0}), Material{1.0, 1.0, 0.0});
  Perturb(disk, 1e-3, 3);
  const double e_rod = total_energy(rod), e_disk = total_energy(disk);
  const double dt_rod = 10.0 * cfl_limit(rod), dt_disk = 10.0 * cfl_limit(disk);
  for (int k = 0; k < 500; ++k) {
    backward_euler_step(rod, dt_rod);
    ImplicitOptions cholesky;
    cholesky.solver = LinearSolver::kSparseCholesky;
    backward_euler_step(disk, dt_disk, k % 2 ? cholesky : ImplicitOptions{});
    ASSERT_LE(total_energy(rod), e_rod) << "rod energy grew at step " << k;
    ASSERT_LE(total_energy(disk), e_disk) << "disk energy grew at step " << k;
  }
  EXPECT_LT(total_energy(rod), 0.5 * e_rod);  // implicit damping of the stiff modes
}

// A rod whose left end is pinned and moves at constant velocity: backward Euler's one
// linearized solve is (M - h D - h^2 K) dv = h (f + h K v) over the free nodes, with K v summed
// over every node, the moving pinned one included. K and D here are central differences of
// the force (exact up to rounding: a 1D rod's spring forces are linear).
TEST(TimeStepTest, BackwardEulerCarriesTheMotionOfAPinnedNode) {
  using Points = MassSpringSystem<1>::Points;
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(4), Material{4.0, 1.0, 0.5});
  rod.x *= 1.05;
  rod.pinned[0] = 1;
  rod.v(0, 0) = 2.0;
  rod.v(0, 2) = -0.3;
  rod.v(0, 4) = 0.7;
  const int n = rod.num_nodes();
  const double h = 0.05;
  auto force = [&](const Points& x, const Points& v) {
    Points f = Points::Zero(1, n);
    accumulate_forces(rod, x, v, f);
    return Eigen::VectorXd(f.row(0).transpose());
  };
  Eigen::MatrixXd K(n, n), D(n, n);
  const double eps = 1e-6;
  for (int j = 0; j < n; ++j) {
    Points plus = rod.x, minus = rod.x;
    plus(0, j) += eps;
    minus(0, j) -= eps;
    K.col(j) = (force(plus, rod.v) - force(minus, rod.v)) / (2.0 * eps);
    plus = rod.v;
    minus = rod.v;
    plus(0, j) += eps;
    minus(0, j) -= eps;
    D.col(j) = (force(rod.x, plus) - force(rod.x, minus)) / (2.0 * eps);
  }
  const Eigen::VectorXd v0 = rod.v.row(0).transpose();
  const Eigen::VectorXd b = h * (force(rod.x, rod.v) + h * K * v0);  // K v over every node
  const int free = n - 1;                                            // nodes 1 .. n-1
  Eigen::MatrixXd A =
      -h * D.bottomRightCorner(free, free) - h * h * K.bottomRightCorner(free, free);
  A.diagonal() += rod.mass.tail(free);
  Eigen::VectorXd v1 = v0;
  v1.tail(free) += A.lu().solve(b.tail(free));
  const Eigen::VectorXd x1 = rod.x.row(0).transpose() + h * v1;

  ImplicitOptions cholesky;
  cholesky.solver = LinearSolver::kSparseCholesky;
  backward_euler_step(rod, h, cholesky);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(rod.v(0, i), v1[i], 1e-9) << "node " << i;
    EXPECT_NEAR(rod.x(0, i), x1[i], 1e-9) << "node " << i;
  }
}

}  // namespace
}  // namespace gencoord::deformable
