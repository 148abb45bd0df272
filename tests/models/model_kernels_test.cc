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
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "random_states.hpp"

namespace gencoord::testing {
namespace {

constexpr int kStates = 50;

template <class M>
class ModelKernels : public ::testing::Test {};
TYPED_TEST_SUITE(ModelKernels, AllModels, ModelNames);

TYPED_TEST(ModelKernels, MassMatrixIsSymmetricPositiveDefinite) {
  using M = TypeParam;
  std::mt19937 rng(1);
  const typename M::Params p;
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    const QMat<M> Mt = M::mass_matrix(s.q, s.t, p);
    EXPECT_LT((Mt - Mt.transpose()).norm(), 1e-14 * Mt.norm()) << "state " << k;
    Eigen::SelfAdjointEigenSolver<QMat<M>> eigen(Mt);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 1e-9 * eigen.eigenvalues().maxCoeff())
        << "Mt is not positive definite at state " << k << ", q = " << s.q.transpose();
  }
}

TYPED_TEST(ModelKernels, JacobianMatchesCentralDifferencesOfPositions) {
  using M = TypeParam;
  std::mt19937 rng(2);
  const typename M::Params p;
  const double h = 1e-6;
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    const XJac<M> J = M::jacobian(s.q, s.t, p);
    for (int c = 0; c < M::nq; ++c) {
      QVec<M> plus = s.q, minus = s.q;
      plus[c] += h;
      minus[c] -= h;
      const XVec<M> column = (M::positions(plus, s.t, p) - M::positions(minus, s.t, p)) / (2 * h);
      for (int r = 0; r < M::nx; ++r) {
        EXPECT_NEAR(J(r, c), column[r], 1e-7 * (1 + std::abs(column[r])))
            << "FD mismatch at (" << r << ", " << c << "), state " << k;
      }
    }
  }
}

TYPED_TEST(ModelKernels, VelocitiesAndBiasAccelerationMatchTimeDerivatives) {
  using M = TypeParam;
  std::mt19937 rng(3);
  const typename M::Params p;
  const double h = 1e-6;  // small: the Kapitza pivot moves at 100 rad/s
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    // along the path q(t + e) = q + e v (qddot = 0), dx/dt = xdot and d(xdot)/dt = gamma
    const QVec<M> q_plus = s.q + h * s.v, q_minus = s.q - h * s.v;
    const XVec<M> xdot_fd =
        (M::positions(q_plus, s.t + h, p) - M::positions(q_minus, s.t - h, p)) / (2 * h);
    const XVec<M> gamma_fd =
        (M::velocities(q_plus, s.v, s.t + h, p) - M::velocities(q_minus, s.v, s.t - h, p)) /
        (2 * h);
    const XVec<M> xdot = M::velocities(s.q, s.v, s.t, p);
    const XVec<M> gamma = M::bias_acceleration(s.q, s.v, s.t, p);
    for (int r = 0; r < M::nx; ++r) {
      EXPECT_NEAR(xdot[r], xdot_fd[r], 1e-7 * (1 + std::abs(xdot[r]))) << "xdot(" << r << ")";
      EXPECT_NEAR(gamma[r], gamma_fd[r], 1e-6 * (1 + std::abs(gamma[r])))
          << "gamma(" << r << "), state " << k;
    }
  }
}

