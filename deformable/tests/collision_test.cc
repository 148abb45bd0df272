// SPDX-License-Identifier: BSD-3-Clause
// Contact with obstacles and between surfaces (collision.hpp): the penalty forces against
// their energy, friction's bounds, the surfaces of meshes, and objects dropped on a step, on
// each other and closing on themselves without passing through and without gaining energy.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include "gencoord/deformable/collision.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/scene.hpp"
#include "gencoord/deformable/sheet.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable {
namespace {

using ::testing::HasSubstr;

// Free nodes without springs (a system that only touches): nodes at the columns of x.
template <int Dim>
MassSpringSystem<Dim> Nodes(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x,
                            const Eigen::VectorXd& mass) {
  MassSpringSystem<Dim> s;
  s.x = x;
  s.v = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, x.cols());
  s.mass = mass;
  s.pinned.assign(x.cols(), 0);
  return s;
}

template <int Dim>
typename MassSpringSystem<Dim>::Points Forces(const MassSpringSystem<Dim>& s) {
  typename MassSpringSystem<Dim>::Points f =
      MassSpringSystem<Dim>::Points::Zero(Dim, s.num_nodes());
  accumulate_forces(s, f);
  return f;
}

// The undamped contact force is minus the gradient of the penalty energy, by central
// differences; between nodes (not against obstacles) the forces sum to zero, what the node
// gets the simplex's corners lose.
template <int Dim>
void ExpectForceIsMinusGradient(MassSpringSystem<Dim> s, bool momentum = true) {
  const auto f = Forces(s);
  if (momentum) {
    EXPECT_LT(f.rowwise().sum().norm(), 1e-12 * f.norm()) << "forces do not cancel";
  }
  EXPECT_GT(f.norm(), 0.0) << "no contact";
  const double h = 1e-7;
  for (int n = 0; n < s.num_nodes(); ++n) {
    for (int d = 0; d < Dim; ++d) {
      MassSpringSystem<Dim> plus = s, minus = s;
      plus.x(d, n) += h;
      minus.x(d, n) -= h;
      const double gradient = (potential_energy(plus) - potential_energy(minus)) / (2.0 * h);
      EXPECT_NEAR(f(d, n), -gradient, 1e-6 * f.cwiseAbs().maxCoeff())
          << "node " << n << " axis " << d;
    }
  }
}

TEST(ContactForce, NodeAgainstTriangleIsMinusTheGradientOfItsEnergyInEveryRegion) {
  // a triangle near the plane z = 0 (normal up) and a node 0.03 above it over its face, an
  // edge and a corner, and 0.05 under its face (thickness 0.1); the node is a corner of a
  // second surface triangle far above, so that it belongs to the surface
  const Eigen::Vector3d near[] = {{0.2, 0.3, 0.03},
                                  {0.5, -0.02, 0.03},
                                  {-0.02, -0.03, 0.03},
                                  {0.55, 0.5, 0.03},
                                  {0.2, 0.3, -0.05}};
  for (const Eigen::Vector3d& p : near) {
    Eigen::Matrix3Xd x(3, 6);
    x << 0.0, 1.0, 0.0, p.x(), 5.0, 5.0,  //
        0.0, 0.0, 1.0, p.y(), 0.0, 1.0,   //
        0.0, 0.01, -0.02, p.z(), 5.0, 5.0;
    Eigen::VectorXd mass(6);
    mass << 1.0, 2.0, 3.0, 0.5, 1.0, 1.0;
    MassSpringSystem<3> s = Nodes<3>(x, mass);
    s.collisions.emplace();
    s.collisions->params = ContactParams{40.0, 0.0, 0.0, 0.1};
    s.collisions->surface = {{0, 1, 2}, {3, 4, 5}};
    SCOPED_TRACE(::testing::Message() << "node at " << p.transpose());
    ExpectForceIsMinusGradient(s);
  }
}

