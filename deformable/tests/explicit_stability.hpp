// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the tests of the explicit step's limits measure: the true highest frequency of an
// object by a dense eigensolve, and whether steps of a given size stay bounded or diverge.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable::testing {

/// sqrt of the largest eigenvalue of -M^-1/2 K M^-1/2, K the force's Jacobian in positions at
/// the object's state (every node free: pin nothing in an object passed here).
template <int Dim>
double dense_highest_frequency(const MassSpringSystem<Dim>& s) {
  const MassSpringIntegration<Dim> system(s);
  Linearization<MassSpringIntegration<Dim>> lin;
  system.linearize({s.t, s.x, s.v}, JacobianSource::Auto, &lin);
  const Eigen::MatrixXd k(lin.force_D_q);
  Eigen::VectorXd scale(k.rows());
  for (int n = 0; n < s.num_nodes(); ++n)
    scale.template segment<Dim>(Dim * n).setConstant(1.0 / std::sqrt(s.mass(n)));
  const Eigen::MatrixXd a = -(scale.asDiagonal() * k * scale.asDiagonal());
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (a + a.transpose()))
                       .eigenvalues()
                       .maxCoeff());
}

/// The object with every node given a random velocity (seeded): all its modes ring.
template <int Dim>
MassSpringSystem<Dim> ringing(MassSpringSystem<Dim> s, unsigned seed = 11) {
  std::mt19937 random(seed);
  std::normal_distribution<double> kick(0.0, 0.05);
  for (int n = 0; n < s.num_nodes(); ++n)
    for (int d = 0; d < Dim; ++d) s.v(d, n) = kick(random);
  return s;
}

/// The largest total energy over the starting one in the first and in the last 1000 of 3000
/// calls of step(s) (each one step).
struct EnergySwing {
  double first = 0.0, last = 0.0;
};
template <int Dim, class Step>
EnergySwing energy_swing(MassSpringSystem<Dim>& s, Step&& step) {
  const double e0 = total_energy(s);
  EnergySwing swing;
  for (int k = 0; k < 3000; ++k) {
    step(s);
    const double e = total_energy(s) / e0;
    if (k < 1000) swing.first = std::max(swing.first, e);
    if (k >= 2000) swing.last = std::max(swing.last, e);
  }
  return swing;
}

/// Whether symplectic Euler steps of dt, taken whatever the limit, make the energy grow a
/// thousandfold or the state not finite within 3000 steps.
template <int Dim>
bool diverges(MassSpringSystem<Dim> s, double dt) {
  const double e0 = total_energy(s);
  ExplicitOptions anyway;
  anyway.allow_cfl_violation = true;
  try {
    for (int k = 0; k < 3000; ++k) {
      symplectic_euler_step(s, dt, anyway);
      if (total_energy(s) > 1e3 * e0) return true;
    }
  } catch (const ObjectError&) {
    return true;
  }
  return false;
}

}  // namespace gencoord::deformable::testing
