// SPDX-License-Identifier: BSD-3-Clause
// Quadratic triangles and tetrahedra (quadratic_mesh.hpp, quadratic_elements.hpp): the mesh's
// midpoints and the linear simplices that tile it, the lumped masses, forces as minus the
// energy's gradient and the stiffness and damping as their Jacobians (central differences,
// inverted shapes included), rigid motions free, uniform strain exact, and objects of them in
// a relaxed stretch, in explicit and implicit steps and refused when malformed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "explicit_stability.hpp"
#include "figures.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/stretch_modulus.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/validate.hpp"
#include "long_run_checks.hpp"
#include "mesh_files.hpp"
#include "test_helpers.hpp"
#include "test_materials.hpp"

namespace gencoord::deformable {
namespace {

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;
template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;
template <int Dim>
constexpr int kNodes = QuadraticElement<Dim>::kNodes;
template <int Dim>
using FlatNodes = Eigen::Matrix<double, Dim * kNodes<Dim>, 1>;
template <int Dim>
using Square = Eigen::Matrix<double, Dim * kNodes<Dim>, Dim * kNodes<Dim>>;

using testing::corotated;

// one sheared simplex of edge about 0.1
template <int Dim>
SimplexMesh<Dim> one_simplex() {
  SimplexMesh<Dim> mesh;
  mesh.nodes = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, Dim + 1);
  for (int a = 1; a <= Dim; ++a) {
    mesh.nodes(a - 1, a) = 0.1;
    mesh.nodes(0, a) += 0.02 * a;
  }
  std::array<int, Dim + 1> element;
  for (int a = 0; a <= Dim; ++a) element[a] = a;
  mesh.elements = {element};
  return mesh;
}

template <int Dim>
double measure_of(const SimplexMesh<Dim>& mesh) {
  double sum = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) sum += element_measure(mesh, e);
  return sum;
}

template <int Dim>
FlatNodes<Dim> flatten(const QuadraticNodes<Dim>& x) {
  FlatNodes<Dim> out;
  for (int a = 0; a < kNodes<Dim>; ++a) out.template segment<Dim>(Dim * a) = x[a];
  return out;
}

template <int Dim>
QuadraticNodes<Dim> unflatten(const FlatNodes<Dim>& y) {
  QuadraticNodes<Dim> out;
  for (int a = 0; a < kNodes<Dim>; ++a) out[a] = y.template segment<Dim>(Dim * a);
  return out;
}

template <int Dim>
Square<Dim> assemble(const QuadraticJacobian<Dim>& j) {
  Square<Dim> out;
  for (int a = 0; a < kNodes<Dim>; ++a)
    for (int b = 0; b < kNodes<Dim>; ++b) out.template block<Dim, Dim>(Dim * a, Dim * b) = j[a][b];
  return out;
}

template <int Dim>
QuadraticNodes<Dim> zero_nodes() {
  QuadraticNodes<Dim> out;
  for (auto& x : out) x.setZero();
  return out;
}

template <int Dim>
void ExpectMidpointsTileEachElement(const SimplexMesh<Dim>& mesh) {
  const QuadraticMesh<Dim> q = quadratic_mesh(mesh);
  EXPECT_EQ(q.nodes.cols(), mesh.nodes.cols() + static_cast<int>(mesh_edges(mesh).size()));
  EXPECT_TRUE(q.nodes.leftCols(mesh.nodes.cols()).isApprox(mesh.nodes));
  EXPECT_NO_THROW(validate_mesh(q));
  const SimplexMesh<Dim> tiles = subdivided_mesh(q);
  EXPECT_EQ(tiles.elements.size(), mesh.elements.size() * (Dim == 2 ? 4 : 8));
  EXPECT_NO_THROW(validate_mesh(tiles));
  for (const auto& t : tiles.elements) {
    Corners<Dim> c;
    for (int a = 0; a <= Dim; ++a) c[a] = tiles.nodes.col(t[a]);
    EXPECT_GT(signed_measure<Dim>(c), 0.0);
  }
  EXPECT_NEAR(measure_of(tiles), measure_of(mesh), 1e-12 * measure_of(mesh));
}