TEST(ContactForce, NodeAgainstSegmentIsMinusTheGradientOfItsEnergy) {
  for (const double y : {0.04, -0.04}) {
    Eigen::Matrix2Xd x(2, 4);
    x << 0.0, 1.0, 0.3, 0.3, 0.0, 0.05, y, 5.0;
    MassSpringSystem<2> s = Nodes<2>(x, Eigen::Vector4d(1.0, 2.0, 0.5, 1.0));
    s.collisions.emplace();
    s.collisions->params = ContactParams{40.0, 0.0, 0.0, 0.1};
    s.collisions->surface = {{1, 0}, {2, 3}};  // (1, 0): its outward normal points up
    SCOPED_TRACE(::testing::Message() << "node at y = " << y);
    ExpectForceIsMinusGradient(s);
  }
}

TEST(ContactForce, ObstaclesPushOutAlongTheirNormalByTheirDepth) {
  Eigen::Matrix3Xd x(3, 2);
  x << 0.0, 0.5, 0.0, 0.5, 0.9, 0.95;  // node 0 in the sphere by 0.1, node 1 in the box by 0.05
  MassSpringSystem<3> s = Nodes<3>(x, Eigen::Vector2d(2.0, 3.0));
  auto& c = s.collisions.emplace();
  c.params = ContactParams{10.0, 0.0, 0.0, 0.0};
  c.spheres.push_back({Eigen::Vector3d(0.0, 0.0, 0.0), 1.0});
  c.boxes.push_back({Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.0, 1.0, 1.0)});
  const auto f = Forces(s);
  EXPECT_TRUE(f.col(0).isApprox(Eigen::Vector3d(0.0, 0.0, 2.0 * 100.0 * 0.1), 1e-12))
      << f.col(0).transpose();
  // node 1 is outside the sphere (|x| = 1.18); the nearest face of the box is z = 1
  EXPECT_TRUE(f.col(1).isApprox(Eigen::Vector3d(0.0, 0.0, 3.0 * 100.0 * 0.05), 1e-12))
      << f.col(1).transpose();
  ExpectForceIsMinusGradient(s, /*momentum=*/false);
}

// Friction is Coulomb's mu a_n while sliding fast, a drag of rate omega when slow, and always
// against the sliding.
TEST(ContactForce, FrictionIsCoulombWhenFastAndADragWhenSlow) {
  Eigen::Matrix3Xd x(3, 1);
  x << 0.0, 0.0, 0.99;  // 0.01 deep under the top of the box
  MassSpringSystem<3> s = Nodes<3>(x, Eigen::VectorXd::Constant(1, 2.0));
  auto& c = s.collisions.emplace();
  const double omega = 10.0, mu = 0.5, a_n = omega * omega * 0.01;
  c.params = ContactParams{omega, 0.0, mu, 0.0};
  c.boxes.push_back({Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d(1.0, 1.0, 1.0)});
  for (const double speed : {10.0, 1.0, 0.05, 0.01}) {
    s.v.col(0) << speed * 0.6, speed * 0.8, 0.0;
    const Eigen::Vector3d f = Forces(s).col(0);
    const double expected = 2.0 * std::min(mu * a_n, omega * speed);
    EXPECT_NEAR(f.head<2>().norm(), expected, 1e-12 * expected) << "sliding at " << speed;
    EXPECT_NEAR(f.head<2>().normalized().dot(s.v.col(0).head<2>().normalized()), -1.0, 1e-12);
    EXPECT_NEAR(f.z(), 2.0 * a_n, 1e-12);
  }
}

// Every boundary face once, pointing out: the flux of x through the boundary is Dim times the
// measure (divergence theorem), and the count is that of the box's faces.
TEST(Surface, BoundaryTrianglesOfABoxPointOut) {
  const SimplexMesh<3> mesh = box_mesh(0.3, 0.2, 0.1, 3, 2, 1);
  const auto faces = boundary_triangles(mesh);
  EXPECT_EQ(faces.size(), 2u * 2u * (3 * 2 + 2 * 1 + 3 * 1));
  double flux = 0.0;
  for (const auto& f : faces) {
    const Eigen::Vector3d a = mesh.nodes.col(f[0]), b = mesh.nodes.col(f[1]),
                          c = mesh.nodes.col(f[2]);
    flux += ((a + b + c) / 3.0).dot((b - a).cross(c - a)) / 2.0;
  }
  EXPECT_NEAR(flux, 3.0 * 0.3 * 0.2 * 0.1, 1e-12);
}