TYPED_TEST(ModelKernels, KernelsAgreeWithEachOther) {
  using M = TypeParam;
  std::mt19937 rng(4);
  const typename M::Params p;
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    const QMat<M> Mt = M::mass_matrix(s.q, s.t, p);
    const QVec<M> f = M::forces(s.q, s.v, s.t, p);
    QMat<M> Mt2;
    QVec<M> f2;
    M::dynamics(s.q, s.v, s.t, p, &Mt2, &f2);
    EXPECT_LT((Mt - Mt2).norm(), 1e-13 * (1 + Mt.norm()));
    EXPECT_LT((f - f2).norm(), 1e-13 * (1 + f.norm()));
    EXPECT_LT(
        (f - M::applied_forces(s.q, s.v, s.t, p) - M::inertial_forces(s.q, s.v, s.t, p)).norm(),
        1e-12 * (1 + f.norm()));
    // qddot solves Mt qddot = Ft + Fi, both the generated and the runtime's checked version
    const QVec<M> a = M::qddot(s.q, s.v, s.t, p);
    EXPECT_LT((Mt * a - f).norm(), 1e-10 * (1 + f.norm()));
    if constexpr (has_kinematic_constraints_v<M>) {
      // the runtime's is the constrained acceleration: Mt a = f + A^T lambda, A a = -gamma
      typename M::template CVector<double> lambda;
      const QVec<M> constrained = constrained_acceleration<M>(p, s.q, s.v, s.t, &lambda);
      const auto A = M::constraint_jacobian(s.q, s.t, p);
      const auto constraint_force = (A.transpose() * lambda).eval();
      EXPECT_LT((Mt * constrained - f - constraint_force).norm(),
                1e-10 * (1 + f.norm() + constraint_force.norm()));
      const auto gamma = M::constraint_bias(s.q, s.v, s.t, p);
      EXPECT_LT((A * constrained + gamma).norm(),
                1e-10 * (1 + gamma.norm() + A.norm() * constrained.norm()));
    } else {
      EXPECT_LT((acceleration<M>(p, s) - a).norm(), 1e-10 * (1 + a.norm()));
    }
    // Mt = J^T M J and T = 1/2 v^T Mt v when X has no explicit time dependence; in general
    // T = 1/2 xdot^T M xdot with xdot from velocities()
    const XJac<M> J = M::jacobian(s.q, s.t, p);
    const auto masses = M::template particle_masses<double>(p);
    XVec<M> mass_diagonal;
    for (int i = 0; i < M::num_particles; ++i) {
      mass_diagonal.template segment<M::dim>(M::dim * i).setConstant(masses[i]);
    }
    EXPECT_LT((J.transpose() * mass_diagonal.asDiagonal() * J - Mt).norm(), 1e-12 * Mt.norm());
    const XVec<M> xdot = M::velocities(s.q, s.v, s.t, p);
    const double kinetic = 0.5 * xdot.dot(mass_diagonal.asDiagonal() * xdot);
    EXPECT_NEAR(M::kinetic_energy(s.q, s.v, s.t, p), kinetic, 1e-12 * (1 + kinetic));
    EXPECT_NEAR(M::energy(s.q, s.v, s.t, p), kinetic + M::potential_energy(s.q, s.t, p),
                1e-12 * (1 + std::abs(kinetic)));
    // momenta from their definitions
    const XVec<M> x = M::positions(s.q, s.t, p);
    Eigen::Matrix<double, M::dim, 1> momentum = Eigen::Matrix<double, M::dim, 1>::Zero();
    Eigen::Vector3d angular = Eigen::Vector3d::Zero();
    for (int i = 0; i < M::num_particles; ++i) {
      momentum += masses[i] * xdot.template segment<M::dim>(M::dim * i);
      Eigen::Vector3d xi = Eigen::Vector3d::Zero(), vi = Eigen::Vector3d::Zero();
      xi.head<M::dim>() = x.template segment<M::dim>(M::dim * i);
      vi.head<M::dim>() = xdot.template segment<M::dim>(M::dim * i);
      angular += masses[i] * xi.cross(vi);
    }
    EXPECT_LT((M::linear_momentum(s.q, s.v, s.t, p) - momentum).norm(),
              1e-12 * (1 + momentum.norm()));
    const auto L = M::angular_momentum(s.q, s.v, s.t, p);
    if constexpr (M::dim == 3) {
      EXPECT_LT((L - angular).norm(), 1e-12 * (1 + angular.norm()));
    } else {
      EXPECT_NEAR(L[0], angular.z(), 1e-12 * (1 + angular.norm()));
    }
  }
}

TYPED_TEST(ModelKernels, SolveAgreesWithEigenAndRefusesIndefiniteMatrices) {
  // the generated LDL^T (written out for small nq, loops beyond) on random SPD matrices
  using M = TypeParam;
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int k = 0; k < kStates; ++k) {
    QMat<M> B;
    QVec<M> f;
    for (int i = 0; i < M::nq; ++i) {
      f(i) = uniform(rng);
      for (int j = 0; j < M::nq; ++j) B(i, j) = uniform(rng);
    }
    const QMat<M> A = B * B.transpose() + 0.1 * QMat<M>::Identity();
    QVec<M> a;
    ASSERT_TRUE(M::solve(A, f, &a));
    const QVec<M> expected = Eigen::LLT<QMat<M>>(A).solve(f);
    EXPECT_LT((a - expected).norm(), 1e-10 * (1 + expected.norm()));
    QMat<M> indefinite = A;
    indefinite(M::nq - 1, M::nq - 1) = -1.0;
    EXPECT_FALSE(M::solve(indefinite, f, &a));
    QMat<M> not_a_number = A;
    not_a_number(0, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(M::solve(not_a_number, f, &a));
  }
}

