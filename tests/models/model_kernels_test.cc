// SPDX-License-Identifier: BSD-3-Clause
// Checks every generated model's kernels against each other and against finite differences:
// Mt symmetric positive definite, J = dX/dq, xdot = J v + X_t, gamma = d(xdot)/dt at
// qddot = 0, qddot solves Mt qddot = Ft + Fi, energy and momenta match their definitions.
#include <limits>
#include <random>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <gtest/gtest.h>

#include "all_models.hpp"
#include "model_view.hpp"

namespace gencoord::testing {
namespace {

// Every check is a plain function of a ModelView (model_view.hpp), compiled once for all the
// models of the type list.
using Vec = ModelView::Vec;
using Mat = ModelView::Mat;

constexpr int kStates = 50;

void check_mass_matrix(const ModelView& m) {
  std::mt19937 rng(1);
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    const Mat Mt = m.mass_matrix(s.q, s.t);
    EXPECT_LT((Mt - Mt.transpose()).norm(), 1e-14 * Mt.norm()) << "state " << k;
    Eigen::SelfAdjointEigenSolver<Mat> eigen(Mt);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 1e-9 * eigen.eigenvalues().maxCoeff())
        << "Mt is not positive definite at state " << k << ", q = " << s.q.transpose();
  }
}

void check_jacobian(const ModelView& m) {
  std::mt19937 rng(2);
  const double h = 1e-6;
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    const Mat J = m.jacobian(s.q, s.t);
    for (int c = 0; c < m.nq; ++c) {
      Vec plus = s.q, minus = s.q;
      plus[c] += h;
      minus[c] -= h;
      const Vec column = (m.positions(plus, s.t) - m.positions(minus, s.t)) / (2 * h);
      for (int r = 0; r < m.nx; ++r) {
        EXPECT_NEAR(J(r, c), column[r], 1e-7 * (1 + std::abs(column[r])))
            << "FD mismatch at (" << r << ", " << c << "), state " << k;
      }
    }
  }
}

void check_velocities_and_bias(const ModelView& m) {
  std::mt19937 rng(3);
  const double h = 1e-6;  // small: the Kapitza pivot moves at 100 rad/s
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    // along the path q(t + e) = q + e v (qddot = 0), dx/dt = xdot and d(xdot)/dt = gamma
    const Vec q_plus = s.q + h * s.v, q_minus = s.q - h * s.v;
    const Vec xdot_fd = (m.positions(q_plus, s.t + h) - m.positions(q_minus, s.t - h)) / (2 * h);
    const Vec gamma_fd =
        (m.velocities(q_plus, s.v, s.t + h) - m.velocities(q_minus, s.v, s.t - h)) / (2 * h);
    const Vec xdot = m.velocities(s.q, s.v, s.t);
    const Vec gamma = m.bias_acceleration(s.q, s.v, s.t);
    for (int r = 0; r < m.nx; ++r) {
      EXPECT_NEAR(xdot[r], xdot_fd[r], 1e-7 * (1 + std::abs(xdot[r]))) << "xdot(" << r << ")";
      EXPECT_NEAR(gamma[r], gamma_fd[r], 1e-6 * (1 + std::abs(gamma[r])))
          << "gamma(" << r << "), state " << k;
    }
  }
}