TEST(Surface, BoundarySegmentsOfARectangleRunCounterClockwise) {
  const SimplexMesh<2> mesh = rectangle_mesh(0.4, 0.2, 4, 2);
  const auto segments = boundary_segments(mesh);
  EXPECT_EQ(segments.size(), 2u * (4 + 2));
  double area = 0.0;  // the shoelace formula: positive for a counter-clockwise boundary
  for (const auto& s : segments) {
    const Eigen::Vector2d a = mesh.nodes.col(s[0]), b = mesh.nodes.col(s[1]);
    area += 0.5 * (a.x() * b.y() - b.x() * a.y());
  }
  EXPECT_NEAR(area, 0.4 * 0.2, 1e-12);
}

TEST(Surface, BadSettingsAreRefused) {
  MassSpringSystem<3> cube = make_mass_spring(box_mesh(0.1, 0.1, 0.1, 1, 1, 1), Material{});
  try {
    enable_collisions<3>(cube, {{0, 1, 99}}, 0.0, 0.0);
    FAIL() << "accepted node 99";
  } catch (const ObjectError& e) {
    EXPECT_THAT(e.what(), HasSubstr("node 99"));
  }
  enable_collisions<3>(cube, boundary_triangles(box_mesh(0.1, 0.1, 0.1, 1, 1, 1)), 0.3, 0.1);
  cube.collisions->spheres.push_back({Eigen::Vector3d::Zero(), -1.0});
  try {
    symplectic_euler_step(cube, 1e-6);
    FAIL() << "stepped with a negative radius";
  } catch (const ObjectError& e) {
    EXPECT_THAT(e.what(), HasSubstr("radius -1"));
  }
}

// Two objects appended into one scene, far apart and deformed, feel in it the forces each feels
// alone: springs and volume terms keep their nodes (and a term its springs), shifted.
TEST(Scene, AppendedObjectsKeepTheirOwnForces) {
  Material soft{2e5, 1000.0, 20.0};
  soft.poisson_ratio = 0.45;  // with volume terms
  const SimplexMesh<3> a_mesh = box_mesh(0.2, 0.2, 0.2, 2, 2, 2);
  const SimplexMesh<3> b_mesh = box_mesh(0.1, 0.2, 0.3, 1, 2, 2, Eigen::Vector3d(5.0, 0.0, 0.0));
  MassSpringSystem<3> a = make_mass_spring(a_mesh, soft), b = make_mass_spring(b_mesh, soft);
  ASSERT_FALSE(b.volume_terms.empty());
  a.x.row(0) *= 1.01;  // stretched: springs and volume terms push
  b.x.row(2) = 0.98 * b.x.row(2);
  b.springs[3].broken = true;  // a broken spring silences its elements' terms in the scene too
  MassSpringSystem<3> scene = a;
  const int first = append_object(scene, b);
  EXPECT_EQ(first, a.num_nodes());
  EXPECT_EQ(scene.volume_terms.size(), a.volume_terms.size() + b.volume_terms.size());
  const auto f = Forces(scene), f_a = Forces(a), f_b = Forces(b);
  EXPECT_TRUE(f.leftCols(first).isApprox(f_a, 1e-14));
  EXPECT_TRUE(f.rightCols(b.num_nodes()).isApprox(f_b, 1e-14));
  EXPECT_NEAR(potential_energy(scene), potential_energy(a) + potential_energy(b),
              1e-12 * potential_energy(scene));
}

