// SPDX-License-Identifier: BSD-3-Clause
// Bad meshes, materials, objects, step sizes and solver settings: each refused with its typed
// error (gencoord/deformable/errors.hpp, or StepSizeError) naming the element, node or spring.
#include "gencoord/deformable/validate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/errors.hpp"

namespace gencoord::deformable {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Runs f, which must throw E; returns the error for further checks.
template <class E, class F>
E Refused(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e;
  }
  ADD_FAILURE() << "expected an exception";
  throw std::logic_error("not refused");
}

SimplexMesh<2> Triangle() {
  SimplexMesh<2> mesh;
  mesh.nodes.resize(2, 3);
  mesh.nodes << 0.0, 1.0, 0.0, 0.0, 0.0, 1.0;
  mesh.elements = {{0, 1, 2}};
  return mesh;
}

SimplexMesh<3> Tetrahedron() {
  SimplexMesh<3> mesh;
  mesh.nodes.resize(3, 4);
  mesh.nodes << 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  mesh.elements = {{0, 1, 2, 3}};
  return mesh;
}

TEST(ValidationTest, ValidInputsAreAccepted) {
  EXPECT_NO_THROW(make_mass_spring(Triangle(), Material{}));
  EXPECT_NO_THROW(make_mass_spring(Tetrahedron(), Material{}));
  EXPECT_NO_THROW(make_rod(uniform_rod_nodes(4), Material{}));
}

TEST(ValidationTest, ElementIndexOutOfRange) {
  SimplexMesh<2> mesh = Triangle();
  mesh.elements = {{0, 1, 99}};
  const MeshError e = Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("element 0"), HasSubstr("node 99"),
                              HasSubstr("out of range"), HasSubstr("3 nodes")));
  EXPECT_EQ(e.element(), 0);
  EXPECT_EQ(e.node(), 99);
  mesh.elements = {{0, -1, 2}};
  EXPECT_THROW(make_mass_spring(mesh, Material{}), MeshError);
}

TEST(ValidationTest, RepeatedNodeInAnElement) {
  SimplexMesh<2> mesh = Triangle();
  mesh.elements = {{0, 1, 1}};
  EXPECT_THAT(Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); }).what(),
              AllOf(HasSubstr("element 0"), HasSubstr("repeats node 1")));
}

TEST(ValidationTest, DegenerateTetrahedron) {
  SimplexMesh<3> mesh = Tetrahedron();
  mesh.nodes.col(3) << 0.5, 0.5, 0.0;  // in the plane of the others: zero volume
  const MeshError e = Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("element 0"), HasSubstr("degenerate"), HasSubstr("volume"),
                              HasSubstr("coplanar")));
  EXPECT_EQ(e.element(), 0);
}

TEST(ValidationTest, CollinearTriangleAndCoincidentNodes) {
  SimplexMesh<2> mesh = Triangle();
  mesh.nodes.col(2) << 2.0, 0.0;
  EXPECT_THAT(Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); }).what(),
              AllOf(HasSubstr("element 0"), HasSubstr("area"), HasSubstr("collinear")));
  mesh.nodes.col(2) = mesh.nodes.col(1);  // a zero-length edge
  EXPECT_THROW(make_mass_spring(mesh, Material{}), MeshError);
}

TEST(ValidationTest, ShapesAreJudgedAtAnyScale) {
  SimplexMesh<3> mesh = Tetrahedron();
  mesh.nodes *= 1e100;  // a volume of 1e300 / 6: representable, and as regular as at scale 1
  EXPECT_NO_THROW(make_mass_spring(mesh, Material{}));
  for (double scale : {1e200, 1e-200}) {
    mesh = Tetrahedron();
    mesh.nodes *= scale;
    EXPECT_THAT(Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); }).what(),
                AllOf(HasSubstr("element 0 has a volume"),
                      HasSubstr("outside the range of a "
                                "double"),
                      Not(HasSubstr("coplanar"))));
  }
}