void check_kernels_agree(const ModelView& m) {
  std::mt19937 rng(4);
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    const Mat Mt = m.mass_matrix(s.q, s.t);
    const Vec f = m.forces(s.q, s.v, s.t);
    Mat Mt2;
    Vec f2;
    m.dynamics(s.q, s.v, s.t, &Mt2, &f2);
    EXPECT_LT((Mt - Mt2).norm(), 1e-13 * (1 + Mt.norm()));
    EXPECT_LT((f - f2).norm(), 1e-13 * (1 + f.norm()));
    EXPECT_LT((f - m.applied_forces(s.q, s.v, s.t) - m.inertial_forces(s.q, s.v, s.t)).norm(),
              1e-12 * (1 + f.norm()));
    // qddot solves Mt qddot = Ft + Fi, both the generated and the runtime's checked version
    const Vec a = m.qddot(s.q, s.v, s.t);
    EXPECT_LT((Mt * a - f).norm(), 1e-10 * (1 + f.norm()));
    if (m.constrained_acceleration) {
      // the runtime's is the constrained acceleration: Mt a = f + A^T lambda, A a = -gamma
      Vec lambda;
      const Vec constrained = m.constrained_acceleration(s.q, s.v, s.t, &lambda);
      const Mat A = m.constraint_jacobian(s.q, s.t);
      const Vec constraint_force = A.transpose() * lambda;
      EXPECT_LT((Mt * constrained - f - constraint_force).norm(),
                1e-10 * (1 + f.norm() + constraint_force.norm()));
      const Vec gamma = m.constraint_bias(s.q, s.v, s.t);
      EXPECT_LT((A * constrained + gamma).norm(),
                1e-10 * (1 + gamma.norm() + A.norm() * constrained.norm()));
    } else {
      EXPECT_LT((m.runtime_acceleration(s.q, s.v, s.t) - a).norm(), 1e-10 * (1 + a.norm()));
    }
    // Mt = J^T M J and T = 1/2 v^T Mt v when X has no explicit time dependence; in general
    // T = 1/2 xdot^T M xdot with xdot from velocities()
    const Mat J = m.jacobian(s.q, s.t);
    const Vec masses = m.particle_masses();
    Vec mass_diagonal(m.nx);
    for (int i = 0; i < m.num_particles; ++i) {
      mass_diagonal.segment(m.dim * i, m.dim).setConstant(masses[i]);
    }
    EXPECT_LT((J.transpose() * mass_diagonal.asDiagonal() * J - Mt).norm(), 1e-12 * Mt.norm());
    const Vec xdot = m.velocities(s.q, s.v, s.t);
    const double kinetic = 0.5 * xdot.dot(mass_diagonal.asDiagonal() * xdot);
    EXPECT_NEAR(m.kinetic_energy(s.q, s.v, s.t), kinetic, 1e-12 * (1 + kinetic));
    EXPECT_NEAR(m.energy(s.q, s.v, s.t), kinetic + m.potential_energy(s.q, s.t),
                1e-12 * (1 + std::abs(kinetic)));
    // momenta from their definitions
    const Vec x = m.positions(s.q, s.t);
    Vec momentum = Vec::Zero(m.dim);
    Eigen::Vector3d angular = Eigen::Vector3d::Zero();
    for (int i = 0; i < m.num_particles; ++i) {
      momentum += masses[i] * xdot.segment(m.dim * i, m.dim);
      Eigen::Vector3d xi = Eigen::Vector3d::Zero(), vi = Eigen::Vector3d::Zero();
      xi.head(m.dim) = x.segment(m.dim * i, m.dim);
      vi.head(m.dim) = xdot.segment(m.dim * i, m.dim);
      angular += masses[i] * xi.cross(vi);
    }
    EXPECT_LT((m.linear_momentum(s.q, s.v, s.t) - momentum).norm(), 1e-12 * (1 + momentum.norm()));
    const Vec L = m.angular_momentum(s.q, s.v, s.t);
    if (m.dim == 3) {
      EXPECT_LT((L - angular).norm(), 1e-12 * (1 + angular.norm()));
    } else {
      EXPECT_NEAR(L[0], angular.z(), 1e-12 * (1 + angular.norm()));
    }
  }
}

void check_solve(const ModelView& m) {
  // the generated LDL^T (written out for small nq, loops beyond) on random SPD matrices
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int k = 0; k < kStates; ++k) {
    Mat B(m.nq, m.nq);
    Vec f(m.nq);
    for (int i = 0; i < m.nq; ++i) {
      f(i) = uniform(rng);
      for (int j = 0; j < m.nq; ++j) B(i, j) = uniform(rng);
    }
    const Mat A = B * B.transpose() + 0.1 * Mat::Identity(m.nq, m.nq);
    Vec a;
    ASSERT_TRUE(m.solve(A, f, &a));
    const Vec expected = Eigen::LLT<Mat>(A).solve(f);
    EXPECT_LT((a - expected).norm(), 1e-10 * (1 + expected.norm()));
    Mat indefinite = A;
    indefinite(m.nq - 1, m.nq - 1) = -1.0;
    EXPECT_FALSE(m.solve(indefinite, f, &a));
    Mat not_a_number = A;
    not_a_number(0, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(m.solve(not_a_number, f, &a));
  }
}

void check_potential_gradient(const ModelView& m) {
  // At v = 0 the applied forces of a model whose forces without a potential all vanish at
  // rest (the generator's forces_have_potential) are Ft = -dV/dq.
  if (!m.forces_have_potential) {
    GTEST_SKIP() << m.name << " has a force without a potential that acts at rest";
  }
  std::mt19937 rng(5);
  const double h = 1e-6;
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    const Vec force = m.applied_forces(s.q, Vec::Zero(m.nq), s.t);
    for (int c = 0; c < m.nq; ++c) {
      Vec plus = s.q, minus = s.q;
      plus[c] += h;
      minus[c] -= h;
      const double gradient =
          (m.potential_energy(plus, s.t) - m.potential_energy(minus, s.t)) / (2 * h);
      EXPECT_NEAR(force[c], -gradient, 1e-6 * (1 + std::abs(gradient)))
          << "coordinate " << m.coordinate_names[c] << ", state " << k;
    }
  }
}

