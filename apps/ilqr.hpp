// SPDX-License-Identifier: BSD-3-Clause
// Iterative LQR (iLQR) on a generated model with control inputs: the optimal-control solver
// that apps/mpc_swing_up.cpp runs once offline and then at every control period.
//
// The discrete dynamics x_{k+1} = F(x_k, u_k) are RK4 steps of length dt with the input held,
// F and its Jacobians from gencoord::rk4_transition (each stage linearized by
// gencoord::linearize: exact). The cost is quadratic about a goal state,
//   J = sum_k dt/2 (e_k' Q e_k + u_k' R u_k) + 1/2 e_N' Qf e_N,   e = x - goal.
// Each iteration takes the Gauss-Newton model of J about the last rollout (the dynamics'
// second derivatives dropped, as iLQR does), solves it by a backward Riccati pass with
// Levenberg-Marquardt regularization of Quu, and rolls the new feedback policy
//   u_k = u_k + alpha kff_k + K_k (x_new_k - x_k)
// out through F, halving alpha until J falls by a fraction of the model's prediction.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gencoord/control/transition.hpp"
#include "gencoord/errors.hpp"

namespace gencoord::apps {

template <class M>
struct IlqrProblem {
  typename M::Params params;
  int steps = 100;           // N
  double dt = 0.02;          // the step (s)
  Eigen::VectorXd goal;      // the goal state (dim 2 nq)
  Eigen::MatrixXd Q, R, Qf;  // running state, input and final state weights
};

struct IlqrOptions {
  int max_iterations = 200;
  double tolerance = 1e-10;      // stop when a step's predicted decrease is below this x J
  double regularization = 1e-6;  // the first mu added to Quu's diagonal
};

/// A trajectory, its cost, and the last feedback gains (u = u_k + K_k (x - x_k) near it).
struct IlqrSolution {
  std::vector<Eigen::VectorXd> x;  // N + 1 states
  std::vector<Eigen::VectorXd> u;  // N inputs
  std::vector<Eigen::MatrixXd> K;  // N gains (empty until an iteration has run)
  double cost = 0.0;
  int iterations = 0;
  bool converged = false;
};

namespace detail {

struct Rollout {
  std::vector<Eigen::VectorXd> x, u;
  std::vector<Eigen::MatrixXd> A, B;
  double cost = 0.0;
};

template <class M>
double stage_cost(const IlqrProblem<M>& p, const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
  const Eigen::VectorXd e = x - p.goal;
  return 0.5 * p.dt * (e.dot(p.Q * e) + u.dot(p.R * u));
}

template <class M>
double final_cost(const IlqrProblem<M>& p, const Eigen::VectorXd& x) {
  const Eigen::VectorXd e = x - p.goal;
  return 0.5 * e.dot(p.Qf * e);
}

// x_0 = start, then F step by step; u_k = reference_u + kff_k + K_k (x_k - reference_x) where a
// policy is given, else the inputs `reference_u` as they are
template <class M>
Rollout roll_out(const IlqrProblem<M>& p, const Eigen::VectorXd& start,
                 const std::vector<Eigen::VectorXd>& reference_u,
                 const std::vector<Eigen::VectorXd>* reference_x = nullptr,
                 const std::vector<Eigen::VectorXd>* kff = nullptr,
                 const std::vector<Eigen::MatrixXd>* K = nullptr, double alpha = 0.0) {
  Rollout r;
  r.x.push_back(start);
  for (int k = 0; k < p.steps; ++k) {
    Eigen::VectorXd u = reference_u[k];
    if (K) u += alpha * (*kff)[k] + (*K)[k] * (r.x[k] - (*reference_x)[k]);
    const Transition step = rk4_transition<M>(p.params, r.x[k], InputVec<M>(u), k * p.dt, p.dt);
    r.cost += stage_cost(p, r.x[k], u);
    r.u.push_back(u);
    r.A.push_back(step.A);
    r.B.push_back(step.B);
    r.x.push_back(step.x);
  }
  r.cost += final_cost(p, r.x.back());
  return r;
}

}  // namespace detail

/// iLQR from `start`, the first guess rolled out by the policy u_k = guess.u_k + guess.K_k
/// (x_k - guess.x_k) (the inputs alone where guess.K is empty): a last plan shifted in time
/// stays near its trajectory where its inputs alone would drift off an unstable one.
/// `guess` holds N inputs and, with gains, N + 1 states; see the file comment.
/// \throws DynamicsError if the first rollout leaves the model's domain.
template <class M>
IlqrSolution ilqr(const IlqrProblem<M>& p, const Eigen::VectorXd& start, const IlqrSolution& guess,
                  const IlqrOptions& options = {}) {
  const int nu = num_inputs_v<M>, N = p.steps;
  const std::vector<Eigen::VectorXd> no_step(N, Eigen::VectorXd::Zero(nu));
  detail::Rollout r = guess.K.empty()
                          ? detail::roll_out(p, start, guess.u)
                          : detail::roll_out(p, start, guess.u, &guess.x, &no_step, &guess.K);
  IlqrSolution out;
  double mu = options.regularization;
  std::vector<Eigen::VectorXd> kff(N), trial_kff(N);  // the last whole backward pass's, and
  std::vector<Eigen::MatrixXd> K, trial_K(N);         // the one under way
  while (out.iterations < options.max_iterations) {
    ++out.iterations;
    // backward pass: V(x) ~ V + Vx' dx + 1/2 dx' Vxx dx, from the end
    Eigen::VectorXd Vx = p.Qf * (r.x[N] - p.goal);
    Eigen::MatrixXd Vxx = p.Qf;
    double predicted_linear = 0.0, predicted_quadratic = 0.0;  // J's change at alpha: a l + a^2 q
    bool definite = true;
    for (int k = N - 1; k >= 0 && definite; --k) {
      const Eigen::MatrixXd& A = r.A[k];
      const Eigen::MatrixXd& B = r.B[k];
      const Eigen::VectorXd Qx = p.dt * p.Q * (r.x[k] - p.goal) + A.transpose() * Vx;
      const Eigen::VectorXd Qu = p.dt * p.R * r.u[k] + B.transpose() * Vx;
      const Eigen::MatrixXd Qxx = p.dt * p.Q + A.transpose() * Vxx * A;
      const Eigen::MatrixXd Qux = B.transpose() * Vxx * A;
      const Eigen::MatrixXd Quu = p.dt * p.R + B.transpose() * Vxx * B;
      const Eigen::LLT<Eigen::MatrixXd> llt(Quu + mu * Eigen::MatrixXd::Identity(nu, nu));
      if (llt.info() != Eigen::Success) {
        definite = false;
        break;
      }
      const Eigen::VectorXd& k_ff = trial_kff[k] = -llt.solve(Qu);
      const Eigen::MatrixXd& K_k = trial_K[k] = -llt.solve(Qux);
      predicted_linear += k_ff.dot(Qu);
      predicted_quadratic += 0.5 * k_ff.dot(Quu * k_ff);
      Vx = Qx + K_k.transpose() * (Quu * k_ff + Qu) + Qux.transpose() * k_ff;
      Vxx = Qxx + K_k.transpose() * Quu * K_k + K_k.transpose() * Qux + Qux.transpose() * K_k;
      Vxx = 0.5 * (Vxx + Vxx.transpose()).eval();
    }
    if (!definite) {
      mu *= 10;
      if (mu > 1e10) break;
      continue;
    }
    kff = trial_kff;
    K = trial_K;
    if (-predicted_linear < options.tolerance * r.cost) {  // nothing left to gain
      out.converged = true;
      break;
    }
    bool accepted = false;
    for (double alpha = 1.0; alpha > 1e-4 && !accepted; alpha /= 2) {
      detail::Rollout trial;
      try {
        trial = detail::roll_out(p, start, r.u, &r.x, &kff, &K, alpha);
      } catch (const DynamicsError&) {  // a step too long for the model: a shorter one
        continue;
      }
      const double predicted = alpha * predicted_linear + alpha * alpha * predicted_quadratic;
      if (std::isfinite(trial.cost) && trial.cost - r.cost < 1e-4 * predicted) {
        r = std::move(trial);
        accepted = true;
      }
    }
    if (accepted) {
      mu = std::max(mu / 10, 1e-12);
    } else {
      mu *= 10;
      if (mu > 1e10) break;
    }
  }
  out.x = std::move(r.x);
  out.u = std::move(r.u);
  out.K = std::move(K);
  out.cost = r.cost;
  return out;
}

}  // namespace gencoord::apps
