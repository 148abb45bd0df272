// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file material.hpp
/// Material constants of a homogeneous elastic object.
///
/// Units follow the object's dimension: for a 1D rod, rho is a linear density (kg/m) and E a
/// force (N, force per unit strain); for a 2D sheet rho is kg/m^2 and E is N/m; for a 3D
/// solid rho is kg/m^3 and E is N/m^2 (Pa). In every case c = sqrt(E / rho) is a speed (m/s).

#include <cmath>
#include <limits>

namespace gencoord::deformable {

/// How make_mass_spring() turns a mesh into forces.
enum class Elasticity {
  /// springs along the edges, calibrated to E (lattice_elasticity.hpp), with area or volume
  /// terms for a Poisson's ratio above the network's (volume_terms.hpp); they fracture and
  /// yield (inelastic.hpp)
  kSprings,
  /// co-rotated linear triangles or tetrahedra (continuum_elements.hpp): E and nu on any mesh;
  /// the edges fracture as springs do, but nothing yields
  kCorotated,
};

struct Material {
  double youngs_modulus = 1.0;  ///< E (see the units above)
  double density = 1.0;         ///< rho (see the units above)
  double damping = 0.0;         ///< D: force per unit strain rate, E's units times seconds
  /// Poisson's ratio nu of a sheet (2D, plane stress) or a solid (3D). NaN: the spring
  /// network's own, 1/3 (2D) or 1/4 (3D). Otherwise make_mass_spring() calibrates the springs
  /// to the shear modulus E / (2 (1 + nu)) and adds area or volume terms (volume_terms.hpp)
  /// for the rest of lambda; it accepts [1/3, 1) in 2D and [1/4, 1/2) in 3D. A rod ignores it.
  double poisson_ratio = std::numeric_limits<double>::quiet_NaN();
  Elasticity elasticity = Elasticity::kSprings;  ///< the model of a 2D or 3D mesh; a rod ignores it

  /// Speed of sound c = sqrt(E / rho) (m/s).
  double wave_speed() const { return std::sqrt(youngs_modulus / density); }
};

}  // namespace gencoord::deformable
