// SPDX-License-Identifier: BSD-3-Clause
// Checks every generated kernel (after CSE and the C++ printer), of the reduced model, of its
// kinematic constraints and of its Maximal model, against reference values evaluated in 40-digit
// arithmetic from the unoptimized derivation, at random states with randomly perturbed parameters
// (reference_values.hpp, written at build time by make_reference_values.py).
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "all_models.hpp"
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "reference_values.hpp"

namespace gencoord::testing {
namespace {

constexpr double kReferenceTolerance = 1e-12;

template <class M>
class ReferenceValues : public ::testing::Test {};
TYPED_TEST_SUITE(ReferenceValues, AllModels, ModelNames);

template <int Rows>
Eigen::Matrix<double, Rows, 1> vector_of(const std::vector<double>& values) {
  EXPECT_EQ(static_cast<int>(values.size()), Rows);
  Eigen::Matrix<double, Rows, 1> result = Eigen::Matrix<double, Rows, 1>::Zero();
  for (int i = 0; i < std::min<int>(Rows, static_cast<int>(values.size())); ++i) {
    result[i] = values[i];
  }
  return result;
}

/// The values of a std::array as an Eigen column (the sparse Jacobian kernels return arrays).
template <std::size_t N>
Eigen::Matrix<double, static_cast<int>(N), 1> array_of(const std::array<double, N>& values) {
  return Eigen::Map<const Eigen::Matrix<double, static_cast<int>(N), 1>>(values.data());
}

/// Compares kernels with reference values entry by entry, keeping the worst relative error.
class Comparison {
 public:
  explicit Comparison(std::string model) : model_(std::move(model)) {}

  void set_state(int state) { state_ = state; }

  /// `expected` holds the reference entries row-major. An entry's error is relative to its
  /// reference value, or to `floor` times the largest reference entry of the kernel, or to
  /// `scale`, where those are larger (so sums that cancel to near zero are not held to 1e-12
  /// of their tiny result).
  // not a template: compiled once, not once per kernel type of every model
  void operator()(const std::string& kernel, const Eigen::MatrixXd& actual,
                  const std::vector<double>& expected, double floor = 1e-3, double scale = 0) {
    ASSERT_EQ(static_cast<long>(expected.size()), static_cast<long>(actual.size()))
        << model_ << "::" << kernel << ": reference and kernel sizes differ";
    double largest = 0;
    for (double e : expected) largest = std::max(largest, std::abs(e));
    for (int r = 0; r < actual.rows(); ++r) {
      for (int c = 0; c < actual.cols(); ++c) {
        const double a = actual(r, c), e = expected[r * actual.cols() + c];
        const double error =
            std::abs(a - e) / std::max({std::abs(e), floor * largest, scale, 1e-300});
        ++comparisons_;
        double& worst = worst_[kernel];
        worst = std::max(worst, error);
        EXPECT_LE(error, kReferenceTolerance)
            << std::setprecision(17) << model_ << "::" << kernel << " entry (" << r << ", " << c
            << ") at state " << state_ << ": generated " << a << ", reference " << e
            << ", relative error " << std::setprecision(3) << error;
      }
    }
  }

  template <class Scalar>
  void scalar(const std::string& kernel, Scalar actual, const std::vector<double>& expected) {
    (*this)(kernel, Eigen::Matrix<double, 1, 1>::Constant(actual), expected);
  }

  std::string summary() const {
    std::ostringstream out;
    out << model_ << ": " << comparisons_ << " comparisons; worst relative error";
    for (const auto& [kernel, worst] : worst_) {
      out << " " << kernel << " " << std::setprecision(2) << worst;
    }
    return out.str();
  }

