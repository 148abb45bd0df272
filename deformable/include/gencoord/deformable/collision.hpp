// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file collision.hpp
/// Contact of a mass-spring object with static obstacles (spheres and axis-aligned boxes) and
/// with its own surface, which also covers several objects in one system (append_object()):
/// self-collision and collision between objects are the same test.
///
/// Every contact is a penalty per unit mass of the node that touches, like the ground plane
/// (mass_spring_system.hpp), so that its frequency does not depend on the mesh:
///     normal:   a_n = max(0, omega^2 depth - 2 zeta omega v_n)
///     friction: a_t = -min(mu a_n / |v_t|, omega) v_t
/// with v_n and v_t the normal and tangential parts of the node's velocity relative to what it
/// touches. Friction is Coulomb's law (|a_t| = mu a_n) while the node slides faster than
/// mu a_n / omega, and a viscous drag of rate omega below that: a drag faster than omega would
/// need a smaller explicit step than the normal penalty does. Neither the damper nor friction
/// can add energy, and the undamped normal part derives from the potential
/// m omega^2 depth^2 / 2 (potential_energy() includes it).
///
/// - Obstacles are signed-distance shapes: depth is how far the node is inside (nothing
///   outside; inside a box, the nearest face pushes).
/// - The surface is a list of simplices (triangles in 3D, segments in 2D) that nodes may not
///   come closer to than `thickness`: depth = thickness - d, d the distance to the closest
///   point of the simplex, along the direction from that point to the node, tested for every
///   node of the surface against every surface simplex it is not a corner of. The reaction
///   goes to the simplex's corners with the closest point's barycentric weights, so momentum
///   is conserved. A simplex of a solid's boundary is one-sided (its orientation's normal
///   points out): a node that got behind it, over its face and less than a thickness deep,
///   is pushed back out with depth = thickness + d, up to twice the push a two-sided simplex
///   (a sheet) can give at most, m omega^2 thickness. Deeper the node is let go: the penalty
///   ends there with a jump in energy, and a longer reach let nodes sliding behind a surface
///   gain energy where it ends (measured with the cube dropped on a cube in the tests). Candidate
///   pairs come from a spatial hash over the simplices' bounding boxes, rebuilt at every force
///   evaluation (no stale hierarchy to refit as the object deforms). `thickness` must stay below
///   the distance from any surface node to the surface simplices it is not a corner of at rest:
///   enable_collisions() takes a quarter of the shortest surface edge (a right-angled grid's
///   nearest such simplex is 0.71 of an edge away). In a scene of several objects each
///   simplex keeps its object's thickness (Collisions::surface_thickness).
/// - Implicit steps (backward Euler) include each contact's stiffness and damping on the
///   diagonal blocks of the nodes involved only, the pairs changing from step to step while the
///   step matrix keeps its sparsity pattern (implicit_stepper.hpp): blocks that bound the
///   contact's coupling of a node and a simplex from above, 2 K on the node and 2 w_a K on the
///   simplex's corner a, K the penalty's block and w_a the closest point's weights.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// A fixed sphere (a circle in 2D).
template <int Dim>
struct SphereObstacle {
  Eigen::Matrix<double, Dim, 1> center = Eigen::Matrix<double, Dim, 1>::Zero();
  double radius = 1.0;  ///< (m), > 0
};

/// A fixed axis-aligned box [lower, upper] (a step, a table, a wall).
template <int Dim>
struct BoxObstacle {
  Eigen::Matrix<double, Dim, 1> lower = Eigen::Matrix<double, Dim, 1>::Zero();
  Eigen::Matrix<double, Dim, 1> upper = Eigen::Matrix<double, Dim, 1>::Ones();
};

/// The contact penalty (see the file comment).
struct ContactParams {
  double omega = 0.0;          ///< penalty frequency (1/s)
  double damping_ratio = 0.0;  ///< zeta of the normal damper
  double friction = 0.0;       ///< Coulomb coefficient mu, >= 0
  double thickness = 0.0;      ///< (m) how close nodes come to surface simplices (the thinnest's,
                               ///< when Collisions::surface_thickness gives each its own)
};

/// Everything that can be touched, and how.
template <int Dim>
struct Collisions {
  ContactParams params;
  std::vector<SphereObstacle<Dim>> spheres;
  std::vector<BoxObstacle<Dim>> boxes;
  /// Simplices of the surface (node indices, Dim each); empty: no self-collision.
  std::vector<std::array<int, Dim>> surface;
  /// Per simplex of `surface`, whether both of its sides repel (a sheet's triangles); empty:
  /// every simplex is one-sided (a solid's boundary, oriented outward).
  std::vector<char> two_sided;
  /// Per simplex of `surface`, its own thickness (m), where objects of different thickness
  /// share a scene (append_object()): each keeps the layer its own mesh allows, so a fine
  /// object does not thin a coarse one's; empty: params.thickness for every simplex.
  std::vector<double> surface_thickness;
};

/// The boundary of a mesh: the faces that belong to one element only, each oriented with its
/// normal pointing out of the mesh (in 2D, segments that run counter-clockwise around it).
std::vector<std::array<int, 3>> boundary_triangles(const SimplexMesh<3>& mesh);
std::vector<std::array<int, 2>> boundary_segments(const SimplexMesh<2>& mesh);

template <int Dim>
struct MassSpringSystem;

/// Which sides of a surface repel: the outside of a solid's boundary, or both (a sheet).
enum class Sides { kOutside, kBoth };

/// Turns on contact for `s` with its surface simplices `surface` (boundary_triangles(),
/// boundary_segments(), a sheet's triangles; empty for obstacles only), penalty frequency
/// omega = 0.5 c / L_min as with_ground() (stable with any explicit step within the CFL limit),
/// thickness a quarter of the shortest surface edge at the current positions, and the given
/// friction coefficient and damping ratio. Obstacles are added to the returned Collisions.
/// \throws ObjectError if a surface index is out of range or repeats within its simplex.
template <int Dim>
Collisions<Dim>& enable_collisions(MassSpringSystem<Dim>& s,
                                   std::vector<std::array<int, Dim>> surface, double friction,
                                   double damping_ratio, Sides sides = Sides::kOutside);

}  // namespace gencoord::deformable
