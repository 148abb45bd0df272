// SPDX-License-Identifier: BSD-3-Clause
// Explicit stability limits of the maximal model: the fastest mode's rate omega_max (a
// frequency or a damping rate) and the largest stable step of symplectic Euler (h omega < 2)
// and RK4 (h omega < 2 sqrt 2).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Core>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/maximal/model.hpp"
#include "gencoord/maximal/state.hpp"
#include "gencoord/numerics/symmetric_eigenvalues.hpp"

namespace gencoord {

/// The fastest mode's rate at a state: the stiffest mode's angular frequency, where
/// omega^2 is the largest eigenvalue of the generalized eigenproblem K u = omega^2 M u with
/// K = -dF/dx (symmetrized) at (x, xdot, t), or the fastest damping rate, the largest
/// eigenvalue of D u = rate M u with D = -dF/dxdot (symmetrized: the penalty dampers and the
/// viscous penalties of velocity constraints), whichever is larger; the explicit steps'
/// limits on the imaginary and on the negative real axis are alike (2 and 2.8 for RK4).
/// Solved densely (fine for nx up to a few hundred). Returns 0 when neither is positive.
/// \throws InverseMapError as MaximalModel::force_jacobian_triplets().
template <class M>
double omega_max(const MaximalModel<M>& model, const MaximalState<M>& s) {
  Eigen::MatrixXd K_x, K_v;
  model.force_jacobians_dense(s.q, s.v, s.t, &K_x, &K_v);
  // M^-1/2 A_sym M^-1/2 for A = -K, symmetric: same eigenvalues as M^-1 A_sym
  const Eigen::VectorXd w = model.masses().cwiseSqrt().cwiseInverse();
  auto largest = [&](const Eigen::MatrixXd& K) {
    return largest_symmetric_eigenvalue(w.asDiagonal() * (-0.5 * (K + K.transpose())) *
                                        w.asDiagonal());
  };
  const double lambda = largest(K_x);
  const double rate = K_v.isZero() ? 0.0 : largest(K_v);  // no dampers: skip the solve
  return std::max({lambda > 0.0 ? std::sqrt(lambda) : 0.0, rate, 0.0});
}

/// Stability limit of h omega for symplectic Euler on an undamped oscillator.
inline constexpr double kSymplecticEulerLimit = 2.0;
/// Stability limit of h omega for classical RK4 on the imaginary axis (2 sqrt 2).
inline constexpr double kRk4Limit = 2.8284271247461903;

/// Largest stable step of symplectic Euler: safety * 2 / omega_max (infinity if omega_max = 0).
/// \param[in] omega   The stiffest mode's frequency (omega_max()).
/// \param[in] safety  Fraction of the limit, in (0, 1]; < 1 leaves room for the stiffness
///                    changing along the motion.
inline double symplectic_euler_stable_step(double omega, double safety = 0.9) {
  return omega > 0.0 ? safety * kSymplecticEulerLimit / omega
                     : std::numeric_limits<double>::infinity();
}

/// Largest stable step of RK4: safety * 2 sqrt(2) / omega_max (infinity if omega_max = 0).
inline double rk4_stable_step(double omega, double safety = 0.9) {
  return omega > 0.0 ? safety * kRk4Limit / omega : std::numeric_limits<double>::infinity();
}

/// Largest stable step of an integrator for a stiffest-mode frequency omega (omega_max()),
/// times safety: symplectic_euler_stable_step(), rk4_stable_step(), infinity for the
/// A-stable implicit ones.
/// \throws std::invalid_argument for forward Euler, unstable on an undamped oscillator at
///         every step size.
inline double stable_step(Integrator integrator, double omega, double safety = 0.9) {
  switch (integrator) {
    case Integrator::ForwardEuler:
      throw std::invalid_argument(
          "gencoord: forward Euler is unstable on the maximal model's undamped penalty modes");
    case Integrator::SymplecticEuler:
      return symplectic_euler_stable_step(omega, safety);
    case Integrator::RK4:
      return rk4_stable_step(omega, safety);
    case Integrator::BackwardEuler:
    case Integrator::Trapezoidal:
    case Integrator::ImplicitMidpoint:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace gencoord
