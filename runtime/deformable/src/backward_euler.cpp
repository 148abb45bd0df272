// Backward Euler of a mass-spring object: the runtime's backward Euler, linearized.
#include "gencoord/integrate/backward_euler.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable {

template <int Dim>
ImplicitStats backward_euler_step(MassSpringSystem<Dim>& s, double dt,
                                  const ImplicitOptions& options) {
  validate_time_step(dt);
  validate_object(s);
  const MassSpringIntegration<Dim> system(s, options);
  NewtonOptions newton;
  newton.linearized = true;
  finish_step<Dim>(gencoord::backward_euler_step(system, system.state(), dt, newton), dt, &s);
  return system.last_solve();
}

template ImplicitStats backward_euler_step<1>(MassSpringSystem<1>&, double, const ImplicitOptions&);
template ImplicitStats backward_euler_step<2>(MassSpringSystem<2>&, double, const ImplicitOptions&);
template ImplicitStats backward_euler_step<3>(MassSpringSystem<3>&, double, const ImplicitOptions&);

}  // namespace gencoord::deformable