TEST(QuadraticMesh, MidpointsTileEachElement) {
  ExpectMidpointsTileEachElement<2>(rectangle_mesh(1.0, 0.5, 4, 2));
  ExpectMidpointsTileEachElement<3>(box_mesh(1.0, 0.5, 0.5, 2, 1, 1));
  ExpectMidpointsTileEachElement<3>(read_gmsh<3>(kMeshes + "/block_v41.msh"));
}

// each element's lumped masses: positive, 1/19 and 16/57 of it (triangle), 1/36 and 4/27
// (tetrahedron), summing to rho V
template <int Dim>
void ExpectLumpedMasses() {
  const SimplexMesh<Dim> mesh = one_simplex<Dim>();
  const MassSpringSystem<Dim> s = make_mass_spring(quadratic_mesh(mesh), corotated(1e5, 0.3));
  const double m = 1000.0 * measure_of(mesh);
  EXPECT_NEAR(s.mass.sum(), m, 1e-12 * m);
  for (int a = 0; a < kNodes<Dim>; ++a)
    EXPECT_NEAR(s.mass(a) / m,
                a <= Dim ? (Dim == 2 ? 1.0 / 19 : 1.0 / 36) : (Dim == 2 ? 16.0 / 57 : 4.0 / 27),
                1e-12);
  EXPECT_EQ(s.springs.size(), static_cast<size_t>(kNodes<Dim> * (kNodes<Dim> - 1) / 2));
  ASSERT_EQ(s.quadratic_elements.size(), 1u);
  EXPECT_TRUE(s.elements.empty());
}

TEST(QuadraticElement, LumpedMassesArePositiveAndSumToTheElements) {
  ExpectLumpedMasses<2>();
  ExpectLumpedMasses<3>();
}

// the element of one_simplex() in a quadratic object, with damping time beta
template <int Dim>
QuadraticElement<Dim> one_element(double beta = 0.0) {
  const MassSpringSystem<Dim> s =
      make_mass_spring(quadratic_mesh(one_simplex<Dim>()), corotated(1e5, 0.3, beta * 1e5));
  return s.quadratic_elements.at(0);
}

template <int Dim>
QuadraticNodes<Dim> rest_nodes() {
  const QuadraticMesh<Dim> q = quadratic_mesh(one_simplex<Dim>());
  QuadraticNodes<Dim> out;
  for (int a = 0; a < kNodes<Dim>; ++a) out[a] = q.nodes.col(a);
  return out;
}

// the rest nodes moved at random by up to `size` (seeded); `invert` mirrors corner 0 through
// the opposite face first
template <int Dim>
QuadraticNodes<Dim> deformed(double size, unsigned seed, bool invert = false) {
  QuadraticNodes<Dim> x = rest_nodes<Dim>();
  if (invert) x[0] = 2.0 * x[1] - x[0];
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> move(-size, size);
  for (auto& p : x)
    for (int d = 0; d < Dim; ++d) p(d) += move(random);
  return x;
}

template <int Dim>
void ExpectDerivativesMatchCentralDifferences(bool invert) {
  const QuadraticElement<Dim> e = one_element<Dim>();
  const QuadraticNodes<Dim> x = deformed<Dim>(0.02, 7, invert);
  const FlatNodes<Dim> y = flatten<Dim>(x);
  const FlatNodes<Dim> f = flatten<Dim>(quadratic_element_forces(e, x, zero_nodes<Dim>()));
  const Square<Dim> k = assemble<Dim>(quadratic_element_stiffness(e, x, false));
  const double h = 1e-7;
  FlatNodes<Dim> grad;
  Square<Dim> jac;
  for (int i = 0; i < y.size(); ++i) {
    FlatNodes<Dim> up = y, down = y;
    up(i) += h;
    down(i) -= h;
    grad(i) = (quadratic_element_energy(e, unflatten<Dim>(up)) -
               quadratic_element_energy(e, unflatten<Dim>(down))) /
              (2.0 * h);
    jac.col(i) =
        (flatten<Dim>(quadratic_element_forces(e, unflatten<Dim>(up), zero_nodes<Dim>())) -
         flatten<Dim>(quadratic_element_forces(e, unflatten<Dim>(down), zero_nodes<Dim>()))) /
        (2.0 * h);
  }
  EXPECT_LT((f + grad).norm(), 1e-6 * f.norm()) << (invert ? "inverted" : "upright");
  EXPECT_LT((k - jac).norm(), 1e-5 * k.norm()) << (invert ? "inverted" : "upright");
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  // the definite stiffness has no positive eigenvalue
  const Square<Dim> definite = assemble<Dim>(quadratic_element_stiffness(e, x, true));
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<Square<Dim>>(definite).eigenvalues().maxCoeff(),
            1e-9 * definite.norm());
}