TEST(ValidationTest, UnusedNode) {
  SimplexMesh<2> mesh = Triangle();
  mesh.nodes.conservativeResize(2, 4);
  mesh.nodes.col(3) << 5.0, 5.0;
  const MeshError e = Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("node 3"), HasSubstr("no element"), HasSubstr("mass")));
  EXPECT_EQ(e.node(), 3);
}

TEST(ValidationTest, EmptyMesh) {
  EXPECT_THAT(Refused<MeshError>([] { make_mass_spring(SimplexMesh<2>{}, Material{}); }).what(),
              HasSubstr("at least one element"));
}

TEST(ValidationTest, NonFiniteNode) {
  SimplexMesh<2> mesh = Triangle();
  mesh.nodes(1, 2) = kNaN;
  const MeshError e = Refused<MeshError>([&] { make_mass_spring(mesh, Material{}); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("node 2"), HasSubstr("not finite")));
  EXPECT_EQ(e.node(), 2);
  EXPECT_THAT(Refused<MeshError>([] {
                make_rod({0.0, kInf}, Material{});
              }).what(),
              AllOf(HasSubstr("node 1"), HasSubstr("not finite")));
  EXPECT_THAT(Refused<MeshError>([] {
                make_rod({0.0, kNaN, 1.0}, Material{});
              }).what(),
              HasSubstr("node 1"));
}

TEST(ValidationTest, RodNodesMustIncrease) {
  EXPECT_THAT(Refused<MeshError>([] {
                make_rod({0.0, 0.5, 0.5, 1.0}, Material{});
              }).what(),
              AllOf(HasSubstr("element 1"), HasSubstr("nodes 1, 2"), HasSubstr("increase")));
  EXPECT_THROW(make_rod({0.0, 1.0, 0.5}, Material{}), MeshError);
  EXPECT_THAT(Refused<MeshError>([] { make_rod({0.0}, Material{}); }).what(),
              HasSubstr("two nodes"));
}

TEST(ValidationTest, BadMaterial) {
  for (const Material& m : {Material{-1.0, 1.0, 0.0}, Material{0.0, 1.0, 0.0},
                            Material{kNaN, 1.0, 0.0}, Material{kInf, 1.0, 0.0}}) {
    EXPECT_THAT(Refused<MaterialError>([&] { make_mass_spring(Triangle(), m); }).what(),
                HasSubstr("Young's modulus"));
    EXPECT_THROW(make_rod(uniform_rod_nodes(3), m), MaterialError);
  }
  for (const Material& m :
       {Material{1.0, 0.0, 0.0}, Material{1.0, -2.0, 0.0}, Material{1.0, kNaN, 0.0}}) {
    EXPECT_THAT(Refused<MaterialError>([&] { make_mass_spring(Tetrahedron(), m); }).what(),
                HasSubstr("density"));
  }
  EXPECT_THAT(Refused<MaterialError>([&] {
                make_rod({0, 1}, Material{1.0, 1.0, -1.0});
              }).what(),
              HasSubstr("damping"));
}

TEST(ValidationTest, BadTimeStep) {
  for (double dt : {0.0, -1e-3, kNaN, kInf, -kInf}) {
    MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(4), Material{});
    EXPECT_THAT(Refused<StepSizeError>([&] { symplectic_euler_step(rod, dt); }).what(),
                HasSubstr("positive and finite"))
        << dt;
    EXPECT_THROW(backward_euler_step(rod, dt), StepSizeError) << dt;
    EXPECT_EQ(rod.t, 0.0);
    EXPECT_EQ(rod.steps, 0);
  }
}

TEST(ValidationTest, ZeroLengthSpringIsRefusedNotSkippedByTheCflCheck) {
  MassSpringSystem<2> s = make_mass_spring(Triangle(), Material{});
  s.springs[1].params.rest_length = 0.0;
  const ObjectError e = Refused<ObjectError>([&] { symplectic_euler_step(s, 1e-3); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("spring 1"), HasSubstr("rest length")));
  EXPECT_EQ(e.spring(), 1);
  s.springs[1].params.rest_length = kNaN;
  EXPECT_THROW(backward_euler_step(s, 1e-3), ObjectError);
}