// Contact in a scene of a coarse and a fine object: each surface simplex keeps its object's
// thickness, so a node near the coarse object's surface is pushed as it would be by the coarse
// object alone (and a third object of the same thickness keeps the list whole); a list that
// does not fit the surface is refused.
TEST(Scene, EachSurfaceKeepsItsContactThickness) {
  const SimplexMesh<3> coarse_mesh = box_mesh(0.2, 0.2, 0.2, 2, 2, 2);
  const SimplexMesh<3> fine_mesh = box_mesh(0.2, 0.2, 0.2, 4, 4, 4, Eigen::Vector3d(1.0, 0, 0));
  const Material soft{2e5, 1000.0, 20.0};
  MassSpringSystem<3> coarse = make_mass_spring(coarse_mesh, soft);
  enable_collisions<3>(coarse, boundary_triangles(coarse_mesh), 0.5, 0.3);
  MassSpringSystem<3> fine = make_mass_spring(fine_mesh, soft);
  enable_collisions<3>(fine, boundary_triangles(fine_mesh), 0.5, 0.3);
  const double h_coarse = coarse.collisions->params.thickness;
  const double h_fine = fine.collisions->params.thickness;
  ASSERT_NEAR(h_fine, 0.5 * h_coarse, 1e-12);
  MassSpringSystem<3> scene = coarse;
  append_object(scene, fine);
  append_object(scene, fine);
  const Collisions<3>& c = *scene.collisions;
  ASSERT_EQ(c.surface_thickness.size(), c.surface.size());
  const std::size_t first_fine = coarse.collisions->surface.size();
  for (std::size_t k = 0; k < c.surface.size(); ++k)
    EXPECT_EQ(c.surface_thickness[k], k < first_fine ? h_coarse : h_fine) << "simplex " << k;
  EXPECT_EQ(c.params.thickness, h_fine);
  // a node of the fine object moved to 0.75 h_coarse above the coarse one's top touches it:
  // the contact penalty's energy is positive
  MassSpringSystem<3> probe = scene;
  const int node = coarse.num_nodes();  // the fine object's first node, (1, 0, 0)
  probe.x.col(node) << 0.1, 0.1, 0.2 + 0.75 * h_coarse;
  MassSpringSystem<3> no_contact = probe;
  no_contact.collisions.reset();
  EXPECT_GT(potential_energy(probe) - potential_energy(no_contact), 0.0);
  probe.collisions->surface_thickness.pop_back();
  EXPECT_THROW(validate_object(probe), ObjectError);
}

// Lowest height of `s`'s nodes [first, last) inside the footprint [x0, x1] x [y0, y1].
double LowestInside(const MassSpringSystem<3>& s, int first, int last, double x0, double x1) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int n = first; n < last; ++n) {
    if (s.x(0, n) > x0 && s.x(0, n) < x1) lowest = std::min(lowest, s.x(2, n));
  }
  return lowest;
}

