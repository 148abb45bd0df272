// SPDX-License-Identifier: BSD-3-Clause
// Every generated kernel instantiated with float agrees with the same kernel in double.
//
// Inputs (q, v, qdd, t, the Maximal state, the parameters) are rounded to float first, so
// both precisions see the same numbers and only the float arithmetic inside the kernel
// differs. Its error is bounded relative to the kernel's condition at that state: kFloatTolerance
// times the larger of (a) float's unit round-off times the kernel's largest entry and (b) how
// much the double kernel moves when every input is perturbed by a relative float round-off
// (the kernel's sensitivity: a phase omega t with omega t large, a difference of nearly equal
// terms). qddot solves Mt a = f, which multiplies the rounding of Mt and f by Mt's condition
// number: its (a) is multiplied by it. Each operation rounds once, and the generated code's
// intermediate terms can be larger than its results (sums that cancel after CSE), which
// input perturbations do not see: kFloatTolerance = 1000 allows for both. The inertial forces Fi
// enter the dynamics only in Ft + Fi, and a tree whose every joint turns about a fixed axis
// has Fi = 0 as a sum that cancels (the Delta robot's arms): their (a) takes the largest
// entry of Ft + Fi as the scale where that is larger. Observed worst ratios of
// error to (a, b) are below 100 (printed per model), so a kernel that loses more than three
// decades beyond its condition fails.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>

#include <gtest/gtest.h>

#include "all_models.hpp"
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "random_states.hpp"

namespace gencoord::testing {
namespace {

constexpr int kFloatStates = 8;
constexpr int kPerturbations = 3;
constexpr double kFloatTolerance = 1000.0;
constexpr double kFloatEpsilon = std::numeric_limits<float>::epsilon();

template <class M>
class FloatKernels : public ::testing::Test {};
TYPED_TEST_SUITE(FloatKernels, AllModels, ModelNames);

double to_float(double x) { return static_cast<double>(static_cast<float>(x)); }

/// Every input of every kernel, in double, each exactly representable in float.
template <class M>
struct Inputs {
  typename M::template QVector<double> q, v, qdd;
  typename M::template XVector<double> pos, vel;
  double t = 0, kappa = 0, penalty_damping = 0;
  typename M::Params params;

  /// Every input scaled by (1 + e) with e in [-kFloatEpsilon, kFloatEpsilon] (parameters
  /// included), then rounded to float.
  template <class Change>
  Inputs<M> map(Change change) const {
    Inputs<M> out = *this;
    for (int i = 0; i < M::nq; ++i) {
      out.q[i] = change(q[i]);
      out.v[i] = change(v[i]);
      out.qdd[i] = change(qdd[i]);
    }
    for (int i = 0; i < M::nx; ++i) {
      out.pos[i] = change(pos[i]);
      out.vel[i] = change(vel[i]);
    }
    out.t = change(t);
    out.kappa = change(kappa);
    out.penalty_damping = change(penalty_damping);
    for (const char* name : M::parameter_names) {
      double* value = out.params.find(name);
      *value = change(*value);
    }
    return out;
  }
};

template <class M>
Inputs<M> random_inputs(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), factor(0.7, 1.3);
  const auto s = random_state<M>(rng);
  Inputs<M> in;
  in.q = s.q;
  in.v = s.v;
  in.t = s.t;
  for (int i = 0; i < M::nq; ++i) in.qdd[i] = u(rng);
  // parameters near the defaults, drawn again until every body is a real one (its point
  // masses finite): scaling a tensor's entries one by one can break the triangle inequality
  for (int attempt = 0; attempt < 100; ++attempt) {
    in.params = typename M::Params();
    for (const char* name : M::parameter_names) *in.params.find(name) *= factor(rng);
    if (M::positions(in.q, in.t, in.params).allFinite()) break;
  }
  // the Maximal state near the reduced one, off its constraints so that penalties act
  in.pos = M::positions(in.q, in.t, in.params);
  in.vel = M::velocities(in.q, in.v, in.t, in.params);
  for (int i = 0; i < M::nx; ++i) {
    in.pos[i] += 0.05 * u(rng);
    in.vel[i] += 0.05 * u(rng);
  }
  in.kappa = 1e3;
  in.penalty_damping = 0.5;
  return in.map(to_float);
}

/// A kernel's result as a double column: Eigen objects, arrays and scalars.
template <class Derived>
Eigen::VectorXd column(const Eigen::MatrixBase<Derived>& m) {
  Eigen::VectorXd out(m.size());
  for (Eigen::Index k = 0; k < m.size(); ++k) out[k] = static_cast<double>(m.derived()(k));
  return out;
}
template <class S, std::size_t N>
Eigen::VectorXd column(const std::array<S, N>& a) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(N));
  for (std::size_t k = 0; k < N; ++k) out[static_cast<Eigen::Index>(k)] = a[k];
  return out;
}
Eigen::VectorXd column(double x) { return Eigen::VectorXd::Constant(1, x); }
Eigen::VectorXd column(float x) { return Eigen::VectorXd::Constant(1, x); }

