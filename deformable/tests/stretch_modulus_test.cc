// SPDX-License-Identifier: BSD-3-Clause
// The relaxed static stretch (stretch_modulus.hpp): the affine calibration overestimates thin
// strips and bars, the measured modulus approaches it as they get wider, and after
// calibrate_to_stretch() a strip pulled by a force stretches by sigma / E in a simulation.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/stretch_modulus.hpp"

namespace gencoord::deformable {
namespace {

// A strip 1 m long of `across` cells of 0.05 m: the affine estimate is E, the relaxed
// stretch is softer by a boundary layer that matters less as the strip widens.
TEST(StretchModulus, ThinStripsAreSofterThanTheAffineEstimateAndConvergeToIt) {
  const double E = 2.25;
  double previous = 0.0;
  for (const int across : {2, 4, 8, 16}) {
    const double width = 0.05 * across;
    const SimplexMesh<2> mesh = rectangle_mesh(1.0, width, 20, across);
    const MassSpringSystem<2> s = make_mass_spring(mesh, Material{E, 1.0, 0.0});
    const double measured = stretch_modulus(s, mesh.nodes, 1.0 * width, 0) / E;
    std::printf("[ stretch ] strip %d cells across: E_stretch / E = %.4f\n", across, measured);
    EXPECT_LT(measured, 1.0);
    EXPECT_GT(measured, previous);
    previous = measured;
  }
  EXPECT_GT(previous, 0.98);
}

// After calibrate_to_stretch, a strip pinned at its left end and pulled at its right end by
// a stress sigma settles (backward Euler with damping) to the strain sigma / E in its middle,
// with the network's Poisson's ratio and with area terms that raise it to 0.6.
class CalibratedStrip : public ::testing::TestWithParam<double> {};

TEST_P(CalibratedStrip, StretchesBySigmaOverE) {
  const double E = 1000.0, width = 0.1, sigma = 1.0;  // N/m and N/m: strain 1e-3
  const SimplexMesh<2> mesh = rectangle_mesh(2.0, width, 40, 2);
  Material material{E, 1.0, 50.0};
  material.poisson_ratio = GetParam();
  MassSpringSystem<2> s = make_mass_spring(mesh, material);
  const double factor = calibrate_to_stretch(s, mesh, E, 0);
  pin_nodes_where(s, 0, 0.0);
  std::vector<int> right;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (mesh.nodes(0, n) > 2.0 - 1e-9) right.push_back(n);
  }
  // the end force, shared by the end nodes as a uniform traction would be (ends get half)
  Eigen::Matrix2Xd pull = Eigen::Matrix2Xd::Zero(2, s.num_nodes());
  for (int n : right) {
    const bool corner = mesh.nodes(1, n) < 1e-9 || mesh.nodes(1, n) > width - 1e-9;
    pull(0, n) = sigma * width / static_cast<double>(right.size() - 1) * (corner ? 0.5 : 1.0);
  }
  // a constant force per node enters as gravity would: a per-node acceleration
  BackwardEulerStepper<2> stepper;
  const double dt = 0.01;
  for (int k = 0; k < 3000; ++k) {
    for (int n : right) s.v.col(n) += dt * pull.col(n) / s.mass(n);
    stepper.step(s, dt);
  }
  // the strain between x = 0.5 and 1.5, from the mean x-displacement of those columns
  auto mean_ux = [&](double x) {
    double sum = 0.0;
    int count = 0;
    for (int n = 0; n < s.num_nodes(); ++n) {
      if (std::abs(mesh.nodes(0, n) - x) < 1e-9) {
        sum += s.x(0, n) - mesh.nodes(0, n);
        ++count;
      }
    }
    return sum / count;
  };
  const double strain = (mean_ux(1.5) - mean_ux(0.5)) / 1.0;
  std::printf("[ stretch ] calibrated strip, nu %.2f (factor %.4f): strain %.6e, sigma / E %.6e\n",
              GetParam(), factor, strain, sigma / E);
  EXPECT_GT(factor, 1.0);
  EXPECT_NEAR(strain, sigma / E, 0.01 * sigma / E);
}

INSTANTIATE_TEST_SUITE_P(NetworkAndAreaTerms, CalibratedStrip,
                         ::testing::Values(std::numeric_limits<double>::quiet_NaN(), 0.6));

TEST(StretchModulus, RefusesABodyThatCarriesNoStretch) {
  const SimplexMesh<2> mesh = rectangle_mesh(1.0, 0.1, 10, 1);
  MassSpringSystem<2> s = make_mass_spring(mesh, Material{});
  for (Spring& sp : s.springs) sp.broken = true;
  EXPECT_THROW(stretch_modulus(s, mesh.nodes, 0.1, 0), ObjectError);
  EXPECT_THROW(calibrate_to_stretch(s, mesh, -1.0, 0), MaterialError);
}

}  // namespace
}  // namespace gencoord::deformable