TEST(QuadraticElement, ForcesAndStiffnessAreTheEnergysDerivatives) {
  ExpectDerivativesMatchCentralDifferences<2>(false);
  ExpectDerivativesMatchCentralDifferences<2>(true);
  ExpectDerivativesMatchCentralDifferences<3>(false);
  ExpectDerivativesMatchCentralDifferences<3>(true);
}

// a rigid motion costs nothing and pushes nothing; a uniform strain F = A has energy
// V0 psi(A) whatever the element's order
template <int Dim>
void ExpectRigidMotionFreeAndUniformStrainExact() {
  const QuadraticElement<Dim> e = one_element<Dim>();
  const QuadraticNodes<Dim> rest = rest_nodes<Dim>();
  Mat<Dim> rotation;
  if constexpr (Dim == 2) {
    rotation = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  } else {
    rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  }
  QuadraticNodes<Dim> moved;
  for (int a = 0; a < kNodes<Dim>; ++a) moved[a] = rotation * rest[a] + Vec<Dim>::Constant(0.3);
  EXPECT_NEAR(quadratic_element_energy(e, moved), 0.0, 1e-18);
  for (const auto& f : quadratic_element_forces(e, moved, zero_nodes<Dim>()))
    EXPECT_LT(f.norm(), 1e-9);
  Mat<Dim> strain = Mat<Dim>::Identity();
  strain(0, 0) += 0.01;
  strain(Dim - 1, 0) += 0.004;
  QuadraticNodes<Dim> stretched;
  for (int a = 0; a < kNodes<Dim>; ++a) stretched[a] = rotation * strain * rest[a];
  ContinuumElement<Dim> linear;
  linear.mu = e.mu;
  linear.lambda = e.lambda;
  Corners<Dim> unit;
  for (int a = 0; a <= Dim; ++a)
    unit[a] = a == 0 ? Vec<Dim>::Zero() : Vec<Dim>(Vec<Dim>::Unit(a - 1));
  Corners<Dim> unit_stretched;
  for (int a = 0; a <= Dim; ++a) unit_stretched[a] = rotation * strain * unit[a];
  const double density = continuum_element_energy(linear, unit_stretched);  // V0 = 1
  EXPECT_NEAR(quadratic_element_energy(e, stretched), e.rest_measure * density,
              1e-12 * e.rest_measure * density);
}

TEST(QuadraticElement, RigidMotionIsFreeAndUniformStrainExact) {
  ExpectRigidMotionFreeAndUniformStrainExact<2>();
  ExpectRigidMotionFreeAndUniformStrainExact<3>();
}

// the damping force is linear in the velocities with the damping Jacobian as its matrix, and
// a rigid rotation's velocities are not damped
template <int Dim>
void ExpectDampingLinearInVelocity() {
  const QuadraticElement<Dim> e = one_element<Dim>(0.01);
  const QuadraticNodes<Dim> x = deformed<Dim>(0.01, 3);
  QuadraticNodes<Dim> v = deformed<Dim>(0.5, 4);
  for (int a = 0; a < kNodes<Dim>; ++a) v[a] -= rest_nodes<Dim>()[a];
  const FlatNodes<Dim> damping_force =
      flatten<Dim>(quadratic_element_forces(e, x, v)) -
      flatten<Dim>(quadratic_element_forces(e, x, zero_nodes<Dim>()));
  const Square<Dim> d = assemble<Dim>(quadratic_element_damping(e, x));
  EXPECT_LT((damping_force - d * flatten<Dim>(v)).norm(), 1e-10 * damping_force.norm());
  EXPECT_GT(damping_force.norm(), 0.0);
  QuadraticNodes<Dim> spin;  // about the origin, at the positions x
  for (int a = 0; a < kNodes<Dim>; ++a) {
    if constexpr (Dim == 2) {
      spin[a] = Vec<Dim>(-x[a](1), x[a](0));
    } else {
      spin[a] = Eigen::Vector3d(0.3, -0.2, 1.0).cross(x[a]);
    }
  }
  EXPECT_LT((d * flatten<Dim>(spin)).norm(), 1e-12 * d.norm());
}

