// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file mesh_to_springs.hpp
/// Mass-spring object from a simplex mesh and a material, with a mesh-independent wave speed.
///
/// Each element of measure A (area or volume) gives rho A / (Dim + 1) to each of its nodes
/// and rho A / (number of its edges) to the "mass around" each of its edges. A spring of rest
/// length L and mass around it m gets
///     k = c^2 m / L,   d = D m / (rho L),   c = sqrt(E / rho),
/// i.e. the 1D rod's k = E and d = D scaled by m / (rho L), so that one spring's own wave speed
/// sqrt(k L / m) equals c everywhere, so that the mesh does not show in the material.
/// The springs are then calibrated to the material's E (lattice_elasticity.hpp); with a
/// Poisson's ratio (Material::poisson_ratio) to the network that has its shear modulus, and
/// every element gets an area or volume term for the rest of lambda (volume_terms.hpp).
///
/// With Material::elasticity = Elasticity::kCorotated the elements carry the material instead
/// (continuum_elements.hpp): every element becomes a co-rotated linear triangle or tetrahedron
/// with the material's E, nu and damping, the springs along the edges keep their rest lengths
/// but have no stiffness or damping, and the wave speed is set from the elements' highest
/// frequency (continuum_highest_frequency()) so that cfl_limit() is 2 / omega_max.

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/material.hpp"
#include "gencoord/deformable/mesh.hpp"
#include "gencoord/deformable/quadratic_mesh.hpp"

namespace gencoord::deformable {

/// Builds the object at rest in the mesh's rest shape. Nothing pinned, no gravity, no ground.
/// \throws MeshError, MaterialError (validate.hpp; lame_split() for the Poisson's ratio of the
///         springs, continuum_lame() for the elements').
template <int Dim>
MassSpringSystem<Dim> make_mass_spring(const SimplexMesh<Dim>& mesh, const Material& material);

/// Builds the object of quadratic continuum elements (quadratic_elements.hpp) of `material` on
/// a quadratic mesh (quadratic_mesh()), at rest. Each element's mass is lumped by the
/// diagonal of its consistent mass matrix scaled to the element's mass (row sums would give
/// a quadratic tetrahedron's corners negative masses): a triangle gives 1/19 of it to each
/// corner and 16/57 to each midpoint, a tetrahedron 1/36 and 4/27. Every node pair of an
/// element is a spring without stiffness; the wave speed is set from the elements' highest
/// frequency so that cfl_limit() is 2 / omega_max, as for linear elements.
/// \throws MeshError (validate_mesh()), MaterialError (validate_material(), continuum_lame(),
///         or a material whose elasticity is not Elasticity::kCorotated).
template <int Dim>
MassSpringSystem<Dim> make_mass_spring(const QuadraticMesh<Dim>& mesh, const Material& material);

/// Pins every node whose coordinate `axis` is within `tolerance` of `value`; returns how many.
template <int Dim>
int pin_nodes_where(MassSpringSystem<Dim>& s, int axis, double value, double tolerance = 1e-9);

}  // namespace gencoord::deformable