/// Checks kernels at one state; keeps each kernel's worst error relative to its bound.
template <class M>
class FloatCheck {
 public:
  FloatCheck(const Inputs<M>& in, std::mt19937* rng) : in_(in), rng_(rng) {}

  /// `kernel(scalar, inputs)` evaluates one kernel with Scalar = decltype(scalar).
  /// `condition` multiplies the round-off term (a) (see the file comment).
  template <class Kernel>
  void operator()(const std::string& name, Kernel kernel, double condition = 1.0,
                  double scale = 0.0) {
    // only the evaluations depend on the kernel's type; judge() is compiled once per model
    const Eigen::VectorXd exact = column(kernel(0.0, in_));
    const Eigen::VectorXd single = column(kernel(0.0f, in_));
    std::array<Eigen::VectorXd, kPerturbations> moved;
    if (exact.size() != 0) {
      for (Eigen::VectorXd& column_moved : moved) column_moved = column(kernel(0.0, perturbed()));
    }
    judge(name, exact, single, moved, condition, scale);
  }

  void set_inputs(const Inputs<M>& in) { in_ = in; }

  const Inputs<M>& inputs() const { return in_; }

  std::string summary() const {
    std::ostringstream out;
    out << M::name << ": worst error / (a, b)";
    for (const auto& [name, worst] : worst_) out << " " << name << " " << worst;
    return out.str();
  }

 private:
  /// The inputs, each scaled by (1 + e) with e in [-kFloatEpsilon, kFloatEpsilon].
  Inputs<M> perturbed() const {
    std::uniform_real_distribution<double> e(-kFloatEpsilon, kFloatEpsilon);
    return in_.map([&](double x) { return x * (1 + e(*rng_)); });
  }

  /// The kernel's worst error relative to its bound, from its double and float results and
  /// its double results at perturbed inputs (compiled once per model, not per kernel).
  void judge(const std::string& name, const Eigen::VectorXd& exact, const Eigen::VectorXd& single,
             const std::array<Eigen::VectorXd, kPerturbations>& moved, double condition,
             double scale) {
    ASSERT_EQ(exact.size(), single.size());
    if (exact.size() == 0) return;
    ASSERT_TRUE(exact.allFinite()) << M::name << "::" << name;
    double sensitivity = 0;
    for (const Eigen::VectorXd& column_moved : moved) {
      sensitivity = std::max(sensitivity, (column_moved - exact).cwiseAbs().maxCoeff());
    }
    const double bound = std::max(
        kFloatEpsilon * condition * std::max(exact.cwiseAbs().maxCoeff(), scale), sensitivity);
    const double ratio = (single - exact).cwiseAbs().maxCoeff() / std::max(bound, 1e-300);
    double& worst = worst_[name];
    worst = std::max(worst, ratio);
    EXPECT_LE(ratio, kFloatTolerance)
        << M::name << "::" << name << ": float " << single.transpose() << "\n double "
        << exact.transpose() << "\n sensitivity " << sensitivity;
  }

  Inputs<M> in_;
  std::mt19937* rng_;
  std::map<std::string, double> worst_;
};

template <class S, class M>
struct Cast {
  const Inputs<M>& in;
  auto q() const { return in.q.template cast<S>().eval(); }
  auto v() const { return in.v.template cast<S>().eval(); }
  auto qdd() const { return in.qdd.template cast<S>().eval(); }
  auto pos() const { return in.pos.template cast<S>().eval(); }
  auto vel() const { return in.vel.template cast<S>().eval(); }
  S t() const { return static_cast<S>(in.t); }
  S kappa() const { return static_cast<S>(in.kappa); }
  S damping() const { return static_cast<S>(in.penalty_damping); }
};

/// Wraps `body(cast inputs, params)` as a kernel of (scalar, inputs).
template <class M, class Body>
auto kernel_of(Body body) {
  return [body](auto scalar, const Inputs<M>& in) {
    using S = decltype(scalar);
    return body(Cast<S, M>{in}, in.params);
  };
}