TYPED_TEST(ModelKernels, PotentialEnergyGradientIsTheConservativeForce) {
  // At v = 0 the applied forces of a model whose forces without a potential all vanish at
  // rest (the generator's forces_have_potential) are Ft = -dV/dq.
  using M = TypeParam;
  if (!M::forces_have_potential) {
    GTEST_SKIP() << M::name << " has a force without a potential that acts at rest";
  }
  std::mt19937 rng(5);
  const typename M::Params p;
  const double h = 1e-6;
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    const QVec<M> force = M::applied_forces(s.q, QVec<M>::Zero().eval(), s.t, p);
    for (int c = 0; c < M::nq; ++c) {
      QVec<M> plus = s.q, minus = s.q;
      plus[c] += h;
      minus[c] -= h;
      const double gradient =
          (M::potential_energy(plus, s.t, p) - M::potential_energy(minus, s.t, p)) / (2 * h);
      EXPECT_NEAR(force[c], -gradient, 1e-6 * (1 + std::abs(gradient)))
          << "coordinate " << M::coordinate_names[c] << ", state " << k;
    }
  }
}

TYPED_TEST(ModelKernels, InverseDynamicsVanishesAtTheForwardDynamics) {
  using M = TypeParam;
  std::mt19937 rng(7);
  const typename M::Params p;
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    const QVec<M> a = M::qddot(s.q, s.v, s.t, p);
    const QVec<M> r = M::inverse_dynamics(s.q, s.v, a, s.t, p);
    const double scale = 1 + M::forces(s.q, s.v, s.t, p).norm();
    EXPECT_LT(r.norm(), 1e-12 * scale) << "state " << k;
  }
}

template <class M>
void check_residual_jacobians() {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> accel(-2.0, 2.0);
  const typename M::Params p;
  const double h = 1e-6;
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    QVec<M> a;
    for (int i = 0; i < M::nq; ++i) a[i] = accel(rng);
    QMat<M> r_D_q, r_D_v;
    M::residual_jacobians(s.q, s.v, a, s.t, p, &r_D_q, &r_D_v);
    for (int c = 0; c < M::nq; ++c) {
      QVec<M> plus = s.q, minus = s.q;
      plus[c] += h;
      minus[c] -= h;
      const QVec<M> dq =
          (M::inverse_dynamics(plus, s.v, a, s.t, p) - M::inverse_dynamics(minus, s.v, a, s.t, p)) /
          (2 * h);
      plus = s.v;
      minus = s.v;
      plus[c] += h;
      minus[c] -= h;
      const QVec<M> dv =
          (M::inverse_dynamics(s.q, plus, a, s.t, p) - M::inverse_dynamics(s.q, minus, a, s.t, p)) /
          (2 * h);
      for (int r = 0; r < M::nq; ++r) {
        EXPECT_NEAR(r_D_q(r, c), dq[r], 1e-6 * (1 + std::abs(dq[r])))
            << "dr/dq mismatch at (" << r << ", " << c << "), state " << k;
        EXPECT_NEAR(r_D_v(r, c), dv[r], 1e-6 * (1 + std::abs(dv[r])))
            << "dr/dv mismatch at (" << r << ", " << c << "), state " << k;
      }
    }
  }
}

TYPED_TEST(ModelKernels, ResidualJacobiansMatchCentralDifferences) {
  using M = TypeParam;
  if constexpr (!has_residual_jacobians_v<M>) {
    GTEST_SKIP() << M::name << " has no residual_jacobians (kinematic constraints)";
  } else {
    check_residual_jacobians<M>();
  }
}

template <class M>
void check_declared_constraints() {
  using X = typename M::Maximal;
  if constexpr (X::num_constraints == 0) GTEST_SKIP() << M::name << " declares no constraints";
  std::mt19937 rng(9);
  for (int k = 0; k < kStates; ++k) {
    const auto s = random_state<M>(rng);
    // parameters scaled one by one can make an inertia tensor no body has (the triangle
    // inequality broken), which no point masses stand for: drawn again
    typename M::Params p = sampled_params<M>(rng);
    for (int tries = 0; tries < 10000 && !M::positions(s.q, s.t, p).allFinite(); ++tries)
      p = sampled_params<M>(rng);
    const auto x = M::positions(s.q, s.t, p);
    ASSERT_TRUE(x.allFinite()) << M::name << ": no physical parameters drawn";
    const auto violations = X::constraint_violations(x, s.t, p);
    const double scale = 1 + x.cwiseAbs().maxCoeff();
    for (int c = 0; c < X::num_declared_constraints; ++c) {  // kinematic rows need not hold
      EXPECT_LT(std::abs(violations[c]), 1e-12 * scale)
          << X::constraint_names[c] << " at state " << k;
    }
  }
}

TYPED_TEST(ModelKernels, DeclaredConstraintsHoldForSampledParameters) {
  // A constraint must hold on X(q, t) for every parameter value, not only the defaults: a
  // rod of literal length 1 over a pendulum of length l = 1 would pass at the defaults.
  using M = TypeParam;
  if constexpr (!has_maximal_v<M>) {
    GTEST_SKIP() << M::name << " has no Maximal model";
  } else {
    check_declared_constraints<M>();
  }
}

}  // namespace
}  // namespace gencoord::testing
