// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file scene.hpp
/// Several objects in one mass-spring system, so that they step together and collide
/// (collision.hpp): the system's nodes are the objects' nodes one object after the other.

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {

/// Appends `object`'s nodes (positions, velocities, masses, pinned flags), springs, hinges,
/// volume terms and contact surface to `scene`, its node indices shifted by the scene's node count,
/// which is returned (the first index of the object's nodes in the scene). The scene keeps its own
/// time, gravity, ground and inelastic settings; its wave speed becomes the faster of the two (the
/// CFL limit holds for both). Contact: the object's surface simplices and obstacles join the
/// scene's, with the smaller penalty frequency of the two when both have contact, so that the
/// limits of each still hold, and each surface simplex keeps its object's thickness
/// (Collisions::surface_thickness); a scene without contact takes the object's settings. \throws
/// ObjectError if the scene has taken steps (append objects before simulating).
template <int Dim>
int append_object(MassSpringSystem<Dim>& scene, const MassSpringSystem<Dim>& object);

}  // namespace gencoord::deformable
