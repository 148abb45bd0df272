// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file sheet.hpp
/// Sheets in 3D (cloth, membranes, thin plates): a mass-spring object from a TriangleSurface,
/// with springs along the edges for stretching and hinges across the interior edges for
/// bending (bending.hpp). The material is in 2D units (material.hpp): rho in kg/m^2, E in N/m.
///
/// Stretching. Each triangle of area A gives rho A / 3 to each of its nodes and to the "mass
/// around" each of its edges; each edge becomes a spring with k = c^2 m / L and
/// d = D m / (rho L) (mesh_to_springs.hpp), then calibrated to E (lattice_elasticity.hpp). A
/// planar surface is calibrated in its plane's coordinates by calibrate_springs<2> (isotropic
/// where the edge directions allow: exactly on rectangle_sheet()'s alternating grid). A curved
/// surface has no common plane, so every spring gets the uniform factor 3 E A / sum k L (= 3
/// with this k): the isotropic part of the network, summed over the triangles' own planes,
/// then has the modulus E on any shape, and the mesh keeps its anisotropy.
///
/// Bending. A plate of bending stiffness D (N m; D = E_3 t^3 / (12 (1 - nu^2)) for a plate
/// of thickness t and 3D modulus E_3) under a small uniform curvature K (w = p . K p / 2 in the
/// plane) stores (D / 2) [(tr K)^2 - 2 (1 - nu_b) det K] per area. A flat hinge (bending.hpp)
/// of edge length l, wings at heights hA, hB and at sA, sB along the edge turns by
/// theta = -M : K with
///     M = (hA + hB) / 2 n n + (sA - sB) l sym(e n)
///         + ((sA^2 - sA) l^2 / hA + (sB^2 - sB) l^2 / hB) / 2 e e
/// (e along the edge, n across it towards wing A), so the hinges store (1/2) K : B : K per
/// area with B = (2 / A_h) sum_h kb_h M_h (x) M_h, the affine estimate of their bending
/// stiffness (like the springs' in lattice_elasticity.hpp), A_h = sum_h (A1 + A2) / 3 the area
/// they measure (a boundary edge has no hinge; its third of its triangle is left out, so the
/// interior is not stiffened for the boundary's sake). B's isotropic part
/// lambda I (x) I + 2 mu I_sym has the stiffness in cylindrical bending
/// lambda + 2 mu = sum_h kb_h (2 |M_h|^2 + (tr M_h)^2) / (4 A_h) and
/// nu_b = lambda / (lambda + 2 mu).
/// The discrete-shells weight kb = (D / 2) 3 l^2 / (A1 + A2) (the squared integrated mean
/// curvature (theta l)^2 over the edge's third A_e = (A1 + A2) / 3 of its two triangles) is
/// exact for umbilic bending (a sphere) but not for cylindrical bending: on an equilateral
/// mesh B is isotropic with 3 D and nu_b = -1/3, on rectangle_sheet()'s grid it is 3 D along
/// the axes and 4.5 D along the diagonals. make_sheet() therefore starts from it and calibrates
/// the hinges like the springs: first the uniform factor D / (lambda + 2 mu), then a factor
/// g_h = 1 + phi_h . z per hinge (phi_h = M_h (x) M_h normalized), the smallest change
/// (weighted by each hinge's share of B) that makes B an isotropic plate of cylindrical
/// stiffness D with the nu_b the hinges' directions allow (0 on rectangle_sheet()'s grid,
/// whose hinges never couple K_11 to K_22; -1/3 on a triangular lattice, isotropic inside
/// with the uniform factor alone). Where that takes a factor below a fifth of the uniform one,
/// and on curved surfaces (M_h taken in each hinge's own unfolded plane), the uniform factor
/// stays. A strip of width b along d then bends as a beam of stiffness b D (1 - nu_b^2)
/// (beam_stiffness_along()), a wide plate in cylindrical bending with D. The rest angles are
/// those of the surface (0 for a flat one), so a curved surface keeps its shape.
///
/// The affine estimate holds where every interior node is alike (a triangular lattice,
/// triangle_lattice_sheet()): a uniform curvature leaves each node in equilibrium. On
/// rectangle_sheet()'s alternating grid it does not: every hinge along an axis is centred on a
/// node of four edges, so those nodes move off the quadratic shape to relax the hinges, and
/// the grid bends about a third softer than B says (a cantilever strip sags 1.6 and 1.5 times
/// the Euler-Bernoulli value with 4 and 8 cells across). An irregular mesh relaxes less: a
/// triangular lattice with its nodes moved at random by up to 0.15 of the spacing sags 15% and
/// 6% more at 4 and 8 rows across, the regular lattice 5% and 1% (sheet_test.cc).

