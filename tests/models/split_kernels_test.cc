// Kernels cut into parts (generator/split.py) compute what the whole kernels compute.
//
// The build generates double_pendulum (flat derivation) and n_link_chain_5 (structured
// derivation, forward-mode Jacobians) a second time with --max-function-statements 3, so
// every kernel of every kind is split into many parts that pass values through `carried`
// (scalar, vector and std::array results, out-parameters, symmetric blocks, Jacobians).
// Those headers are included inside namespace `split`, after the standard and Eigen headers
// they include, so both versions of each model live in one program.
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <string_view>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_5.hpp"

namespace split {
#include "split/generated/double_pendulum.hpp"  // NOLINT(build/include): on purpose
#include "split/generated/n_link_chain_5.hpp"   // NOLINT(build/include)
}  // namespace split

namespace gencoord::testing {
namespace {

// The same expressions in the same order: only rounding-free moves through memory differ.
constexpr double kTolerance = 1e-14;

template <class A, class B>
void expect_same(const std::string& kernel, const A& whole, const B& parts) {
  ASSERT_EQ(whole.size(), parts.size()) << kernel;
  for (int i = 0; i < static_cast<int>(whole.size()); ++i) {
    const double a = whole.data()[i], b = parts.data()[i];
    EXPECT_LE(std::abs(a - b), kTolerance * std::max(1.0, std::abs(a)))
        << kernel << " entry " << i << ": whole " << a << ", split " << b;
  }
}

void expect_same(const std::string& kernel, double whole, double parts) {
  const Eigen::Matrix<double, 1, 1> a = Eigen::Matrix<double, 1, 1>::Constant(whole),
                                    b = Eigen::Matrix<double, 1, 1>::Constant(parts);
  expect_same(kernel, a, b);
}

template <class Whole, class Split>
void check_every_kernel() {
  static_assert(Whole::nq == Split::nq && Whole::nx == Split::nx);
  constexpr int nq = Whole::nq, nx = Whole::nx;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.5, 1.5);
  const auto random = [&](auto vector) {
    for (int i = 0; i < vector.size(); ++i) vector[i] = uniform(rng);
    return vector;
  };
  const typename Whole::Params wp;
  const typename Split::Params sp;
  for (int state = 0; state < 20; ++state) {
    SCOPED_TRACE("state " + std::to_string(state));
    const Eigen::Matrix<double, nq, 1> q = random(Eigen::Matrix<double, nq, 1>()),
                                       v = random(Eigen::Matrix<double, nq, 1>()),
                                       a = random(Eigen::Matrix<double, nq, 1>());
    const Eigen::Matrix<double, nx, 1> x = random(Eigen::Matrix<double, nx, 1>()),
                                       xd = random(Eigen::Matrix<double, nx, 1>());
    const double t = uniform(rng), kappa = 1e4, damping = 3.0;
    expect_same("mass_matrix", Whole::mass_matrix(q, t, wp), Split::mass_matrix(q, t, sp));
    expect_same("applied_forces", Whole::applied_forces(q, v, t, wp),
                Split::applied_forces(q, v, t, sp));
    expect_same("generalized_forces", Whole::generalized_forces(q, v, t, wp),
                Split::generalized_forces(q, v, t, sp));
    expect_same("inertial_forces", Whole::inertial_forces(q, v, t, wp),
                Split::inertial_forces(q, v, t, sp));
    expect_same("forces", Whole::forces(q, v, t, wp), Split::forces(q, v, t, sp));
    Eigen::Matrix<double, nq, nq> Mw, Ms, Dw, Ds;
    Eigen::Matrix<double, nq, 1> fw, fs;
    Whole::dynamics(q, v, t, wp, &Mw, &fw);
    Split::dynamics(q, v, t, sp, &Ms, &fs);
    expect_same("dynamics (Mt)", Mw, Ms);
    expect_same("dynamics (f)", fw, fs);
    expect_same("inverse_dynamics", Whole::inverse_dynamics(q, v, a, t, wp),
                Split::inverse_dynamics(q, v, a, t, sp));
    Whole::residual_jacobians(q, v, a, t, wp, &Mw, &Dw);
    Split::residual_jacobians(q, v, a, t, sp, &Ms, &Ds);
    expect_same("residual_jacobians (dr/dq)", Mw, Ms);
    expect_same("residual_jacobians (dr/dv)", Dw, Ds);
    expect_same("kinetic_energy", Whole::kinetic_energy(q, v, t, wp),
                Split::kinetic_energy(q, v, t, sp));
    expect_same("potential_energy", Whole::potential_energy(q, t, wp),
                Split::potential_energy(q, t, sp));
    expect_same("generalized_potential_energy", Whole::generalized_potential_energy(q, t, wp),
                Split::generalized_potential_energy(q, t, sp));
    expect_same("energy", Whole::energy(q, v, t, wp), Split::energy(q, v, t, sp));
    expect_same("positions", Whole::positions(q, t, wp), Split::positions(q, t, sp));
    expect_same("velocities", Whole::velocities(q, v, t, wp), Split::velocities(q, v, t, sp));
    expect_same("jacobian", Whole::jacobian(q, t, wp), Split::jacobian(q, t, sp));
    expect_same("bias_acceleration", Whole::bias_acceleration(q, v, t, wp),
                Split::bias_acceleration(q, v, t, sp));
    expect_same("linear_momentum", Whole::linear_momentum(q, v, t, wp),
                Split::linear_momentum(q, v, t, sp));
    expect_same("angular_momentum", Whole::angular_momentum(q, v, t, wp),
                Split::angular_momentum(q, v, t, sp));
    expect_same("qddot", Whole::qddot(q, v, t, wp), Split::qddot(q, v, t, sp));

    using WX = typename Whole::Maximal;
    using SX = typename Split::Maximal;
    expect_same("Maximal::external_forces", WX::external_forces(x, xd, t, wp),
                SX::external_forces(x, xd, t, sp));
    expect_same("Maximal::penalty_forces", WX::penalty_forces(x, xd, t, kappa, damping, wp),
                SX::penalty_forces(x, xd, t, kappa, damping, sp));
    const auto jw = WX::force_jacobian_x(x, xd, t, kappa, damping, wp);
    const auto js = SX::force_jacobian_x(x, xd, t, kappa, damping, sp);
    expect_same("Maximal::force_jacobian_x",
                Eigen::Map<const Eigen::VectorXd>(jw.data(), jw.size()),
                Eigen::Map<const Eigen::VectorXd>(js.data(), js.size()));
    const auto kw = WX::force_jacobian_xdot(x, xd, t, kappa, damping, wp);
    const auto ks = SX::force_jacobian_xdot(x, xd, t, kappa, damping, sp);
    expect_same("Maximal::force_jacobian_xdot",
                Eigen::Map<const Eigen::VectorXd>(kw.data(), kw.size()),
                Eigen::Map<const Eigen::VectorXd>(ks.data(), ks.size()));
    expect_same("Maximal::potential_energy", WX::potential_energy(x, t, wp),
                SX::potential_energy(x, t, sp));
    expect_same("Maximal::penalty_energy", WX::penalty_energy(x, t, kappa, wp),
                SX::penalty_energy(x, t, kappa, sp));
    expect_same("Maximal::constraint_violations", WX::constraint_violations(x, t, wp),
                SX::constraint_violations(x, t, sp));
  }
}

TEST(SplitKernels, DoublePendulumPartsComputeTheWholeKernels) {
  check_every_kernel<models::DoublePendulum, split::gencoord::models::DoublePendulum>();
}

TEST(SplitKernels, FiveLinkChainPartsComputeTheWholeKernels) {
  check_every_kernel<models::NLinkChain5, split::gencoord::models::NLinkChain5>();
}

}  // namespace
}  // namespace gencoord::testing
