// SPDX-License-Identifier: BSD-3-Clause
// A program outside the repository on the installed gencoord::deformable: a stretched free rod
// oscillates under symplectic Euler and backward Euler steps, and the steps refuse what they
// should (a step above the CFL limit, a negative step with the runtime's StepSizeError).
// Prints "all checks passed" and exits 0, or names the failed check and exits 1.
#include <cmath>
#include <cstdio>

#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/errors.hpp"

namespace gd = gencoord::deformable;

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
  if (!ok) ++failures;
}

}  // namespace

int main() {
  gd::Material material;
  material.youngs_modulus = 100.0;
  material.density = 1.0;
  gd::MassSpringSystem<1> rod = gd::make_rod(gd::uniform_rod_nodes(20), material);
  rod.x *= 1.01;  // stretched by 1 %, at rest
  const double energy = gd::total_energy(rod);
  const double dt = 0.5 * gd::cfl_limit(rod);

  for (int i = 0; i < 1000; ++i) gd::symplectic_euler_step(rod, dt);
  const double drift = std::abs(gd::total_energy(rod) - energy) / energy;
  std::printf("symplectic Euler: 1000 steps of %.3g s, relative energy change %.2e\n", dt, drift);
  check(energy > 0.0 && drift < 0.05, "symplectic Euler keeps the energy within 5 %");

  bool refused = false;
  try {
    gd::symplectic_euler_step(rod, 4.0 * dt);
  } catch (const gd::CflViolation&) {
    refused = true;
  }
  check(refused, "a step above the CFL limit is refused with CflViolation");

  refused = false;
  try {
    gd::symplectic_euler_step(rod, -dt);
  } catch (const gencoord::StepSizeError&) {
    refused = true;
  }
  check(refused, "a negative step is refused with gencoord::StepSizeError");

  const double before = gd::total_energy(rod);
  for (int i = 0; i < 100; ++i) gd::backward_euler_step(rod, 10.0 * dt);
  const double after = gd::total_energy(rod);
  check(std::isfinite(after) && after <= before, "backward Euler steps lose energy");

  if (failures > 0) {
    std::printf("%d checks failed\n", failures);
    return 1;
  }
  std::printf("all checks passed\n");
  return 0;
}