// A soft cube falls across the edge of a step (a box obstacle on the ground), tips over it
// and comes to the ground: no node goes into the step or the ground by half a cell, and the
// energy (with the penalty's) never grows.
TEST(Drop, ASolidOnAStepNeitherPassesThroughNorGainsEnergy) {
  const double edge = 0.2, cells = 4, g = 9.81;
  MassSpringSystem<3> cube =
      make_mass_spring(box_mesh(edge, edge, edge, cells, cells, cells,
                                Eigen::Vector3d(-0.5 * edge, -0.5 * edge, 0.25)),
                       Material{2e5, 1000.0, 20.0});
  cube.gravity << 0.0, 0.0, -g;
  with_ground(cube, 0.0, 0.3);
  auto& c = enable_collisions<3>(cube, {}, 0.5, 0.3);
  const double step_height = 0.1;
  c.boxes.push_back({Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d(0.03, 1.0, step_height)});
  const double dt = 0.5 * cfl_limit(cube);
  const double allowed = 0.5 * min_rest_length(cube);  // half a cell
  const double e0 = total_energy(cube);
  double deepest_step = 0.0, deepest_ground = 0.0, highest_energy = e0;
  while (cube.t < 1.5) {
    symplectic_euler_step(cube, dt);
    for (int n = 0; n < cube.num_nodes(); ++n) {
      const Eigen::Vector3d p = cube.x.col(n);
      if (p.x() < 0.03) deepest_step = std::max(deepest_step, step_height - p.z());
      deepest_ground = std::max(deepest_ground, -p.z());
    }
    highest_energy = std::max(highest_energy, total_energy(cube));
  }
  const double e_end = total_energy(cube);
  std::printf(
      "[ step ] deepest into the step %.4f m, into the ground %.4f m (allowed %.4f), "
      "energy %.4f J -> %.4f J (highest %.4f J)\n",
      deepest_step, deepest_ground, allowed, e0, e_end, highest_energy);
  EXPECT_LT(deepest_step, allowed);
  EXPECT_LT(deepest_ground, allowed);
  EXPECT_LE(highest_energy, e0 * (1.0 + 1e-3));
  EXPECT_LT(e_end, e0 - 0.5 * cube.mass.sum() * g * 0.1) << "did not come down from the step";
  EXPECT_GT(cube.x.row(0).mean(), 0.03) << "did not tip over the edge onto the ground";
}

// Two soft cubes, one glued to the ground and a smaller one dropped onto it off-centre: the
// falling cube's nodes never come half a cell below the lower cube's top, and no energy is
// gained.
TEST(Drop, ACubeOnACubeDoesNotPassThroughIt) {
  const double edge = 0.2, g = 9.81;
  const Material rubber{2e5, 1000.0, 20.0};
  const SimplexMesh<3> lower_mesh =
      box_mesh(edge, edge, edge, 3, 3, 3, Eigen::Vector3d(-0.5 * edge, -0.5 * edge, 0.0));
  // a smaller cube, off-centre but all over the lower one's top
  const SimplexMesh<3> upper_mesh =
      box_mesh(0.6 * edge, 0.6 * edge, 0.6 * edge, 2, 2, 2,
               Eigen::Vector3d(-0.2 * edge, -0.35 * edge, edge + 0.15));
  MassSpringSystem<3> scene = make_mass_spring(lower_mesh, rubber);
  pin_nodes_where(scene, 2, 0.0);  // glued to the floor
  enable_collisions<3>(scene, boundary_triangles(lower_mesh), 0.5, 0.3);
  MassSpringSystem<3> upper = make_mass_spring(upper_mesh, rubber);
  enable_collisions<3>(upper, boundary_triangles(upper_mesh), 0.5, 0.3);
  const int first = append_object(scene, upper), count = scene.num_nodes();
  scene.gravity << 0.0, 0.0, -g;
  with_ground(scene, 0.0, 0.3);
  const ContactParams& p = scene.collisions->params;
  const double allowed = 0.5 * min_rest_length(scene);  // half a cell
  const double dt = 0.5 * cfl_limit(scene), e0 = total_energy(scene);
  double worst = -1.0, highest_energy = e0;
  Eigen::Vector3d landed;  // the upper cube's centre at 0.5 s, after its bounce
  while (scene.t < 0.8) {
    symplectic_euler_step(scene, dt);
    // how far the upper cube's lowest node over the lower cube is below the lower cube's top
    const double top = scene.x.leftCols(first).row(2).maxCoeff();
    worst = std::max(worst, top - LowestInside(scene, first, count, -0.5 * edge, 0.5 * edge));
    highest_energy = std::max(highest_energy, total_energy(scene));
    if (scene.t < 0.5) landed = scene.x.rightCols(count - first).rowwise().mean();
  }
  std::printf(
      "[ cubes ] deepest overlap %.4f m (thickness %.4f m, allowed %.4f m), energy "
      "%.3f J -> %.3f J (highest %.3f J)\n",
      worst, p.thickness, allowed, e0, total_energy(scene), highest_energy);
  EXPECT_LT(worst, allowed);
  EXPECT_LE(highest_energy, e0 * (1.0 + 1e-3));
  // the upper cube landed on the lower one and is still on it, not on the ground, though
  // sliding toward the edge of the lower one's sagging top
  const Eigen::Vector3d centre = scene.x.rightCols(count - first).rowwise().mean();
  std::printf(
      "[ cubes ] upper cube's centre at (%.3f, %.3f, %.3f) m after its bounce (0.5 s), (%.3f, "
      "%.3f, %.3f) m at 0.8 s\n",
      landed.x(), landed.y(), landed.z(), centre.x(), centre.y(), centre.z());
  EXPECT_LT(landed.head<2>().cwiseAbs().maxCoeff(), 0.5 * edge);
  EXPECT_GT(centre.z(), edge);
}