void check_inverse_dynamics(const ModelView& m) {
  std::mt19937 rng(7);
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    const Vec a = m.qddot(s.q, s.v, s.t);
    const Vec r = m.inverse_dynamics(s.q, s.v, a, s.t);
    const double scale = 1 + m.forces(s.q, s.v, s.t).norm();
    EXPECT_LT(r.norm(), 1e-12 * scale) << "state " << k;
  }
}

void check_residual_jacobians(const ModelView& m) {
  if (!m.residual_jacobians) {
    GTEST_SKIP() << m.name << " has no residual_jacobians (kinematic constraints)";
  }
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> accel(-2.0, 2.0);
  const double h = 1e-6;
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    Vec a(m.nq);
    for (int i = 0; i < m.nq; ++i) a[i] = accel(rng);
    Mat r_D_q, r_D_v;
    m.residual_jacobians(s.q, s.v, a, s.t, &r_D_q, &r_D_v);
    for (int c = 0; c < m.nq; ++c) {
      Vec plus = s.q, minus = s.q;
      plus[c] += h;
      minus[c] -= h;
      const Vec dq =
          (m.inverse_dynamics(plus, s.v, a, s.t) - m.inverse_dynamics(minus, s.v, a, s.t)) /
          (2 * h);
      plus = s.v;
      minus = s.v;
      plus[c] += h;
      minus[c] -= h;
      const Vec dv =
          (m.inverse_dynamics(s.q, plus, a, s.t) - m.inverse_dynamics(s.q, minus, a, s.t)) /
          (2 * h);
      for (int r = 0; r < m.nq; ++r) {
        EXPECT_NEAR(r_D_q(r, c), dq[r], 1e-6 * (1 + std::abs(dq[r])))
            << "dr/dq mismatch at (" << r << ", " << c << "), state " << k;
        EXPECT_NEAR(r_D_v(r, c), dv[r], 1e-6 * (1 + std::abs(dv[r])))
            << "dr/dv mismatch at (" << r << ", " << c << "), state " << k;
      }
    }
  }
}

void check_declared_constraints(const ModelView& m) {
  // A constraint must hold on X(q, t) for every parameter value, not only the defaults: a
  // rod of literal length 1 over a pendulum of length l = 1 would pass at the defaults.
  if (!m.constraint_violations) GTEST_SKIP() << m.name << " has no Maximal model";
  if (m.num_maximal_constraints == 0) GTEST_SKIP() << m.name << " declares no constraints";
  std::mt19937 rng(9);
  for (int k = 0; k < kStates; ++k) {
    const auto s = m.random_state(rng);
    // parameters scaled one by one can make an inertia tensor no body has (the triangle
    // inequality broken), which no point masses stand for: drawn again
    m.sample_params(rng);
    for (int tries = 0; tries < 10000 && !m.positions(s.q, s.t).allFinite(); ++tries)
      m.sample_params(rng);
    const Vec x = m.positions(s.q, s.t);
    ASSERT_TRUE(x.allFinite()) << m.name << ": no physical parameters drawn";
    const Vec violations = m.constraint_violations(x, s.t);
    const double scale = 1 + x.cwiseAbs().maxCoeff();
    for (int c = 0; c < m.num_declared_constraints; ++c) {  // kinematic rows need not hold
      EXPECT_LT(std::abs(violations[c]), 1e-12 * scale)
          << m.maximal_constraint_names[c] << " at state " << k;
    }
  }
}

template <class M>
class ModelKernels : public ::testing::Test {};
TYPED_TEST_SUITE(ModelKernels, AllModels, ModelNames);

TYPED_TEST(ModelKernels, MassMatrixIsSymmetricPositiveDefinite) {
  check_mass_matrix(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, JacobianMatchesCentralDifferencesOfPositions) {
  check_jacobian(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, VelocitiesAndBiasAccelerationMatchTimeDerivatives) {
  check_velocities_and_bias(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, KernelsAgreeWithEachOther) { check_kernels_agree(view_of<TypeParam>()); }

TYPED_TEST(ModelKernels, SolveAgreesWithEigenAndRefusesIndefiniteMatrices) {
  check_solve(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, PotentialEnergyGradientIsTheConservativeForce) {
  check_potential_gradient(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, InverseDynamicsVanishesAtTheForwardDynamics) {
  check_inverse_dynamics(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, ResidualJacobiansMatchCentralDifferences) {
  check_residual_jacobians(view_of<TypeParam>());
}

TYPED_TEST(ModelKernels, DeclaredConstraintsHoldForSampledParameters) {
  check_declared_constraints(view_of<TypeParam>());
}

}  // namespace
}  // namespace gencoord::testing