TEST(ValidationTest, BadObjectsAreRefusedByTheSteps) {
  const MassSpringSystem<2> good = make_mass_spring(Triangle(), Material{});
  auto refuse = [&](auto&& spoil, const std::string& words) {
    MassSpringSystem<2> s = good;
    spoil(s);
    EXPECT_THAT(Refused<ObjectError>([&] { symplectic_euler_step(s, 1e-3); }).what(),
                HasSubstr(words));
    EXPECT_THROW(backward_euler_step(s, 1e-3), ObjectError) << words;
  };
  refuse([](auto& s) { s.mass(1) = 0.0; }, "node 1 has mass 0");
  refuse([](auto& s) { s.mass(2) = -1.0; }, "node 2 has mass");
  refuse([](auto& s) { s.mass(0) = kNaN; }, "node 0 has mass");
  refuse([](auto& s) { s.x(0, 1) = kNaN; }, "node 1 has a position or velocity");
  refuse([](auto& s) { s.v(1, 2) = kInf; }, "node 2 has a position or velocity");
  refuse([](auto& s) { s.springs[0].j = 99; }, "spring 0 joins nodes 0 and 99");
  refuse([](auto& s) { s.springs[2].i = s.springs[2].j; }, "spring 2 joins nodes");
  refuse([](auto& s) { s.springs[0].params.stiffness = -1.0; }, "spring 0");
  refuse([](auto& s) { s.springs[0].params.damping = kNaN; }, "damping");
  refuse([](auto& s) { s.mass.resize(2); }, "sizes disagree");
  refuse([](auto& s) { s.gravity(1) = kNaN; }, "gravity");
  refuse([](auto& s) { s.wave_speed = 0.0; }, "wave speed");
  refuse([](auto& s) { s.ground = GroundPlane{0.0, kNaN, 0.0}; }, "ground");
  refuse([](auto& s) { s.inelastic.plastic_fraction = 2.0; }, "plastic fraction");
}

TEST(ValidationTest, PinnedNodeMayHaveZeroMass) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(3), Material{});
  rod.pinned[0] = 1;
  rod.mass(0) = 0.0;
  EXPECT_NO_THROW(symplectic_euler_step(rod, 1e-3));
}

TEST(ValidationTest, DivergedStepIsRefusedAndLeavesTheObject) {
  MassSpringSystem<1> rod = make_rod(uniform_rod_nodes(4), Material{});
  rod.v(0, 2) = 1e300;
  ExplicitOptions force;
  force.allow_cfl_violation = true;
  const MassSpringSystem<1> before = rod;
  const ObjectError e = Refused<ObjectError>([&] { symplectic_euler_step(rod, 1e10, force); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("diverged"), HasSubstr("smaller step")));
  EXPECT_EQ(rod.x, before.x);
  EXPECT_EQ(rod.t, 0.0);
}

TEST(ValidationTest, ConjugateGradientFailureGivesTheResidualAndWhatToChange) {
  MassSpringSystem<2> s = make_mass_spring(rectangle_mesh(1.0, 1.0, 6, 6), Material{});
  s.v.setRandom();
  ImplicitOptions options;
  options.max_iterations = 1;
  options.tolerance = 1e-14;
  const LinearSolveError e =
      Refused<LinearSolveError>([&] { backward_euler_step(s, 1.0, options); });
  EXPECT_THAT(e.what(), AllOf(HasSubstr("conjugate gradients did not converge"),
                              HasSubstr("relative residual"), HasSubstr("max_iterations"),
                              HasSubstr("kSparseCholesky")));
  EXPECT_EQ(e.iterations(), 1);
  EXPECT_GT(e.residual(), 1e-14);
  EXPECT_EQ(e.unknowns(), 2 * s.num_nodes());
}

}  // namespace
}  // namespace gencoord::deformable
