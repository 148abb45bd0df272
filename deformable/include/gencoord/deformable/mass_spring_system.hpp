// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file mass_spring_system.hpp
/// The state and parameters of a deformable mass-spring object in Dim = 1, 2 or 3 dimensions:
/// lumped node masses connected by springs (springs.hpp), with pinned nodes, gravity, a ground
/// plane with penalty contact, contact with obstacles and between surfaces (collision.hpp),
/// and optional fracture and plasticity.

#include <Eigen/Core>
#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "gencoord/deformable/collision.hpp"
#include "gencoord/deformable/continuum_elements.hpp"
#include "gencoord/deformable/quadratic_elements.hpp"
#include "gencoord/deformable/springs.hpp"
#include "gencoord/deformable/volume_terms.hpp"

namespace gencoord::deformable {

/// One spring of the graph, between nodes i and j.
struct Spring {
  int i = 0;
  int j = 0;
  SpringParams params;
  bool broken = false;  ///< a broken spring exerts no force and is skipped everywhere
};

/// A bending hinge of a sheet in 3D (bending.hpp): the edge nodes[0]-nodes[1] shared by the
/// triangles (nodes[0], nodes[1], nodes[2]) and (nodes[1], nodes[0], nodes[3]), with the energy
/// stiffness (theta - rest_angle)^2 in their dihedral angle theta.
struct Hinge {
  std::array<int, 4> nodes{};  ///< edge start, edge end, and the two triangles' third nodes
  int spring = -1;  ///< the edge's spring in MassSpringSystem::springs (-1: none); broken: inert
  double rest_angle = 0.0;  ///< theta0 (rad), in [-pi, pi]; 0 is flat
  double stiffness = 0.0;   ///< kb (J/rad^2 = N m)
};

/// Ground: the half space x[Dim - 1] < height (y in 2D, z in 3D) pushes nodes back with a
/// penalty force per unit mass, so the contact response does not depend on the mesh:
///     f_up = m (omega^2 * depth - 2 zeta omega v_up), clamped at >= 0 (never pulls).
/// For explicit stability keep omega <= c / L_min (the default in with_ground() is half that).
struct GroundPlane {
  double height = 0.0;         ///< (m)
  double omega = 0.0;          ///< penalty frequency (1/s)
  double damping_ratio = 0.0;  ///< zeta; 0 is a perfectly elastic bounce
};

/// Fracture and plasticity thresholds; infinity turns an effect off.
/// After every step, for every unbroken spring with strain e = (l - L) / L:
///  - fracture: if e > fracture_strain the spring breaks (removed for good);
///  - plasticity: otherwise, if |e| > yield_strain, L <- L + plastic_fraction * (l - L).
/// Example (the documented permanent set): L = 1 held at l = 1.5 with yield 0.1 and fraction
/// 0.5 gives L = 1.25 after one step, 1.375 after the second, then strain 0.0909 < 0.1 stops
/// it: released, the spring rests at 1.375, a permanent set of 0.375.
struct InelasticParams {
  double fracture_strain = std::numeric_limits<double>::infinity();
  double yield_strain = std::numeric_limits<double>::infinity();
  double plastic_fraction = 0.0;  ///< in [0, 1]
};

/// A spring that broke: when, which, and at which strain.
struct FractureEvent {
  double t = 0.0;  ///< simulation time after the step that broke it (s)
  long step = 0;   ///< index of that step, counting from 1
  int spring = 0;  ///< index into MassSpringSystem::springs
  double strain = 0.0;
};

template <int Dim>
struct MassSpringSystem {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Points = Eigen::Matrix<double, Dim, Eigen::Dynamic>;

  Points x;                  ///< node positions (m), Dim x n
  Points v;                  ///< node velocities (m/s), Dim x n
  Eigen::VectorXd mass;      ///< lumped node masses (kg), n
  std::vector<char> pinned;  ///< n flags; a pinned node moves with its own v, ignoring forces
  std::vector<Spring> springs;
  /// area (2D) or volume (3D) terms of the elements (volume_terms.hpp); none in 1D
  std::vector<VolumeTerm<Dim>> volume_terms;
  /// continuum elements (continuum_elements.hpp); none in 1D
  std::vector<ContinuumElement<Dim>> elements;
  /// quadratic continuum elements (quadratic_elements.hpp); none in 1D
  std::vector<QuadraticElement<Dim>> quadratic_elements;
  std::vector<Hinge> hinges;  ///< bending hinges; only in 3D (sheet.hpp)
  Vec gravity = Vec::Zero();  ///< acceleration (m/s^2)
  std::optional<GroundPlane> ground;
  std::optional<Collisions<Dim>> collisions;  ///< obstacles and self-contact (collision.hpp)
  InelasticParams inelastic;
  std::vector<FractureEvent> fractures;  ///< appended to by the time steppers
  /// the fastest spring's sqrt(k L / m) (m/s; c for a rod), for the CFL limit; raised for the
  /// volume terms (add_volume_terms()) and, for a sheet with hinges, so that it also covers
  /// their frequency (bending.hpp); for continuum elements omega_max L_min / 2
  /// (make_mass_spring())
  double wave_speed = 1.0;
  double t = 0.0;  ///< time (s)
  long steps = 0;  ///< steps taken

  int num_nodes() const { return static_cast<int>(x.cols()); }
  int num_unbroken_springs() const;
};

/// Adds the total force (springs, dampers, volume terms, continuum elements, hinges, gravity,
/// ground, contact) on every node to f (N), Dim x n.
template <int Dim>
void accumulate_forces(const MassSpringSystem<Dim>& s,
                       Eigen::Matrix<double, Dim, Eigen::Dynamic>& f);

/// The same at positions x and velocities v (Dim x n each) instead of s.x and s.v.
template <int Dim>
void accumulate_forces(const MassSpringSystem<Dim>& s,
                       const typename MassSpringSystem<Dim>::Points& x,
                       const typename MassSpringSystem<Dim>::Points& v,
                       Eigen::Matrix<double, Dim, Eigen::Dynamic>& f);

/// Kinetic energy sum m v^2 / 2 over the unpinned nodes (J).
template <int Dim>
double kinetic_energy(const MassSpringSystem<Dim>& s);

/// Elastic (springs, volume terms, continuum elements, hinges, ground and contact penalties) plus
/// gravitational potential energy (J).
template <int Dim>
double potential_energy(const MassSpringSystem<Dim>& s);

template <int Dim>
double total_energy(const MassSpringSystem<Dim>& s) {
  return kinetic_energy(s) + potential_energy(s);
}

/// Shortest rest length among unbroken springs (m); infinity when there is none.
template <int Dim>
double min_rest_length(const MassSpringSystem<Dim>& s);

/// Adds a ground at `height` with omega = 0.5 c / L_min (stable with any explicit step that
/// satisfies the CFL limit) and the given damping ratio.
template <int Dim>
void with_ground(MassSpringSystem<Dim>& s, double height, double damping_ratio);

}  // namespace gencoord::deformable
