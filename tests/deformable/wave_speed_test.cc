// Speed of sound: a pulse travels at c = sqrt(E / rho) along a rod on uniform and non-uniform
// meshes; in 2D and 3D the k = c^2 m / L rule makes the measured speed mesh-independent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/time_step.hpp"
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

// Plane pulse along x in a long strip (2D) or bar (3D) of length 3 with free sides; the probe
// value is the mean x-displacement of the nodes at rest x = probe (grid columns).
template <int Dim>
double MeasureStripSpeed(const SimplexMesh<Dim>& mesh, const Material& material) {
  MassSpringSystem<Dim> s = make_mass_spring(mesh, material);
  const GaussianPulse pulse{1e-3, 0.6, 0.15, material.wave_speed()};
  const double probe_a = 1.2, probe_b = 2.0;
  std::vector<int> column_a, column_b;
  for (int n = 0; n < s.num_nodes(); ++n) {
    const double px = mesh.nodes(0, n);
    s.x(0, n) += pulse.displacement(px);
    s.v(0, n) = pulse.velocity(px);
    if (std::abs(px - probe_a) < 1e-9) column_a.push_back(n);
    if (std::abs(px - probe_b) < 1e-9) column_b.push_back(n);
  }
  EXPECT_FALSE(column_a.empty() || column_b.empty());
  auto mean_ux = [&](const std::vector<int>& column) {
    double sum = 0.0;
    for (int n : column) sum += s.x(0, n) - mesh.nodes(0, n);
    return sum / column.size();
  };
  const double dt = 0.5 * cfl_limit(s);
  // window before reflections from either end can reach probe b
  const int steps = static_cast<int>(2.2 / material.wave_speed() / dt);
  std::vector<double> at_a, at_b;
  for (int k = 0; k < steps; ++k) {
    symplectic_euler_step(s, dt);
    at_a.push_back(mean_ux(column_a));
    at_b.push_back(mean_ux(column_b));
  }
  return (probe_b - probe_a) / (peak_time(at_b, dt) - peak_time(at_a, dt));
}

TEST(WaveSpeedTest, SheetWaveSpeedIsMeshIndependent) {
  const Material material{1.0, 1.0, 0.0};
  const double coarse = MeasureStripSpeed<2>(rectangle_mesh(3.0, 0.1, 60, 2), material);
  const double fine = MeasureStripSpeed<2>(rectangle_mesh(3.0, 0.1, 120, 4), material);
  EXPECT_NEAR(fine, coarse, 0.05 * coarse)
      << "2D strip: h = 0.05 gives " << coarse << " m/s, h = 0.025 gives " << fine;
  std::printf("[ 2D wave speed ] c = %.4f; h = 0.05: %.4f, h = 0.025: %.4f m/s\n",
              material.wave_speed(), coarse, fine);
}

TEST(WaveSpeedTest, SolidWaveSpeedIsMeshIndependent) {
  const Material material{1.0, 1.0, 0.0};
  const double coarse = MeasureStripSpeed<3>(box_mesh(3.0, 0.1, 0.1, 60, 2, 2), material);
  const double fine = MeasureStripSpeed<3>(box_mesh(3.0, 0.1, 0.1, 120, 4, 4), material);
  EXPECT_NEAR(fine, coarse, 0.05 * coarse)
      << "3D bar: h = 0.05 gives " << coarse << " m/s, h = 0.025 gives " << fine;
  std::printf("[ 3D wave speed ] c = %.4f; h = 0.05: %.4f, h = 0.025: %.4f m/s\n",
              material.wave_speed(), coarse, fine);
}

}  // namespace
}  // namespace gencoord::deformable
