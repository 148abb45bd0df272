// SPDX-License-Identifier: BSD-3-Clause
// The stiffness of a spring network (lattice_elasticity.hpp): the tensor against the energy of
// an affine strain, the plain k = c^2 m / L rule's modulus rho c^2 / 3 (2D) and / 6 (3D), and
// the calibrated networks: isotropic with the requested E, and Poisson's ratio 1/3 or 1/4.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "gencoord/deformable/lattice_elasticity.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "test_helpers.hpp"

namespace gencoord::deformable {
namespace {

using testing::kPi;

template <int Dim>
double measure_of(const SimplexMesh<Dim>& mesh) {
  double sum = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) sum += element_measure(mesh, e);
  return sum;
}

template <int Dim>
SimplexMesh<Dim> jittered(SimplexMesh<Dim> mesh, double h, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-0.2 * h, 0.2 * h);
  for (int n = 0; n < mesh.nodes.cols(); ++n)
    for (int axis = 0; axis < Dim; ++axis) mesh.nodes(axis, n) += offset(random);
  return mesh;
}

// Voigt engineering strain of the symmetric strain `eps`
template <int Dim>
Eigen::Matrix<double, LatticeElasticity<Dim>::kVoigt, 1> voigt_strain(
    const Eigen::Matrix<double, Dim, Dim>& eps) {
  Eigen::Matrix<double, LatticeElasticity<Dim>::kVoigt, 1> out;
  if constexpr (Dim == 2) {
    out << eps(0, 0), eps(1, 1), 2 * eps(0, 1);
  } else {
    out << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(1, 2), 2 * eps(0, 2), 2 * eps(0, 1);
  }
  return out;
}

// The springs' energy under the small affine strain eps, per unit measure, equals
// eps : C : eps / 2 with the tensor lattice_elasticity() reports.
template <int Dim>
void ExpectTensorMatchesEnergy(const SimplexMesh<Dim>& mesh) {
  MassSpringSystem<Dim> s = make_mass_spring(mesh, Material{3.0, 2.0, 0.0});
  const double measure = measure_of(mesh);
  const LatticeElasticity<Dim> lattice = lattice_elasticity(s, mesh.nodes, measure);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::Matrix<double, Dim, Dim> eps;
    for (int i = 0; i < Dim; ++i)
      for (int j = 0; j <= i; ++j) eps(i, j) = eps(j, i) = 1e-6 * uniform(random);
    s.x = mesh.nodes + eps * mesh.nodes;
    const auto e = voigt_strain<Dim>(eps);
    const double expected = 0.5 * e.dot(lattice.voigt * e);
    EXPECT_NEAR(potential_energy(s) / measure, expected, 1e-5 * expected) << "trial " << trial;
  }
}

TEST(LatticeElasticityTest, TensorIsTheEnergyOfAnAffineStrain) {
  ExpectTensorMatchesEnergy<2>(jittered(rectangle_mesh(1.0, 1.0, 8, 8), 0.125, 3));
  ExpectTensorMatchesEnergy<2>(rectangle_mesh(1.0, 1.0, 8, 8, DiagonalPattern::kUniform));
  ExpectTensorMatchesEnergy<3>(jittered(box_mesh(1.0, 1.0, 1.0, 4, 4, 4), 0.25, 3));
}

// The plain rule k = c^2 m / L (each element's mass shared among its edges), built here by
// hand without the calibration, has the isotropic part of modulus rho c^2 / 3 (2D) or
// rho c^2 / 6 (3D) on any mesh: the 0.58 c and 0.41 c that thin strips and bars of it carry.
template <int Dim>
double PlainRuleModulus(const SimplexMesh<Dim>& mesh, const Material& material) {
  MassSpringSystem<Dim> s;
  const double c2 = material.wave_speed() * material.wave_speed();
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const double m = material.density * element_measure(mesh, e) / (Dim * (Dim + 1) / 2);
    const auto& el = mesh.elements[e];
    for (int a = 0; a <= Dim; ++a)
      for (int b = a + 1; b <= Dim; ++b) {
        Spring sp;
        sp.i = el[a];
        sp.j = el[b];
        sp.params.rest_length = (mesh.nodes.col(sp.j) - mesh.nodes.col(sp.i)).norm();
        sp.params.stiffness = c2 * m / sp.params.rest_length;
        s.springs.push_back(sp);  // an edge of several elements: one spring per element
      }
  }
  return lattice_elasticity(s, mesh.nodes, measure_of(mesh)).youngs_modulus;
}

