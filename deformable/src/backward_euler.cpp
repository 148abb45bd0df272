// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler of a mass-spring object: one step of a fresh stepper.
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {

template <int Dim>
ImplicitStats backward_euler_step(MassSpringSystem<Dim>& s, double dt,
                                  const ImplicitOptions& options) {
  return BackwardEulerStepper<Dim>(options).step(s, dt);
}

template ImplicitStats backward_euler_step<1>(MassSpringSystem<1>&, double, const ImplicitOptions&);
template ImplicitStats backward_euler_step<2>(MassSpringSystem<2>&, double, const ImplicitOptions&);
template ImplicitStats backward_euler_step<3>(MassSpringSystem<3>&, double, const ImplicitOptions&);

}  // namespace gencoord::deformable