// A cloth sheet (with bending and two-sided self-contact) dropped onto a sphere drapes over
// it: no node sinks into the sphere by more than half a cell, the energy never grows, the
// middle rests on top of the sphere and the corners hang below it.
TEST(Drop, ASheetDrapesOverASphere) {
  const double side = 0.6, radius = 0.15, g = 9.81;
  const int cells = 12;
  const TriangleSurface cloth = triangle_lattice_sheet(
      side, side, cells, cells, Eigen::Vector3d(-0.5 * side, -0.5 * side, 2.0 * radius + 0.05));
  MassSpringSystem<3> s = make_sheet(cloth, Material{100.0, 0.2, 0.05}, 1e-5);
  s.gravity << 0.0, 0.0, -g;
  auto& c = enable_collisions<3>(s, cloth.triangles, 0.3, 0.3, Sides::kBoth);
  c.spheres.push_back({Eigen::Vector3d(0.0, 0.0, radius), radius});
  const double dt = 0.5 * cfl_limit(s), e0 = total_energy(s);
  const double allowed = 0.5 * min_rest_length(s);
  double deepest = 0.0, highest_energy = e0;
  while (s.t < 0.6) {
    symplectic_euler_step(s, dt);
    for (int n = 0; n < s.num_nodes(); ++n)
      deepest = std::max(deepest, radius - (s.x.col(n) - Eigen::Vector3d(0.0, 0.0, radius)).norm());
    highest_energy = std::max(highest_energy, total_energy(s));
  }
  // the node nearest the middle, and the lowest corner
  int middle = 0;
  for (int n = 1; n < s.num_nodes(); ++n) {
    if (cloth.nodes.col(n).head<2>().norm() < cloth.nodes.col(middle).head<2>().norm()) middle = n;
  }
  const double top = 2.0 * radius, middle_height = s.x(2, middle);
  std::printf(
      "[ sheet on sphere ] deepest into the sphere %.4f m (allowed %.4f), middle at %.4f m "
      "(sphere top %.4f), lowest node %.4f m, energy %.4f J -> %.4f J (highest %.4f J)\n",
      deepest, allowed, middle_height, top, s.x.row(2).minCoeff(), e0, total_energy(s),
      highest_energy);
  EXPECT_LT(deepest, allowed);
  EXPECT_LE(highest_energy, e0 * (1.0 + 1e-3));
  EXPECT_NEAR(middle_height, top, allowed);
  EXPECT_LT(s.x.row(2).minCoeff(), top - 0.1) << "the sheet does not hang down";
}

