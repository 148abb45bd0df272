// SPDX-License-Identifier: BSD-3-Clause
// Ground contact: a disk falls freely, hits the penalty ground and bounces back up.
#include <gtest/gtest.h>

#include <cstdio>

#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {
namespace {

double CenterOfMassHeight(const MassSpringSystem<2>& s) {
  return (s.x.row(1) * s.mass)(0) / s.mass.sum();
}
double CenterOfMassVelocity(const MassSpringSystem<2>& s) {
  return (s.v.row(1) * s.mass)(0) / s.mass.sum();
}

// Stiff enough (c = 71 m/s against an impact at 2.4 m/s) not to crumple: with E = 400 the
// triangles invert on impact and the disk never recovers (no resistance to inversion).
TEST(GroundTest, DiskFallsAndBounces) {
  const double g = 9.81, radius = 0.2, start = 0.5;  // centre height (m)
  MassSpringSystem<2> disk =
      make_mass_spring(disk_mesh(radius, 4, {0.0, start}), Material{5000.0, 1.0, 0.0});
  disk.gravity << 0.0, -g;
  with_ground(disk, 0.0, 0.0);
  const double dt = 0.5 * cfl_limit(disk);
  // free fall until the lowest node touches: the centre follows start - g t^2 / 2
  const double contact_time = std::sqrt(2.0 * (start - radius) / g);
  while (disk.t + dt < 0.9 * contact_time) symplectic_euler_step(disk, dt);
  const double free_fall = start - 0.5 * g * disk.t * disk.t;
  EXPECT_NEAR(CenterOfMassHeight(disk), free_fall, 0.003)
      << "free fall: centre at " << CenterOfMassHeight(disk) << " m, expected " << free_fall;
  // contact, bounce, and the highest point of the rebound
  double deepest = 0.0, rebound = 0.0;
  bool bounced = false;
  while (disk.t < 3.0 * contact_time) {
    symplectic_euler_step(disk, dt);
    deepest = std::min(deepest, disk.x.row(1).minCoeff());
    if (CenterOfMassVelocity(disk) > 0.0) bounced = true;
    if (bounced) rebound = std::max(rebound, CenterOfMassHeight(disk));
  }
  EXPECT_TRUE(bounced) << "the disk never moved up";
  EXPECT_GT(rebound, radius + 0.5 * (start - radius))
      << "rebound to " << rebound << " m from a drop at " << start << " m";
  EXPECT_GT(deepest, -0.25 * radius) << "penetrated the ground by " << -deepest << " m";
  std::printf("[ ground ] drop from %.2f m: rebound to %.3f m, deepest node %.4f m\n", start,
              rebound, deepest);
}

}  // namespace
}  // namespace gencoord::deformable
