// SPDX-License-Identifier: BSD-3-Clause
// The stable explicit step from an estimate of the highest frequency (time_step.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "explicit_step.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "largest_eigenvalue.hpp"
#include "step_matrix.hpp"

namespace gencoord::deformable {

template <int Dim>
double highest_frequency(const MassSpringSystem<Dim>& s) {
  // Lanczos on M^-1/2 K M^-1/2: its Ritz value approaches the largest eigenvalue from below;
  // the margin covers what is left
  constexpr double kMargin = 1.05;
  detail::StepMatrix<Dim> stiffness;
  stiffness.build(s);
  if (stiffness.unknowns() == 0) return 0.0;
  Eigen::VectorXd masses;
  stiffness.assemble_stiffness(s, s.x, &masses);
  const Eigen::VectorXd scale = masses.cwiseSqrt().cwiseInverse();
  const Eigen::SparseMatrix<double> a =
      scale.asDiagonal() * stiffness.matrix() * scale.asDiagonal();
  return kMargin * std::sqrt(std::max(0.0, detail::largest_eigenvalue(a)));
}

template <int Dim>
double stable_step_limit(const MassSpringSystem<Dim>& s) {
  const double omega = highest_frequency(s);
  // a node that touches the ground or an obstacle adds the penalty's omega_p^2 at most
  double omega_p = 0.0, zeta_p = 0.0;
  if (s.ground) {
    omega_p = s.ground->omega;
    zeta_p = s.ground->damping_ratio;
  }
  if (s.collisions) {
    omega_p = std::max(omega_p, s.collisions->params.omega);
    zeta_p = std::max(zeta_p, s.collisions->params.damping_ratio);
  }
  const double zeta = std::max(detail::damping_over_stiffness(s) * omega / 2.0, zeta_p);
  const double combined = std::hypot(omega, omega_p);
  const double estimated = combined > 0.0 ? 2.0 / combined * detail::damping_factor(zeta)
                                          : std::numeric_limits<double>::infinity();
  return std::max(cfl_limit(s), estimated);
}

#define GENCOORD_INSTANTIATE(D)                                     \
  template double highest_frequency<D>(const MassSpringSystem<D>&); \
  template double stable_step_limit<D>(const MassSpringSystem<D>&);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