#include <Eigen/Core>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/material.hpp"
#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// Builds the sheet at rest in the surface's shape: springs calibrated to material.youngs_modulus
/// (N/m), and, for bending_stiffness D > 0 (N m), one hinge per interior edge calibrated to D;
/// wave_speed covers both (bending.hpp). Nothing pinned, no gravity, no ground.
/// \throws MeshError as validate_surface(); MaterialError as validate_material(), or unless D
///         is finite and >= 0, or if a calibrated stiffness would not be finite.
MassSpringSystem<3> make_sheet(const TriangleSurface& surface, const Material& material,
                               double bending_stiffness = 0.0);

/// Flat sheet [0, width] x [0, height] + origin in the plane z = origin.z, cut into nx x ny
/// cells of two triangles each (as rectangle_mesh()), normals along +z.
/// \throws std::invalid_argument unless nx, ny >= 1.
TriangleSurface rectangle_sheet(double width, double height, int nx, int ny,
                                const Eigen::Vector3d& origin = Eigen::Vector3d::Zero(),
                                DiagonalPattern pattern = DiagonalPattern::kAlternating);

/// Flat sheet [0, width] x [0, height] + origin in the plane z = origin.z, in ny rows of
/// triangles between rows of nodes spaced width / nx, every other row shifted by half a
/// spacing (with a node added at each end, so the short edges are straight): a triangular
/// lattice, equilateral when height / ny = sqrt(3) / 2 * width / nx, normals along +z. All its
/// interior nodes are alike (one node per lattice cell), so its hinges bend as the affine
/// estimate says (sheet.hpp); use it where bending matters.
/// \throws std::invalid_argument unless nx, ny >= 1.
TriangleSurface triangle_lattice_sheet(double width, double height, int nx, int ny,
                                       const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

/// Area of triangle t of the surface (m^2).
double triangle_area(const TriangleSurface& surface, int t);

/// The affine bending stiffness of a sheet's hinges (see the file comment), in the coordinates
/// of two orthonormal vectors u, v of its plane.
struct SheetBending {
  /// B in the basis (K_uu, K_vv, sqrt(2) K_uv) of curvatures (N m): energy per area
  /// (1/2) k^T B k for k = (K_uu, K_vv, sqrt(2) K_uv)
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  double stiffness = 0.0;      ///< lambda + 2 mu of the isotropic part (N m)
  double poisson_ratio = 0.0;  ///< nu_b = lambda / (lambda + 2 mu) of the isotropic part
  double anisotropy = 0.0;     ///< |B - B_iso| / |B_iso| (Frobenius norms)

  /// Stiffness in cylindrical bending about the axis across unit vector d = (d_u, d_v):
  /// curvature K = kappa d d, energy per area stiffness * kappa^2 / 2 (N m).
  double cylindrical_stiffness_along(const Eigen::Vector2d& d) const;
  /// Stiffness of a strip along d free to curve across it (a beam's EI per width, N m).
  double beam_stiffness_along(const Eigen::Vector2d& d) const;
};

/// The hinges of s (stiffness and active flags as they are now) over the surface `rest` it
/// was made from (its nodes the rest positions, A_h the active hinges'), measured in the plane
/// spanned by u and v (the xy-plane by default); the hinges' rest geometry is projected onto
/// it, which is exact for a sheet lying in that plane.
/// \throws std::invalid_argument unless u and v are orthonormal, or if `rest` has a node
///         count other than s's.
SheetBending sheet_bending(const MassSpringSystem<3>& s, const TriangleSurface& rest,
                           const Eigen::Vector3d& u = Eigen::Vector3d::UnitX(),
                           const Eigen::Vector3d& v = Eigen::Vector3d::UnitY());

}  // namespace gencoord::deformable
