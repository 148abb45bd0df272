// SPDX-License-Identifier: BSD-3-Clause
// The parts of a symplectic Euler step that symplectic_euler_step() (time_step.hpp) and
// ExplicitStepper (explicit_stepper.hpp) share: the CFL check and the step itself. Private to
// the library.
#pragma once

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable::detail {

/// cfl_limit(s), after checking dt against it as check_cfl() does.
template <int Dim>
double checked_cfl_limit(const MassSpringSystem<Dim>& s, double dt, const ExplicitOptions& options);

/// \throws CflViolation, with the limit and what it is made of, if dt > limit unless options
///         allow it; `estimated`: the limit is stable_step_limit(s), not cfl_limit(s).
template <int Dim>
void check_cfl(const MassSpringSystem<Dim>& s, double dt, double limit,
               const ExplicitOptions& options, bool estimated = false);

/// The largest d / k of the unbroken springs and the active elements' damping time D / E: the
/// stiffness-proportional damping that gives a mode of frequency omega the ratio
/// (d / k) omega / 2.
template <int Dim>
double damping_over_stiffness(const MassSpringSystem<Dim>& s);

/// sqrt(1 + zeta^2) - zeta: the stable step of symplectic Euler on a mode with damping ratio
/// zeta, relative to the undamped 2 / omega (written so that it neither overflows nor cancels).
double damping_factor(double zeta);

/// The runtime's symplectic Euler on the object, then fracture and plasticity; the object
/// validated already. \throws ObjectError if the result is not finite (s unchanged).
template <int Dim>
void take_symplectic_euler_step(MassSpringSystem<Dim>& s, double dt);

}  // namespace gencoord::deformable::detail
