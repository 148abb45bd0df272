// SPDX-License-Identifier: BSD-3-Clause
// Speed of sound: a pulse travels at c = sqrt(E / rho) along a rod, a strip (2D) and a bar
// (3D), on uniform and irregular meshes at several resolutions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "figures.hpp"
#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/stretch_modulus.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "mesh_files.hpp"
#include "test_helpers.hpp"

namespace gencoord::deformable {
namespace {

using testing::GaussianPulse;
using testing::peak_time;

// Axial displacement at rest position `probe` of a rod, by linear interpolation between nodes.
double RodDisplacementAt(const MassSpringSystem<1>& rod, const std::vector<double>& p,
                         double probe) {
  size_t i = 0;
  while (i + 2 < p.size() && p[i + 1] < probe) ++i;
  const double t = (probe - p[i]) / (p[i + 1] - p[i]);
  return (1 - t) * (rod.x(0, i) - p[i]) + t * (rod.x(0, i + 1) - p[i + 1]);
}

// Speed from the arrival times of the pulse peak at two probes.
double MeasureRodSpeed(const std::vector<double>& p, const Material& material) {
  MassSpringSystem<1> rod = make_rod(p, material);
  const GaussianPulse pulse{1e-3, 0.25, 0.05, material.wave_speed()};
  for (int i = 0; i < rod.num_nodes(); ++i) {
    rod.x(0, i) += pulse.displacement(p[i]);
    rod.v(0, i) = pulse.velocity(p[i]);
  }
  const double probe_a = 0.45, probe_b = 0.75;
  const double dt = 0.5 * cfl_limit(rod);
  const int steps = static_cast<int>(0.7 / material.wave_speed() / dt);
  std::vector<double> at_a, at_b;
  for (int k = 0; k < steps; ++k) {
    symplectic_euler_step(rod, dt);
    at_a.push_back(RodDisplacementAt(rod, p, probe_a));
    at_b.push_back(RodDisplacementAt(rod, p, probe_b));
  }
  return (probe_b - probe_a) / (peak_time(at_b, dt) - peak_time(at_a, dt));
}

TEST(WaveSpeedTest, RodPulseTravelsAtSqrtEOverRho) {
  const Material material{4.0, 1.0, 0.0};  // c = 2 m/s
  const double c = material.wave_speed();
  const double uniform = MeasureRodSpeed(uniform_rod_nodes(300), material);
  const double jittered = MeasureRodSpeed(jittered_rod_nodes(300, 0.5, 3), material);
  EXPECT_NEAR(uniform, c, 0.02 * c)
      << "uniform mesh: measured " << uniform << " m/s, expected sqrt(E/rho) = " << c;
  EXPECT_NEAR(jittered, c, 0.02 * c)
      << "non-uniform mesh: measured " << jittered << " m/s, expected " << c;
  std::printf("[ rod wave speed ] sqrt(E/rho) = %.4f, uniform %.4f, non-uniform %.4f m/s\n", c,
              uniform, jittered);
}

// The mesh with every node moved by up to `fraction` of a cell `h` along each axis (seeded),
// ends included: an irregular mesh of the same body.
template <int Dim>
SimplexMesh<Dim> jittered(SimplexMesh<Dim> mesh, double h, double fraction, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-fraction * h, fraction * h);
  for (int n = 0; n < mesh.nodes.cols(); ++n)
    for (int axis = 0; axis < Dim; ++axis) mesh.nodes(axis, n) += offset(random);
  return mesh;
}

// Plane pulse along x in a long strip (2D) or bar (3D) of length 3 with free sides
// (validation::pulse_speed()); `width`: the pulse's (m).
template <int Dim>
double MeasureStripSpeed(const SimplexMesh<Dim>& mesh, double h, const Material& material,
                         bool stretched = false, double width = 0.15) {
  const validation::Model model = material.elasticity == Elasticity::kCorotated
                                      ? validation::Model::kLinear
                                      : validation::Model::kSprings;
  const double speed = validation::pulse_speed(mesh, h, material, model, width, stretched);
  EXPECT_FALSE(std::isnan(speed)) << "no node near a probe";
  return speed;
}

// A thin strip or bar carries longitudinal waves at sqrt(E / rho) of its material: with the
// calibrated springs (lattice_elasticity.hpp) the measured speed converges to it as the mesh
// is refined, on a structured mesh and on the same mesh with every node moved at random. The
// deficit about halves with h (2, 4 and 8 cells across the width): the free sides' layer of
// nodes, which the affine estimate does not see. `tolerance`: the deficit allowed at 8 cells.
template <int Dim>
void ExpectConvergesToTheMaterialsSpeed(double tolerance_structured, double tolerance_jittered) {
  const Material material{2.25, 1.0, 0.0};  // c = 1.5 m/s
  const double c = material.wave_speed();
  double deficit[2] = {1.0, 1.0};
  for (int level = 1; level <= 3; ++level) {
    const int cells = 30 << level;  // h = 0.05, 0.025, 0.0125
    const int across = 1 << level;  // the width 0.1 is 2, 4, 8 cells
    const double h = 3.0 / cells;
    SimplexMesh<Dim> grid;
    if constexpr (Dim == 2) {
      grid = rectangle_mesh(3.0, 0.1, cells, across);
    } else {
      grid = box_mesh(3.0, 0.1, 0.1, cells, across, across);
    }
    const double measured[2] = {MeasureStripSpeed<Dim>(grid, h, material),
                                MeasureStripSpeed<Dim>(jittered(grid, h, 0.2, 7), h, material)};
    for (int kind = 0; kind < 2; ++kind) {
      const double now = 1.0 - measured[kind] / c;
      EXPECT_LT(std::abs(now), deficit[kind]) << Dim << "D, h = " << h << ", kind " << kind;
      deficit[kind] = std::abs(now);
    }
    std::printf("[ %dD wave speed ] c = %.4f; h = %.4f: structured %.4f, jittered %.4f m/s\n", Dim,
                c, h, measured[0], measured[1]);
    // calibrated to the static stretch: within 5% at 2 and 4 cells across already
    if (level == 3) continue;  // (the finest is already within 5% without)
    const double stretched[2] = {
        MeasureStripSpeed<Dim>(grid, h, material, true),
        MeasureStripSpeed<Dim>(jittered(grid, h, 0.2, 7), h, material, true)};
    for (int kind = 0; kind < 2; ++kind)
      EXPECT_NEAR(stretched[kind], c, 0.05 * c) << Dim << "D, h = " << h << ", kind " << kind;
    std::printf(
        "[ %dD wave speed ] calibrated to the stretch: h = %.4f: structured %.4f, jittered "
        "%.4f m/s\n",
        Dim, h, stretched[0], stretched[1]);
  }
  EXPECT_LT(deficit[0], tolerance_structured);
  EXPECT_LT(deficit[1], tolerance_jittered);
}

TEST(WaveSpeedTest, SheetWaveSpeedConvergesToTheMaterials) {
  ExpectConvergesToTheMaterialsSpeed<2>(0.05, 0.05);
}

TEST(WaveSpeedTest, SolidWaveSpeedConvergesToTheMaterials) {
  ExpectConvergesToTheMaterialsSpeed<3>(0.05, 0.06);
}

// Continuum elements (Elasticity::kCorotated) carry the thin strip's and bar's wave at
// sqrt(E / rho) within 2% on unstructured Gmsh meshes at two resolutions, with no calibration,
// Poisson's ratio 0.3. The pulse is 0.3 m wide, three times the width of the body, so that
// neither the lumped masses' dispersion (second order in h / width) nor the bar's own
// (Love's lateral inertia, nu^2 times the square of the width over the pulse's) shows.
TEST(WaveSpeedTest, ContinuumElementsCarryTheMaterialsSpeedOnGmshMeshes) {
  const std::string meshes = test_meshes_dir();
  Material material{2.25, 1.0, 0.0};  // c = 1.5 m/s
  material.poisson_ratio = 0.3;
  material.elasticity = Elasticity::kCorotated;
  const double c = material.wave_speed();
  for (const auto& [file, h] : {std::pair{"strip_h025.msh", 0.025}, {"strip_h0125.msh", 0.0125}}) {
    const double measured =
        MeasureStripSpeed<2>(read_gmsh<2>(meshes + "/" + file), h, material, false, 0.3);
    EXPECT_NEAR(measured, c, 0.02 * c) << file;
    std::printf("[ 2D wave speed ] co-rotated elements, Gmsh %s: %.4f m/s (c = %.4f)\n", file,
                measured, c);
  }
  for (const auto& [file, h] : {std::pair{"bar_h050.msh", 0.05}, {"bar_h033.msh", 0.033}}) {
    const double measured =
        MeasureStripSpeed<3>(read_gmsh<3>(meshes + "/" + file), h, material, false, 0.3);
    EXPECT_NEAR(measured, c, 0.02 * c) << file;
    std::printf("[ 3D wave speed ] co-rotated elements, Gmsh %s: %.4f m/s (c = %.4f)\n", file,
                measured, c);
  }
}

}  // namespace
}  // namespace gencoord::deformable
