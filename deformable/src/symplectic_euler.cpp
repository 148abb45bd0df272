// SPDX-License-Identifier: BSD-3-Clause
// Symplectic Euler of a mass-spring object: the runtime's, with the CFL limit enforced.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "explicit_step.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable {

namespace detail {

template <int Dim>
double damping_over_stiffness(const MassSpringSystem<Dim>& s) {
  double d_over_k = 0.0;
  for (const Spring& sp : s.springs) {
    if (!sp.broken && sp.params.stiffness > 0.0) {
      d_over_k = std::max(d_over_k, sp.params.damping / sp.params.stiffness);
    }
  }
  // continuum elements: stiffness-proportional damping with the same ratio beta = D / E
  if constexpr (Dim >= 2) {
    for (const ContinuumElement<Dim>& element : s.elements) {
      if (continuum_element_active(s, element)) d_over_k = std::max(d_over_k, element.damping_time);
    }
    for (const QuadraticElement<Dim>& element : s.quadratic_elements) {
      if (quadratic_element_active(s, element)) d_over_k = std::max(d_over_k, element.damping_time);
    }
  }
  return d_over_k;
}

double damping_factor(double zeta) { return 1.0 / (std::hypot(1.0, zeta) + zeta); }

}  // namespace detail

template <int Dim>
double damping_ratio_at_cfl(const MassSpringSystem<Dim>& s) {
  // the stiffest mode (wavelength 2 L_min) has omega = 2 c / L_min and, since every spring has
  // the same d / k = D / E, damping ratio zeta = (d / k) omega / 2
  return detail::damping_over_stiffness(s) * s.wave_speed / min_rest_length(s);
}

namespace {
using detail::damping_factor;

// undamped: L_min / c_s (c_s: the fastest spring's own speed). Damping evaluated explicitly shrinks
// it by sqrt(1 + zeta^2) - zeta (the stability bound of symplectic Euler on a damped mode); the
// factor is 1 without damping
template <int Dim>
double cfl_limit_at(const MassSpringSystem<Dim>& s, double zeta) {
  return min_rest_length(s) / s.wave_speed * damping_factor(zeta);
}
}  // namespace

template <int Dim>
double cfl_limit(const MassSpringSystem<Dim>& s) {
  return cfl_limit_at(s, damping_ratio_at_cfl(s));
}

namespace detail {

template <int Dim>
double checked_cfl_limit(const MassSpringSystem<Dim>& s, double dt,
                         const ExplicitOptions& options) {
  const double zeta = damping_ratio_at_cfl(s);
  const double limit = cfl_limit_at(s, zeta);
  check_cfl(s, dt, limit, options);
  return limit;
}

template <int Dim>
void check_cfl(const MassSpringSystem<Dim>& s, double dt, double limit,
               const ExplicitOptions& options, bool estimated) {
  if (dt <= limit || options.allow_cfl_violation) return;
  static const char kWhatToDo[] =
      "take a smaller step, use backward Euler, or set ExplicitOptions::allow_cfl_violation";
  char message[512];
  if (estimated) {
    std::snprintf(message, sizeof message,
                  "explicit step dt = %.6g s exceeds the stable step %.6g s (the larger of "
                  "L_min / c_s and 2 / omega_max, omega_max estimated, with damping); %s",
                  dt, limit, kWhatToDo);
  } else {
    std::snprintf(message, sizeof message,
                  "explicit step dt = %.6g s exceeds the CFL limit %.6g s = L_min / c_s "
                  "(L_min = %.6g m, fastest spring c_s = %.6g m/s) times %.6g for damping; %s",
                  dt, limit, min_rest_length(s), s.wave_speed,
                  damping_factor(damping_ratio_at_cfl(s)), kWhatToDo);
  }
  throw CflViolation(message);
}

template <int Dim>
void take_symplectic_euler_step(MassSpringSystem<Dim>& s, double dt) {
  // the runtime's symplectic Euler on MassSpringIntegration (gencoord/integrate/), written out
  // to the same operations in one pass, without the generic state's copies:
  // v1 = v + dt f / m, x1 = x + dt v1; a pinned node keeps its v and moves with it
  typename MassSpringIntegration<Dim>::State end{s.t + dt, s.x, s.v};
  typename MassSpringSystem<Dim>::Points f =
      MassSpringSystem<Dim>::Points::Zero(Dim, s.num_nodes());
  accumulate_forces(s, s.x, s.v, f);
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (!s.pinned[n]) end.v.col(n) += dt * (f.col(n) / s.mass(n));
    end.q.col(n) += dt * end.v.col(n);
  }
  finish_step<Dim>(std::move(end), dt, &s);
}

}  // namespace detail

template <int Dim>
void symplectic_euler_step(MassSpringSystem<Dim>& s, double dt, const ExplicitOptions& options) {
  validate_time_step(dt);
  validate_object(s);
  detail::checked_cfl_limit(s, dt, options);
  detail::take_symplectic_euler_step(s, dt);
}

template double damping_ratio_at_cfl<1>(const MassSpringSystem<1>&);
template double damping_ratio_at_cfl<2>(const MassSpringSystem<2>&);
template double damping_ratio_at_cfl<3>(const MassSpringSystem<3>&);
template double cfl_limit<1>(const MassSpringSystem<1>&);
template double cfl_limit<2>(const MassSpringSystem<2>&);
template double cfl_limit<3>(const MassSpringSystem<3>&);
#define GENCOORD_INSTANTIATE(D)                                                    \
  template double detail::damping_over_stiffness<D>(const MassSpringSystem<D>&);   \
  template double detail::checked_cfl_limit<D>(const MassSpringSystem<D>&, double, \
                                               const ExplicitOptions&);            \
  template void detail::check_cfl<D>(const MassSpringSystem<D>&, double, double,   \
                                     const ExplicitOptions&, bool);                \
  template void detail::take_symplectic_euler_step<D>(MassSpringSystem<D>&, double);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE
template void symplectic_euler_step<1>(MassSpringSystem<1>&, double, const ExplicitOptions&);
template void symplectic_euler_step<2>(MassSpringSystem<2>&, double, const ExplicitOptions&);
template void symplectic_euler_step<3>(MassSpringSystem<3>&, double, const ExplicitOptions&);

}  // namespace gencoord::deformable
