// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The material the continuum-element tests use.

#include "gencoord/deformable/material.hpp"

namespace gencoord::deformable::testing {

/// Co-rotated continuum elements of Young's modulus E (Pa), Poisson's ratio nu and damping D
/// (Pa s), density 1000 kg/m^3.
inline Material corotated(double youngs, double nu, double damping = 0.0) {
  Material m{youngs, 1000.0, damping};
  m.poisson_ratio = nu;
  m.elasticity = Elasticity::kCorotated;
  return m;
}

}  // namespace gencoord::deformable::testing
