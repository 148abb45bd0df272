// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file validate.hpp
/// Checks of meshes, materials, objects and step sizes, run where they are built or stepped
/// (make_rod, make_mass_spring, the time steps) so that bad input is refused with a typed
/// error (errors.hpp) instead of turning into NaN or out-of-range memory access.

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/material.hpp"
#include "gencoord/deformable/mesh.hpp"
#include "gencoord/deformable/quadratic_mesh.hpp"

namespace gencoord::deformable {

/// Smallest accepted element measure, relative to its longest edge to the power Dim: an
/// element flatter than this is degenerate (its lumped mass and spring stiffness vanish).
inline constexpr double kMinRelativeMeasure = 1e-10;
/// Largest accepted distance of a quadratic element's midpoint node from the middle of its
/// edge at rest, relative to the edge's length (curved elements are not supported).
inline constexpr double kMaxRelativeMidpointOffset = 1e-9;
/// Smallest accepted spacing of rod nodes, relative to the rod's length.
inline constexpr double kMinRelativeLength = 1e-12;

/// \throws MaterialError unless E > 0, rho > 0 (both finite) and damping >= 0 (finite).
void validate_material(const Material& material);

/// \throws MeshError unless the mesh has nodes and elements, every node is finite and used by
/// some element, every index is in range and distinct within its element, and every
/// element's measure exceeds kMinRelativeMeasure times its longest edge to the power Dim.
template <int Dim>
void validate_mesh(const SimplexMesh<Dim>& mesh);

/// \throws MeshError for what validate_mesh() refuses in a linear mesh (the measure being the
/// corners'), a midpoint node more than kMaxRelativeMidpointOffset times its edge's length
/// from the middle of that edge, or two elements sharing an edge with different midpoints.
template <int Dim>
void validate_mesh(const QuadraticMesh<Dim>& mesh);

/// \throws MeshError unless the surface has nodes and triangles, every node is finite and used
/// by some triangle, every index is in range and distinct within its triangle, every
/// triangle's area exceeds kMinRelativeMeasure times its longest edge squared, no two
/// triangles have the same nodes, and no edge borders more than two triangles (a sheet's
/// hinge joins two).
void validate_surface(const TriangleSurface& surface);

/// \throws ObjectError unless the object can be stepped: x, v (Dim x n), mass (n) and pinned
/// (n) agree in size; every x and v is finite; every mass is finite and positive (>= 0 for
/// a pinned node, which ignores forces); every unbroken spring joins two distinct nodes in
/// range with a finite rest length > 0 (sign-free in 1D) and finite stiffness and damping
/// >= 0; every volume term's nodes are distinct and in range, each of its edges names the
/// spring joining its two nodes, its rest measure is positive and its stiffness >= 0 (both
/// finite); every continuum element, linear or quadratic (2D and 3D only), has the same node
/// and pair checks, a positive, finite rest measure, a finite rest shape and finite mu, lambda and
/// damping time
/// >= 0; every hinge (3D only) has four distinct nodes in range, a spring index in
/// [-1, springs), a finite stiffness >= 0 and a rest angle in [-pi, pi]; gravity, the ground
/// and the wave speed (> 0) are finite; the contact settings, obstacles and surface are
/// usable; the inelastic settings are not NaN and the plastic fraction is in [0, 1].
template <int Dim>
void validate_object(const MassSpringSystem<Dim>& s);

/// \throws gencoord::StepSizeError unless dt is finite and positive.
void validate_time_step(double dt);

/// \throws ObjectError if a step of dt from time t ended at positions x or velocities v
/// (Dim x n) that are not finite (it diverged), naming the first such node.
template <int Dim>
void validate_step_result(const typename MassSpringSystem<Dim>::Points& x,
                          const typename MassSpringSystem<Dim>::Points& v, double t, double dt);

}  // namespace gencoord::deformable