TEST(QuadraticElement, DampingIsLinearAndLeavesRotationsAlone) {
  ExpectDampingLinearInVelocity<2>();
  ExpectDampingLinearInVelocity<3>();
}

// a relaxed stretch of a strip and a bar shows E and nu exactly, as for linear elements
TEST(QuadraticElement, StretchShowsTheMaterial) {
  const double youngs = 1e5;
  for (const double nu : {0.3, 0.49}) {
    const StretchResponse s2 = validation::stretch(read_gmsh<2>(kMeshes + "/strip_h025.msh"),
                                                   youngs, nu, validation::Model::kQuadratic);
    EXPECT_NEAR(s2.youngs_modulus / youngs, 1.0, 1e-4) << "strip, nu " << nu;
    EXPECT_NEAR(s2.poisson_ratio, nu, 1e-4) << "strip, nu " << nu;
    const StretchResponse s3 = validation::stretch(read_gmsh<3>(kMeshes + "/bar_h050.msh"), youngs,
                                                   nu, validation::Model::kQuadratic);
    EXPECT_NEAR(s3.youngs_modulus / youngs, 1.0, 1e-4) << "bar, nu " << nu;
    EXPECT_NEAR(s3.poisson_ratio, nu, 1e-4) << "bar, nu " << nu;
  }
}

// the highest-frequency estimate bounds the dense eigensolve's from above, within 10%, and
// cfl_limit() is 2 / omega_max; symplectic Euler at 0.95 of it stays bounded, at 1.3 times
// the true limit it diverges
template <int Dim>
void ExpectExplicitLimitTight(const SimplexMesh<Dim>& mesh, const char* name) {
  const MassSpringSystem<Dim> start =
      testing::ringing(make_mass_spring(quadratic_mesh(mesh), corotated(1e5, 0.3)));
  const double exact = testing::dense_highest_frequency(start);
  const double estimate = continuum_highest_frequency(start);
  EXPECT_GE(estimate, exact) << name;
  EXPECT_LT(estimate, 1.1 * exact) << name;
  MassSpringSystem<Dim> s = start;
  const double limit = cfl_limit(s);
  const testing::EnergySwing swing = testing::energy_swing(
      s, [&](MassSpringSystem<Dim>& o) { symplectic_euler_step(o, 0.95 * limit); });
  EXPECT_LT(swing.last, 1.05 * swing.first) << name;
  EXPECT_TRUE(testing::diverges(start, 1.3 * 2.0 / exact)) << name;
  const double linear = cfl_limit(make_mass_spring(mesh, corotated(1e5, 0.3)));
  std::printf(
      "[ %dD quadratic explicit ] %s: estimate / exact omega_max %.4f; largest energy %.3f E0 "
      "in the first 1000 steps at 0.95 of the limit, %.3f in the last; the CFL limit %.3f of "
      "linear elements' on the same mesh\n",
      Dim, name, estimate / exact, swing.first, swing.last, limit / linear);
}

TEST(QuadraticElement, ExplicitLimitIsTight) {
  ExpectExplicitLimitTight<2>(rectangle_mesh(1.0, 0.2, 10, 2), "strip");
  ExpectExplicitLimitTight<3>(box_mesh(0.4, 0.1, 0.1, 4, 1, 1), "bar");
}