TEST(LatticeElasticityTest, PlainRuleGivesAThirdOrASixthOfRhoCSquared) {
  const Material material{5.0, 2.0, 0.0};  // rho c^2 = 5
  EXPECT_NEAR(PlainRuleModulus<2>(rectangle_mesh(1.0, 0.5, 10, 5), material), 5.0 / 3.0, 1e-12);
  EXPECT_NEAR(PlainRuleModulus<2>(disk_mesh(1.0, 6, Eigen::Vector2d::Zero()), material), 5.0 / 3.0,
              1e-12);
  EXPECT_NEAR(PlainRuleModulus<3>(box_mesh(1.0, 1.0, 0.5, 4, 4, 2), material), 5.0 / 6.0, 1e-12);
}

// Calibrated: the isotropic material with the requested E, along every direction, and
// Poisson's ratio 1/3 (2D) or 1/4 (3D), on structured and irregular meshes.
template <int Dim>
void ExpectIsotropicWithModulus(const SimplexMesh<Dim>& mesh, double youngs, const char* name) {
  const MassSpringSystem<Dim> s = make_mass_spring(mesh, Material{youngs, 1.0, 0.0});
  const LatticeElasticity<Dim> lattice = lattice_elasticity(s, mesh.nodes, measure_of(mesh));
  EXPECT_NEAR(lattice.youngs_modulus, youngs, 1e-12 * youngs) << name;
  EXPECT_LT(lattice.anisotropy, 1e-12) << name;
  for (double degrees : {0.0, 30.0, 45.0, 90.0}) {
    Eigen::Matrix<double, Dim, 1> d = Eigen::Matrix<double, Dim, 1>::Zero();
    d(0) = std::cos(degrees * kPi / 180);
    d(Dim - 1) = std::sin(degrees * kPi / 180);
    EXPECT_NEAR(lattice.youngs_modulus_along(d), youngs, 1e-9 * youngs)
        << name << " along " << degrees << " deg";
  }
  // uniaxial stress along x: the lateral strain over the axial one
  const Eigen::Matrix<double, LatticeElasticity<Dim>::kVoigt, 1> strain =
      lattice.voigt.ldlt().solve(Eigen::Matrix<double, LatticeElasticity<Dim>::kVoigt, 1>::Unit(0));
  EXPECT_NEAR(-strain(1) / strain(0), Dim == 2 ? 1.0 / 3.0 : 0.25, 1e-9) << name;
  std::printf("[ lattice ] %s: E = %.6g, Poisson's ratio %.4f, anisotropy %.2g\n", name,
              lattice.youngs_modulus, -strain(1) / strain(0), lattice.anisotropy);
}

TEST(LatticeElasticityTest, CalibratedNetworksAreTheIsotropicMaterial) {
  ExpectIsotropicWithModulus<2>(rectangle_mesh(1.0, 1.0, 8, 8), 7.0, "2D alternating grid");
  ExpectIsotropicWithModulus<2>(jittered(rectangle_mesh(1.0, 1.0, 8, 8), 0.125, 5), 7.0,
                                "2D jittered grid");
  ExpectIsotropicWithModulus<2>(disk_mesh(1.0, 6, Eigen::Vector2d::Zero()), 7.0, "2D disk");
  ExpectIsotropicWithModulus<3>(box_mesh(1.0, 1.0, 1.0, 4, 4, 4), 7.0, "3D box");
  ExpectIsotropicWithModulus<3>(jittered(box_mesh(1.0, 1.0, 1.0, 4, 4, 4), 0.25, 5), 7.0,
                                "3D jittered box");
}

// A grid whose diagonals all run the same way has springs in three directions only: no
// weighting of them is isotropic, and the calibration says how far it stays.
TEST(LatticeElasticityTest, ThreeDirectionsCannotBeIsotropic) {
  const SimplexMesh<2> mesh = rectangle_mesh(1.0, 1.0, 8, 8, DiagonalPattern::kUniform);
  const MassSpringSystem<2> s = make_mass_spring(mesh, Material{1.0, 1.0, 0.0});
  const LatticeElasticity<2> lattice = lattice_elasticity(s, mesh.nodes, measure_of(mesh));
  EXPECT_GT(lattice.anisotropy, 0.1);
  std::printf(
      "[ lattice ] 2D grid, diagonals one way: anisotropy %.3f, E along x %.4f, along "
      "the diagonals %.4f, across them %.4f (requested 1)\n",
      lattice.anisotropy, lattice.youngs_modulus_along(Eigen::Vector2d(1, 0)),
      lattice.youngs_modulus_along(Eigen::Vector2d(1, 1).normalized()),
      lattice.youngs_modulus_along(Eigen::Vector2d(1, -1).normalized()));
}

}  // namespace
}  // namespace gencoord::deformable