 private:
  std::string model_;
  int state_ = 0;
  long comparisons_ = 0;
  std::map<std::string, double> worst_;
};

/// The residual Jacobians at one reference state (where it has them: large models only at
/// the first).
template <class M, class Q>
void check_residual_jacobians(const ReferenceState& s, const Q& q, const Q& v, const Q& qdd,
                              double t, const typename M::Params& p, Comparison* comparison) {
  if (s.dr_dq.empty()) return;
  Comparison& expect = *comparison;
  // one comparison, so that an entry that is zero in both (dr/dv of a model whose forces
  // do not depend on v) is measured against the Jacobian's scale, not its own
  typename M::template QMatrix<double> dr_dq, dr_dv;
  M::residual_jacobians(q, v, qdd, t, p, &dr_dq, &dr_dv);
  Eigen::MatrixXd both(2 * M::nq, M::nq);
  for (int r = 0; r < M::nq; ++r) {
    for (int c = 0; c < M::nq; ++c) {
      both(r, c) = dr_dq(r, c);
      both(M::nq + r, c) = dr_dv(r, c);
    }
  }
  std::vector<double> expected = s.dr_dq;
  expected.insert(expected.end(), s.dr_dv.begin(), s.dr_dv.end());
  expect("residual_jacobians ([dr/dq; dr/dv])", both, expected);
}

/// The Maximal model's kernels at one reference state.
template <class M>
void check_maximal(const ReferenceState& s, double t, const typename M::Params& p,
                   Comparison* comparison) {
  Comparison& expect = *comparison;
  using X = typename M::Maximal;
  const auto pos = vector_of<M::nx>(s.pos);
  const auto vel = vector_of<M::nx>(s.vel);
  const double kappa = s.kappa, damping = s.penalty_damping;
  expect("Maximal::external_forces", X::external_forces(pos, vel, t, p), s.maximal_external_forces);
  // the penalty forces on a body's point masses sum pins at body points far from its centre,
  // each an affine combination of the point masses with weights of ten or more, and cancel:
  // the forces are held to 1e-12 of the kernel's largest entry (the Whipple bicycle's frames
  // reach 3.5e-12 of their own size), their Jacobians to 1e-12 of a hundredth of it
  const double penalty_floor = 1e-2;
  expect("Maximal::penalty_forces", X::penalty_forces(pos, vel, t, kappa, damping, p),
         s.maximal_penalty_forces, 1.0);
  expect("Maximal::force_jacobian_x", array_of(X::force_jacobian_x(pos, vel, t, kappa, damping, p)),
         s.maximal_force_jacobian_x, penalty_floor);
  expect("Maximal::force_jacobian_xdot",
         array_of(X::force_jacobian_xdot(pos, vel, t, kappa, damping, p)),
         s.maximal_force_jacobian_xdot, penalty_floor);
  expect.scalar("Maximal::potential_energy", X::potential_energy(pos, t, p),
                s.maximal_potential_energy);
  expect.scalar("Maximal::penalty_energy", X::penalty_energy(pos, t, kappa, p),
                s.maximal_penalty_energy);
  expect("Maximal::constraint_violations", X::constraint_violations(pos, t, p),
         s.maximal_constraint_violations);
}

TYPED_TEST(ReferenceValues, KernelsMatchTheUnoptimizedDerivation) {
  using M = TypeParam;
  const ReferenceModel* reference = find_reference(M::name);
  ASSERT_NE(reference, nullptr) << "no reference values for " << M::name;
  ASSERT_EQ(static_cast<int>(reference->parameter_names.size()), M::num_parameters);
  ASSERT_FALSE(reference->states.empty());

  Comparison expect(M::name);
  for (int k = 0; k < static_cast<int>(reference->states.size()); ++k) {
    const ReferenceState& s = reference->states[k];
    expect.set_state(k);
    typename M::Params p;
    for (int i = 0; i < M::num_parameters; ++i) {
      double* value = p.find(reference->parameter_names[i]);
      ASSERT_NE(value, nullptr) << M::name << ": no parameter " << reference->parameter_names[i];
      *value = s.params[i];
    }
    const auto q = vector_of<M::nq>(s.q);
    const auto v = vector_of<M::nq>(s.v);
    const double t = s.t;

    expect("mass_matrix", M::mass_matrix(q, t, p), s.mass_matrix);
    expect("applied_forces", M::applied_forces(q, v, t, p), s.applied_forces);
    // Fi on the scale of Ft + Fi, where it enters the dynamics: a tree whose every joint
    // turns about a fixed axis has Fi = 0 as a sum that cancels (the Delta robot's arms)
    double force_scale = 0;
    for (const double f : s.forces) force_scale = std::max(force_scale, std::abs(f));
    expect("inertial_forces", M::inertial_forces(q, v, t, p), s.inertial_forces, 1e-3,
           1e-3 * force_scale);
    expect("forces", M::forces(q, v, t, p), s.forces);
    typename M::template QMatrix<double> Mt;
    typename M::template QVector<double> f;
    M::dynamics(q, v, t, p, &Mt, &f);
    expect("dynamics (Mt)", Mt, s.mass_matrix);
    expect("dynamics (f)", f, s.forces);
    expect.scalar("kinetic_energy", M::kinetic_energy(q, v, t, p), s.kinetic_energy);
    expect.scalar("potential_energy", M::potential_energy(q, t, p), s.potential_energy);
    expect.scalar("energy", M::energy(q, v, t, p), s.energy);
    expect("positions", M::positions(q, t, p), s.positions);
    expect("velocities", M::velocities(q, v, t, p), s.velocities);
    expect("jacobian", M::jacobian(q, t, p), s.jacobian);
    expect("bias_acceleration", M::bias_acceleration(q, v, t, p), s.bias_acceleration);
    expect("linear_momentum", M::linear_momentum(q, v, t, p), s.linear_momentum);
    expect("angular_momentum", M::angular_momentum(q, v, t, p), s.angular_momentum);
    expect("particle_masses", M::template particle_masses<double>(p), s.particle_masses);
    expect("fixed_point_positions", M::fixed_point_positions(t, p), s.fixed_point_positions);
    expect("generalized_forces", M::generalized_forces(q, v, t, p), s.generalized_forces);
    expect.scalar("generalized_potential_energy", M::generalized_potential_energy(q, t, p),
                  s.generalized_potential_energy);

    const auto qdd = vector_of<M::nq>(s.qdd);
    expect("inverse_dynamics", M::inverse_dynamics(q, v, qdd, t, p), s.inverse_dynamics);
    // large models: at the first state only; constrained ones have none
    if constexpr (has_residual_jacobians_v<M>)
      check_residual_jacobians<M>(s, q, v, qdd, t, p, &expect);
    // qddot solves Mt qdd = f: round-off bounds its error normwise (times cond(Mt)), not entry
    // by entry, so each entry is compared relative to the largest
    expect("qddot", M::qddot(q, v, t, p), s.qddot, 1.0);

    if constexpr (has_kinematic_constraints_v<M>) {
      expect("constraint_jacobian", M::constraint_jacobian(q, t, p), s.constraint_jacobian);
      expect("constraint_velocities", M::constraint_velocities(q, v, t, p),
             s.constraint_velocities);
      expect("constraint_bias", M::constraint_bias(q, v, t, p), s.constraint_bias);
    }
    if constexpr (has_holonomic_constraints_v<M>) {
      expect("holonomic_constraints", M::holonomic_constraints(q, t, p), s.holonomic_constraints);
      expect("holonomic_jacobian", M::holonomic_jacobian(q, t, p), s.holonomic_jacobian);
    }
    if constexpr (has_maximal_v<M>) check_maximal<M>(s, t, p, &expect);
  }
  std::cout << "[          ] " << expect.summary() << "\n";
}

}  // namespace
}  // namespace gencoord::testing