// A C-shaped object whose upper jaw swings down onto the lower one: with self-collision the
// jaws never cross; without, they do (so the check can fail).
double LowestJawGap(bool collide) {
  // a 1 x 0.5 rectangle of 10 x 5 cells with the slot 0.1 < y < 0.4, x > 0.2 cut out
  SimplexMesh<2> block = rectangle_mesh(1.0, 0.5, 10, 5);
  SimplexMesh<2> shape;
  shape.nodes = block.nodes;
  for (const auto& e : block.elements) {
    const Eigen::Vector2d centre =
        (block.nodes.col(e[0]) + block.nodes.col(e[1]) + block.nodes.col(e[2])) / 3.0;
    if (!(centre.x() > 0.2 && centre.y() > 0.1 && centre.y() < 0.4)) shape.elements.push_back(e);
  }
  std::vector<int> index(block.nodes.cols(), -1);  // the used nodes, renumbered
  int used = 0;
  for (auto& e : shape.elements) {
    for (int& n : e) {
      if (index[n] < 0) index[n] = used++;
      n = index[n];
    }
  }
  shape.nodes.resize(2, used);
  Eigen::Matrix2Xd rest(2, used);
  for (int n = 0; n < block.nodes.cols(); ++n) {
    if (index[n] >= 0) shape.nodes.col(index[n]) = block.nodes.col(n);
  }
  rest = shape.nodes;
  MassSpringSystem<2> s = make_mass_spring(shape, Material{2000.0, 1.0, 0.0});
  if (collide) enable_collisions<2>(s, boundary_segments(shape), 0.0, 0.0);
  // the upper jaw moves down, the lower one up, at 4 m/s each, against c = 45 m/s
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.x(0, n) > 0.25) s.v(1, n) = s.x(1, n) >= 0.4 ? -4.0 : (s.x(1, n) <= 0.1 ? 4.0 : 0.0);
  }
  const double dt = 0.5 * cfl_limit(s);
  double lowest_gap = 1.0;
  while (s.t < 0.1) {
    symplectic_euler_step(s, dt);
    // the gap at the tips: upper jaw's lowest tip node minus the lower jaw's highest
    double upper = 1.0, lower = -1.0;
    for (int n = 0; n < s.num_nodes(); ++n) {
      if (rest(0, n) < 0.8) continue;
      if (rest(1, n) == 0.4) upper = std::min(upper, s.x(1, n));
      if (rest(1, n) == 0.1) lower = std::max(lower, s.x(1, n));
    }
    lowest_gap = std::min(lowest_gap, upper - lower);
  }
  return lowest_gap;
}

TEST(SelfCollision, AClosingJawDoesNotPassThroughItself) {
  const double with = LowestJawGap(true), without = LowestJawGap(false);
  std::printf(
      "[ jaw ] smallest gap between the jaw tips: %.4f m with self-collision, %.4f m "
      "without\n",
      with, without);
  EXPECT_LT(without, -0.05) << "the jaws never met: the test does not test anything";
  EXPECT_GT(with, 0.0);
}

// Backward Euler at 20x the explicit limit keeps the cube out of the step as well.
TEST(Drop, ImplicitStepsKeepASolidOutOfAStep) {
  const double edge = 0.2, g = 9.81;
  MassSpringSystem<3> cube = make_mass_spring(
      box_mesh(edge, edge, edge, 3, 3, 3, Eigen::Vector3d(-0.5 * edge, -0.5 * edge, 0.2)),
      Material{2e5, 1000.0, 20.0});
  cube.gravity << 0.0, 0.0, -g;
  auto& c = enable_collisions<3>(cube, {}, 0.5, 0.3);
  c.boxes.push_back({Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d(1.0, 1.0, 0.1)});
  const double dt = 20.0 * cfl_limit(cube), e0 = total_energy(cube);
  BackwardEulerStepper<3> stepper;
  double deepest = 0.0;
  while (cube.t < 1.0) {
    stepper.step(cube, dt);
    deepest = std::max(deepest, 0.1 - cube.x.row(2).minCoeff());
  }
  std::printf("[ implicit step ] dt %.4f s: deepest %.4f m, energy %.4f J -> %.4f J\n", dt, deepest,
              e0, total_energy(cube));
  EXPECT_LT(deepest, 0.05);
  EXPECT_LT(total_energy(cube), e0);
  EXPECT_LT(kinetic_energy(cube), 1e-3 * (e0 - total_energy(cube))) << "not at rest";
}

}  // namespace
}  // namespace gencoord::deformable
