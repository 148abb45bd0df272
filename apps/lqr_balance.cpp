// SPDX-License-Identifier: BSD-3-Clause
// lqr_balance: the C++ side of apps/lqr_balance.py. Linearizes the cart-pole and the double
// inverted pendulum on a cart about the upright equilibrium (gencoord::linearize), designs
// LQR gains with the runtime's Riccati solver (gencoord::lqr_gain), and simulates each
// nonlinear model under u = -K x from a 0.2 rad offset of the lower pole with RK4
// (gencoord::ControlledSystem).
//
//   lqr_balance [--output-dir out]
//
// Writes <output-dir>/lqr_<model>_cpp.csv (t, q, v, u every 10 ms) and prints the gains and
// the largest |q|, |v| left after 10 s; exits with status 1 if a pole is not balanced.
#include <Eigen/Core>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "gencoord/control/controlled_system.hpp"
#include "gencoord/control/linearize.hpp"
#include "gencoord/control/lqr.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "generated/cart_pole.hpp"
#include "generated/double_pendulum_on_cart.hpp"

namespace {

constexpr double kOffset = 0.2;     // initial angle of the lower pole (rad)
constexpr double kDuration = 10.0;  // simulated time (s)
constexpr double kBalanced = 1e-3;  // largest |q|, |v| allowed at the end

// The same weights as apps/lqr_balance.py: the cart's position 10, the angles 100, rates 1.
Eigen::MatrixXd state_weights(int nq) {
  Eigen::VectorXd w = Eigen::VectorXd::Ones(2 * nq);
  w[0] = 10.0;
  w.segment(1, nq - 1).setConstant(100.0);
  return w.asDiagonal();
}

template <class M>
double balance(const std::string& output_dir) {
  using Q = gencoord::QVec<M>;
  const typename M::Params params;
  const Q upright = Q::Zero();
  const gencoord::LinearizedDynamics linear =
      gencoord::linearize<M>(params, upright, upright, gencoord::InputVec<M>::Zero(), 0.0);
  const Eigen::MatrixXd K =
      gencoord::lqr_gain(linear.A, linear.B, state_weights(M::nq), Eigen::MatrixXd::Identity(1, 1));
  const auto law = [K](double, const Q& q, const Q& v) {
    Eigen::VectorXd x(2 * M::nq);
    x << q, v;
    return gencoord::InputVec<M>(-K * x);
  };
  gencoord::State<M> initial;
  initial.q = upright;
  initial.q[1] = kOffset;
  initial.v = upright;
  std::ofstream csv(output_dir + "/lqr_" + M::name + "_cpp.csv");
  csv.precision(17);
  long long step = 0;
  const gencoord::ControlledSystem<M> system(params, law);
  const gencoord::State<M> end =
      gencoord::simulate(system, initial, {gencoord::Integrator::RK4, 1e-3, kDuration},
                         [&](const gencoord::State<M>& s) {
                           if (step++ % 10) return;
                           csv << s.t;
                           for (int i = 0; i < M::nq; ++i) csv << ',' << s.q[i];
                           for (int i = 0; i < M::nq; ++i) csv << ',' << s.v[i];
                           csv << ',' << system.inputs(s)[0] << '\n';
                         });
  const double left = std::max(end.q.cwiseAbs().maxCoeff(), end.v.cwiseAbs().maxCoeff());
  std::cout << M::name << ": K = " << K.format(Eigen::IOFormat(4, 0, ", ", "", "", "", "[", "]"))
            << "; after " << kDuration << " s the largest |q|, |v| is " << left << "\n";
  return left;
}

}  // namespace

int main(int argc, char** argv) {
  std::string output_dir = "out";
  if (argc == 3 && std::string(argv[1]) == "--output-dir") {
    output_dir = argv[2];
  } else if (argc != 1) {
    std::cerr << "usage: lqr_balance [--output-dir DIR]\n";
    return 2;
  }
  try {
    std::filesystem::create_directories(output_dir);
    const double worst = std::max(balance<gencoord::models::CartPole>(output_dir),
                                  balance<gencoord::models::DoublePendulumOnCart>(output_dir));
    if (worst > kBalanced) {
      std::cerr << "lqr_balance: not balanced: " << worst << " > " << kBalanced << "\n";
      return 1;
    }
  } catch (const std::exception& error) {
    std::cerr << "lqr_balance: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