TYPED_TEST(FloatKernels, AgreeWithDoubleWithinTheKernelsCondition) {
  using M = TypeParam;
  std::mt19937 rng(11);
  FloatCheck<M> check(random_inputs<M>(rng), &rng);
  for (int state = 0; state < kFloatStates; ++state) {
    check.set_inputs(random_inputs<M>(rng));
    const Inputs<M>& in = check.inputs();
    const auto K = [](auto body) { return kernel_of<M>(body); };
    check("mass_matrix", K([](auto c, auto& p) { return M::mass_matrix(c.q(), c.t(), p); }));
    check("applied_forces",
          K([](auto c, auto& p) { return M::applied_forces(c.q(), c.v(), c.t(), p); }));
    check("generalized_forces",
          K([](auto c, auto& p) { return M::generalized_forces(c.q(), c.v(), c.t(), p); }));
    check("inertial_forces",
          K([](auto c, auto& p) { return M::inertial_forces(c.q(), c.v(), c.t(), p); }), 1.0,
          M::forces(in.q, in.v, in.t, in.params).cwiseAbs().maxCoeff());
    check("forces", K([](auto c, auto& p) { return M::forces(c.q(), c.v(), c.t(), p); }));
    check("dynamics", K([](auto c, auto& p) {
            typename M::template QMatrix<decltype(c.t())> Mt;
            typename M::template QVector<decltype(c.t())> f;
            M::dynamics(c.q(), c.v(), c.t(), p, &Mt, &f);
            Eigen::Matrix<decltype(c.t()), Eigen::Dynamic, 1> both(M::nq * (M::nq + 1));
            both << Mt.reshaped(), f;
            return both;
          }));
    check("inverse_dynamics",
          K([](auto c, auto& p) { return M::inverse_dynamics(c.q(), c.v(), c.qdd(), c.t(), p); }));
    if constexpr (has_residual_jacobians_v<M>) {
      check("residual_jacobians", K([](auto c, auto& p) {
              typename M::template QMatrix<decltype(c.t())> dq, dv;
              M::residual_jacobians(c.q(), c.v(), c.qdd(), c.t(), p, &dq, &dv);
              Eigen::Matrix<decltype(c.t()), Eigen::Dynamic, 1> both(2 * M::nq * M::nq);
              both << dq.reshaped(), dv.reshaped();
              return both;
            }));
    }
    const Eigen::SelfAdjointEigenSolver<typename M::template QMatrix<double>> eigen(
        M::mass_matrix(in.q, in.t, in.params));
    const double condition = eigen.eigenvalues().maxCoeff() / eigen.eigenvalues().minCoeff();
    check("qddot", K([](auto c, auto& p) { return M::qddot(c.q(), c.v(), c.t(), p); }), condition);
    check("kinetic_energy",
          K([](auto c, auto& p) { return M::kinetic_energy(c.q(), c.v(), c.t(), p); }));
    check("potential_energy",
          K([](auto c, auto& p) { return M::potential_energy(c.q(), c.t(), p); }));
    check("generalized_potential_energy",
          K([](auto c, auto& p) { return M::generalized_potential_energy(c.q(), c.t(), p); }));
    check("energy", K([](auto c, auto& p) { return M::energy(c.q(), c.v(), c.t(), p); }));
    check("positions", K([](auto c, auto& p) { return M::positions(c.q(), c.t(), p); }));
    check("velocities", K([](auto c, auto& p) { return M::velocities(c.q(), c.v(), c.t(), p); }));
    check("jacobian", K([](auto c, auto& p) { return M::jacobian(c.q(), c.t(), p); }));
    check("bias_acceleration",
          K([](auto c, auto& p) { return M::bias_acceleration(c.q(), c.v(), c.t(), p); }));
    check("linear_momentum",
          K([](auto c, auto& p) { return M::linear_momentum(c.q(), c.v(), c.t(), p); }));
    check("angular_momentum",
          K([](auto c, auto& p) { return M::angular_momentum(c.q(), c.v(), c.t(), p); }));
    check("particle_masses",
          K([](auto c, auto& p) { return M::template particle_masses<decltype(c.t())>(p); }));
    check("fixed_point_positions",
          K([](auto c, auto& p) { return M::fixed_point_positions(c.t(), p); }));
    if constexpr (has_kinematic_constraints_v<M>) {
      check("constraint_jacobian",
            K([](auto c, auto& p) { return M::constraint_jacobian(c.q(), c.t(), p); }));
      check("constraint_velocities",
            K([](auto c, auto& p) { return M::constraint_velocities(c.q(), c.v(), c.t(), p); }));
      check("constraint_bias",
            K([](auto c, auto& p) { return M::constraint_bias(c.q(), c.v(), c.t(), p); }));
    }
    if constexpr (has_maximal_v<M>) {
      using X = typename M::Maximal;
      check("Maximal::external_forces",
            K([](auto c, auto& p) { return X::external_forces(c.pos(), c.vel(), c.t(), p); }));
      check("Maximal::penalty_forces", K([](auto c, auto& p) {
              return X::penalty_forces(c.pos(), c.vel(), c.t(), c.kappa(), c.damping(), p);
            }));
      check("Maximal::force_jacobian_x", K([](auto c, auto& p) {
              return X::force_jacobian_x(c.pos(), c.vel(), c.t(), c.kappa(), c.damping(), p);
            }));
      check("Maximal::force_jacobian_xdot", K([](auto c, auto& p) {
              return X::force_jacobian_xdot(c.pos(), c.vel(), c.t(), c.kappa(), c.damping(), p);
            }));
      check("Maximal::potential_energy",
            K([](auto c, auto& p) { return X::potential_energy(c.pos(), c.t(), p); }));
      check("Maximal::penalty_energy",
            K([](auto c, auto& p) { return X::penalty_energy(c.pos(), c.t(), c.kappa(), p); }));
      check("Maximal::constraint_violations",
            K([](auto c, auto& p) { return X::constraint_violations(c.pos(), c.t(), p); }));
    }
  }
  std::cout << "[          ] " << check.summary() << "\n";
}

}  // namespace
}  // namespace gencoord::testing
