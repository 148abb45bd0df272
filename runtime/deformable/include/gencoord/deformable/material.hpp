#pragma once
/// \file material.hpp
/// Material constants of a homogeneous elastic object.
///
/// Units follow the object's dimension: for a 1D rod, rho is a linear density (kg/m) and E a
/// force (N, force per unit strain); for a 2D sheet rho is kg/m^2 and E is N/m; for a 3D
/// solid rho is kg/m^3 and E is N/m^2 (Pa). In every case c = sqrt(E / rho) is a speed (m/s).

#include <cmath>

namespace gencoord::deformable {

struct Material {
  double youngs_modulus = 1.0;  ///< E (see the units above)
  double density = 1.0;         ///< rho (see the units above)
  double damping = 0.0;         ///< D: force per unit strain rate, E's units times seconds

  /// Speed of sound c = sqrt(E / rho) (m/s).
  double wave_speed() const { return std::sqrt(youngs_modulus / density); }
};

}  // namespace gencoord::deformable
