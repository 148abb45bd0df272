// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The true highest frequency of an object, by a dense eigensolve, for the tests of the
// library's estimates.

#include <Eigen/Eigenvalues>
#include <cmath>

#include "gencoord/deformable/mass_spring_integration.hpp"

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

}  // namespace gencoord::deformable::testing
