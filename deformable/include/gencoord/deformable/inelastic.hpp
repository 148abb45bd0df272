// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file inelastic.hpp
/// Brittle fracture and plasticity of springs (thresholds in MassSpringSystem::inelastic).

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {

/// Applies the rules of InelasticParams once to every unbroken spring at the current
/// positions, recording a FractureEvent for each spring that breaks. Called by the time
/// steppers after each step; returns the number of springs broken by this call.
template <int Dim>
int apply_fracture_and_plasticity(MassSpringSystem<Dim>& s);

}  // namespace gencoord::deformable