// backward Euler on a swinging, undamped quadratic strip pinned at one end never gains energy
TEST(QuadraticElement, ImplicitStepNeverGainsEnergy) {
  const QuadraticMesh<2> mesh = quadratic_mesh(rectangle_mesh(1.0, 0.1, 10, 1));
  MassSpringSystem<2> s = make_mass_spring(mesh, corotated(1e5, 0.3));
  pin_nodes_where(s, 0, 0.0);
  for (int n = 0; n < s.num_nodes(); ++n) s.v(1, n) = 0.5 * s.x(0, n);
  s.gravity = Vec<2>(0.0, -9.81);
  BackwardEulerStepper<2> stepper;
  const double e0 = total_energy(s);
  double previous = e0;
  for (int k = 0; k < 200; ++k) {
    stepper.step(s, 10.0 * cfl_limit(s));
    const double e = total_energy(s);
    EXPECT_LE(e, previous * (1.0 + 1e-9) + 1e-12) << "step " << k;
    previous = e;
  }
  EXPECT_LT(previous, e0);
}

// The cube of quadratic elements dropped onto the block in implicit steps (long_run_checks.hpp);
// deformable_long_tests repeats it in explicit steps and with linear elements
TEST(QuadraticElement, CubeDroppedOnABlockStaysOnIt) { ExpectCubeStaysOnTheBlock(true, true); }

TEST(QuadraticElement, MalformedInputIsRefused) {
  QuadraticMesh<2> curved = quadratic_mesh(rectangle_mesh(1.0, 0.5, 2, 1));
  const int moved = curved.elements[1][4];
  curved.nodes(1, moved) += 0.01;
  try {
    make_mass_spring(curved, corotated(1e5, 0.3));
    ADD_FAILURE() << "a curved element was accepted";
  } catch (const MeshError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("is not at the middle of its edge"));
    EXPECT_EQ(e.node(), moved);
    EXPECT_EQ(e.element(), 1);
  }
  // two triangles whose shared edge (the square's diagonal) has a midpoint node each: a crack
  QuadraticMesh<2> cracked = quadratic_mesh(rectangle_mesh(1.0, 1.0, 1, 1));
  int shared = -1;  // where the second triangle lists the shared midpoint (3, 4 or 5)
  for (int k = 3; k < 6; ++k)
    for (int j = 3; j < 6; ++j)
      if (cracked.elements[0][k] == cracked.elements[1][j]) shared = j;
  ASSERT_GE(shared, 0);
  const int copy = static_cast<int>(cracked.nodes.cols());
  cracked.nodes.conservativeResize(2, copy + 1);
  cracked.nodes.col(copy) = cracked.nodes.col(cracked.elements[1][shared]);
  cracked.elements[1][shared] = copy;
  try {
    make_mass_spring(cracked, corotated(1e5, 0.3));
    ADD_FAILURE() << "a cracked mesh was accepted";
  } catch (const MeshError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("different midpoint nodes"));
    EXPECT_EQ(e.node(), copy);
  }
  // the stretch of an object with rest positions that are not its own nodes'
  const SimplexMesh<2> strip = rectangle_mesh(1.0, 0.1, 10, 1);
  const MassSpringSystem<2> quadratic_strip =
      make_mass_spring(quadratic_mesh(strip), corotated(1e5, 0.3));
  EXPECT_THROW(stretch_response(quadratic_strip, strip.nodes, 0.1, 0), ObjectError);
  Material springs{1e5, 1000.0, 0.0};
  EXPECT_THROW(make_mass_spring(quadratic_mesh(rectangle_mesh(1.0, 0.5, 2, 1)), springs),
               MaterialError);
  MassSpringSystem<3> s =
      make_mass_spring(quadratic_mesh(box_mesh(1, 1, 1, 1, 1, 1)), corotated(1e5, 0.3));
  s.quadratic_elements[2].springs[7] = s.quadratic_elements[2].springs[8];
  try {
    validate_object(s);
    ADD_FAILURE() << "a quadratic element with a wrong spring was accepted";
  } catch (const ObjectError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("quadratic element 2"));
  }
}

}  // namespace
}  // namespace gencoord::deformable
