// SPDX-License-Identifier: BSD-3-Clause
// One step of a model's dynamics as a discrete map x_next = F(x, u), the input held over the
// step, and its exact Jacobians dF/dx and dF/du: what iLQR, DDP and discrete-time MPC take.
//
// F is the classical Runge-Kutta step of xdot = f(x, u, t), x = (q, v):
//   k1 = f(x),  k2 = f(x + h/2 k1),  k3 = f(x + h/2 k2),  k4 = f(x + h k3),
//   F = x + h/6 (k1 + 2 k2 + 2 k3 + k4).
// Its Jacobians follow the stages by the chain rule, each stage's df/dx and df/du from
// linearize() (the generated residual Jacobians: exact), so they are the derivatives of the
// map F itself, not of a linear model of it:
//   dk1/dx = A1,  dk2/dx = A2 (I + h/2 dk1/dx),  ...,  dk2/du = A2 h/2 dk1/du + B2,  ...
// Four linearizations a step; MuJoCo's mjd_transitionFD takes 2 (nx + nu) + 1 steps instead.
#pragma once

#include <Eigen/Core>

#include <stdexcept>

#include "gencoord/control/linearize.hpp"
#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// x_next = F(x, u) and its Jacobians; x = (q, v) of dimension 2 nq.
struct Transition {
  Eigen::VectorXd x;  // F(x, u)
  Eigen::MatrixXd A;  // dF/dx (2 nq x 2 nq)
  Eigen::MatrixXd B;  // dF/du (2 nq x num_inputs)
};

/// One RK4 step of length h from state x = (q, v) at time t with the inputs u held, and its
/// exact Jacobians (see the file comment).
/// \param[in] p  The model parameters; their input fields are replaced by u.
/// \param[in] x  The state (q, v), dim 2 nq.
/// \param[in] u  The control inputs (dim num_inputs_v<M>).
/// \param[in] t  The time at the start of the step.
/// \param[in] h  The step.
/// \throws DynamicsError if the dynamics fail at a stage; std::invalid_argument if x has the
///         wrong size.
template <class M>
Transition rk4_transition(const ParamsOf<M>& p, const Eigen::VectorXd& x, const InputVec<M>& u,
                          double t, double h) {
  static_assert(assert_model_v<M>);
  static_assert(!has_generalized_speeds_v<M>,
                "gencoord: rk4_transition steps x = (q, v) with q' = v; a model with "
                "generalized speeds keeps unit quaternions, which a plain RK4 sum does not");
  constexpr int n = M::nq;
  if (x.size() != 2 * n) throw std::invalid_argument("rk4_transition: x must have size 2 nq");
  const int nx = 2 * n;
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(nx, nx);
  const double offsets[4] = {0.0, h / 2, h / 2, h};  // each stage's point: x + offset k_prev
  const double weights[4] = {h / 6, h / 3, h / 3, h / 6};
  Transition out{x, Eigen::MatrixXd::Identity(nx, nx), Eigen::MatrixXd::Zero(nx, num_inputs_v<M>)};
  Eigen::VectorXd k = Eigen::VectorXd::Zero(nx);
  Eigen::MatrixXd k_D_x = Eigen::MatrixXd::Zero(nx, nx);
  Eigen::MatrixXd k_D_u = Eigen::MatrixXd::Zero(nx, num_inputs_v<M>);
  for (int stage = 0; stage < 4; ++stage) {
    const Eigen::VectorXd point = x + offsets[stage] * k;
    const LinearizedDynamics f =
        linearize<M>(p, point.head(n), point.tail(n), u, t + offsets[stage]);
    k = f.xdot;
    k_D_u = f.A * (offsets[stage] * k_D_u) + f.B;  // uses the previous stage's k_D_u
    k_D_x = f.A * (I + offsets[stage] * k_D_x);
    out.x += weights[stage] * k;
    out.A += weights[stage] * k_D_x;
    out.B += weights[stage] * k_D_u;
  }
  return out;
}

}  // namespace gencoord
