// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file implicit_stepper.hpp
/// Backward Euler steps of one mass-spring object that keep their linear-algebra set-up from
/// step to step: the step matrix's sparsity pattern (and, with the sparse Cholesky solver, its
/// symbolic analysis) is built once and rebuilt only when the pattern changes (a spring
/// breaks, is added or removed, or a node is pinned or released); each step writes the new
/// values into it and, with conjugate gradients, starts from the previous step's velocity
/// change (ImplicitOptions::warm_start). backward_euler_step() (time_step.hpp) is one step of
/// a fresh stepper.

#include <memory>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {

template <int Dim>
class BackwardEulerStepper {
 public:
  explicit BackwardEulerStepper(const ImplicitOptions& options = {});
  ~BackwardEulerStepper();
  BackwardEulerStepper(BackwardEulerStepper&&) noexcept;
  BackwardEulerStepper& operator=(BackwardEulerStepper&&) noexcept;

  /// One backward Euler step of dt (s), as backward_euler_step(). Any object may be passed;
  /// the kept pattern is rebuilt when `s` does not match it.
  /// \throws as backward_euler_step(); s is then left unchanged.
  ImplicitStats step(MassSpringSystem<Dim>& s, double dt);

  const ImplicitOptions& options() const;

 private:
  struct Kept;
  std::unique_ptr<Kept> kept_;
};

}  // namespace gencoord::deformable
