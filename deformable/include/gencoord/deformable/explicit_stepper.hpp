// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file explicit_stepper.hpp
/// Symplectic Euler steps of one mass-spring object that check it once: symplectic_euler_step()
/// (time_step.hpp) validates the whole object and recomputes the CFL limit at every step,
/// which costs more than the step's force sum on a large object. ExplicitStepper validates the
/// object and computes its limit, stable_step_limit() (up to 2.5 times cfl_limit() in 3D, from
/// an estimate of the highest frequency), at its first step, and again only when what they depend
/// on may have changed: the counts of nodes, springs, elements, terms and hinges, a spring that
/// broke (a new fracture event), the wave speed, the gravity, the ground, the collisions, the
/// pinned nodes, or, while plasticity is on, every step (yielding changes rest lengths; the
/// limit then follows the change of cfl_limit() below the last estimate). A fracture keeps the
/// estimate: removing a spring lowers every frequency. A value
/// the user changes in place between steps (a spring's stiffness, a node's mass) is not
/// re-checked: call invalidate() after such a change. A step whose result is not finite is
/// still refused (ObjectError, the object left unchanged), with the full validation's message
/// when that finds the cause.

#include <memory>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {

template <int Dim>
class ExplicitStepper {
 public:
  explicit ExplicitStepper(const ExplicitOptions& options = {});
  ~ExplicitStepper();
  ExplicitStepper(ExplicitStepper&&) noexcept;
  ExplicitStepper& operator=(ExplicitStepper&&) noexcept;

  /// One symplectic Euler step of dt (s), as symplectic_euler_step().
  /// \throws as symplectic_euler_step(); s is then left unchanged.
  void step(MassSpringSystem<Dim>& s, double dt);

  /// The limit the last step was checked against (s), stable_step_limit() of the object when
  /// last computed; 0 before the first step.
  double cfl_limit() const;

  /// Forgets the validation, so the next step validates the object again.
  void invalidate();

 private:
  struct Kept;
  std::unique_ptr<Kept> kept_;
};

}  // namespace gencoord::deformable
