// SPDX-License-Identifier: BSD-3-Clause
// Procedural meshes and the mesh-to-springs rule k = c^2 m / L.
#include "gencoord/deformable/mesh.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

#include "gencoord/deformable/mesh_to_springs.hpp"
#include "test_helpers.hpp"

namespace gencoord::deformable {
namespace {

using testing::kPi;

TEST(MeshTest, RectangleHasTheExpectedNodesEdgesAndMass) {
  const int nx = 7, ny = 4;
  for (auto pattern : {DiagonalPattern::kUniform, DiagonalPattern::kAlternating}) {
    const SimplexMesh<2> mesh = rectangle_mesh(2.0, 0.5, nx, ny, pattern);
    EXPECT_EQ(mesh.nodes.cols(), (nx + 1) * (ny + 1));
    EXPECT_EQ(mesh.elements.size(), 2u * nx * ny);
    // horizontal + vertical + one diagonal per cell
    EXPECT_EQ(mesh_edges(mesh).size(),
              static_cast<size_t>(nx * (ny + 1) + ny * (nx + 1) + nx * ny));
    const MassSpringSystem<2> s = make_mass_spring(mesh, Material{4.0, 3.0, 0.0});
    EXPECT_NEAR(s.mass.sum(), 3.0 * 2.0 * 0.5, 1e-12);
  }
}

TEST(MeshTest, DiskMassIsDensityTimesInscribedPolygonArea) {
  const int rings = 5;
  const double radius = 0.4;
  const SimplexMesh<2> mesh = disk_mesh(radius, rings, Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(mesh.nodes.cols(), 1 + 3 * rings * (rings + 1));
  // the outer ring is a regular polygon with 6 rings sides: area (N / 2) R^2 sin(2 pi / N)
  const int sides = 6 * rings;
  const double polygon = 0.5 * sides * radius * radius * std::sin(2.0 * kPi / sides);
  double area = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const double a = element_measure(mesh, e);
    EXPECT_GT(a, 0.0) << "degenerate triangle " << e;
    area += a;
  }
  EXPECT_NEAR(area, polygon, 1e-12);
  // Euler's formula for a triangulated disk: V - E + F = 1
  const long v = mesh.nodes.cols(), f = static_cast<long>(mesh.elements.size());
  const long edges = static_cast<long>(mesh_edges(mesh).size());
  EXPECT_EQ(v - edges + f, 1);
}

TEST(MeshTest, BoxHasTheExpectedVolumeAndKuhnEdges) {
  const int nx = 3, ny = 2, nz = 4;
  const SimplexMesh<3> mesh = box_mesh(0.3, 0.2, 0.4, nx, ny, nz);
  EXPECT_EQ(mesh.elements.size(), 6u * nx * ny * nz);
  double volume = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e)
    volume += element_measure(mesh, e);
  EXPECT_NEAR(volume, 0.3 * 0.2 * 0.4, 1e-14);
  // axis edges + one diagonal per face of the grid + one body diagonal per cube
  const long axis = nx * (ny + 1) * (nz + 1) + ny * (nx + 1) * (nz + 1) + nz * (nx + 1) * (ny + 1);
  const long faces = nx * ny * (nz + 1) + ny * nz * (nx + 1) + nx * nz * (ny + 1);
  EXPECT_EQ(static_cast<long>(mesh_edges(mesh).size()), axis + faces + nx * ny * nz);
}

// Every spring's own wave speed sqrt(k L / m), with m the mass around it, is c times the
// square root of its calibration factor, which depends on its direction only
// (lattice_elasticity.hpp); the fastest spring sets the object's wave speed (the CFL limit).
TEST(MeshTest, SpringSpeedsDependOnDirectionOnly) {
  const Material material{9.0, 4.0, 0.0};  // c = 1.5
  const SimplexMesh<3> mesh = box_mesh(0.3, 0.2, 0.4, 3, 2, 4);
  const MassSpringSystem<3> s = make_mass_spring(mesh, material);
  // mass around each edge, recomputed here: volume / 6 from each tetrahedron containing it
  std::map<std::pair<int, int>, double> around;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const auto& el = mesh.elements[e];
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        around[{std::min(el[a], el[b]), std::max(el[a], el[b])}] +=
            4.0 * element_measure(mesh, e) / 6.0;
      }
    }
  }
  ASSERT_EQ(around.size(), s.springs.size());
  std::map<std::array<long, 3>, double> speed_of_direction;  // n and -n together
  double fastest = 0.0;
  for (const Spring& sp : s.springs) {
    const double speed =
        std::sqrt(sp.params.stiffness * sp.params.rest_length / around.at({sp.i, sp.j}));
    Eigen::Vector3d n = (mesh.nodes.col(sp.j) - mesh.nodes.col(sp.i)).normalized();
    const bool negative =
        n.x() < -1e-9 || (n.x() < 1e-9 && (n.y() < -1e-9 || (n.y() < 1e-9 && n.z() < 0)));
    if (negative) n = -n;
    const std::array<long, 3> key{std::lround(1e6 * n.x()), std::lround(1e6 * n.y()),
                                  std::lround(1e6 * n.z())};
    const auto [at, added] = speed_of_direction.emplace(key, speed);
    if (!added) {
      EXPECT_NEAR(speed, at->second, 1e-12 * speed);
    }
    fastest = std::max(fastest, speed);
  }
  EXPECT_EQ(speed_of_direction.size(), 13u);  // the cubic lattice's 13 directions
  EXPECT_NEAR(s.wave_speed, fastest, 1e-12 * fastest);
  EXPECT_GT(fastest, 1.5);  // faster than c: a network is softer than each of its springs
  EXPECT_NEAR(s.mass.sum(), 4.0 * 0.3 * 0.2 * 0.4, 1e-12);
}

}  // namespace
}  // namespace gencoord::deformable
