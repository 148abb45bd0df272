// SPDX-License-Identifier: BSD-3-Clause
// Trajectory optimization of a generated model with control inputs by direct collocation,
// solved by IPOPT; what apps/swing_up.cpp and apps/arm_reach.cpp share.
//
// The states x_k = (q_k, v_k) and inputs u_k at K + 1 nodes over T seconds are the unknowns;
// the dynamics x' = f(x, u) hold between nodes by Hermite-Simpson collocation (the cubic
// through both nodes' states and rates; its midpoint's rate f(x_c, u_c), u_c the mean input),
// fourth-order accurate; the cost is the inputs' effort, the integral of |u|^2 by Simpson's
// rule, plus velocity_weight times the integral of |v|^2 by the trapezoidal rule (a smooth
// motion where some joints are light enough to whip for free). f and its Jacobians [df/dx, df/du]
// come from gencoord::linearize (the generated residual Jacobians and input matrix: exact), chained
// through the midpoint by hand; IPOPT approximates the Lagrangian's Hessian by L-BFGS. The start
// and the goal are fixed states; the inputs and, optionally, some coordinates have bounds. replay()
// runs the optimized inputs, piecewise quadratic in time as Simpson's rule has them, open loop
// through ControlledSystem and RK4: the test that the optimum is a motion of the model, not only of
// the collocation.
#pragma once

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <vector>

#include "gencoord/control/controlled_system.hpp"
#include "gencoord/control/linearize.hpp"
#include "gencoord/integrate/simulate.hpp"

namespace gencoord::apps {

template <class M>
struct CollocationProblem {
  static constexpr int nx = 2 * M::nq, nu = num_inputs_v<M>;
  using X = Eigen::Matrix<double, nx, 1>;
  using U = Eigen::Matrix<double, nu, 1>;
  typename M::Params params;
  int intervals = 60;     // K
  double duration = 2.0;  // T (s)
  X start = X::Zero(), goal = X::Zero();
  U input_limit = U::Constant(1e19);  // |u_i| <= input_limit_i
  X state_limit = X::Constant(1e19);  // |x_i| <= state_limit_i
  double velocity_weight = 0.0;       // the cost's weight of |v|^2
};

/// What optimize() found: the nodes' states and inputs, and IPOPT's account.
template <class M>
struct CollocationResult {
  using Problem = CollocationProblem<M>;
  std::vector<typename Problem::X> x;
  std::vector<typename Problem::U> u;
  int status = -1;  // Ipopt::ApplicationReturnStatus
  int iterations = 0;
  double seconds = 0.0, violation = 0.0, effort = 0.0;
  bool solved() const { return status == Ipopt::Solve_Succeeded; }
};

namespace detail {

template <class M>
class CollocationNlp : public Ipopt::TNLP {
  using Problem = CollocationProblem<M>;
  static constexpr int nx = Problem::nx, nu = Problem::nu, node = nx + nu;
  using X = typename Problem::X;
  using U = typename Problem::U;
  using NodeBlock = Eigen::Matrix<double, nx, node>;  // d(rows)/d(x_k, u_k)

 public:
  explicit CollocationNlp(const Problem& p) : p_(p), h_(p.duration / p.intervals) {}
  CollocationResult<M> result;

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac, Ipopt::Index& nnz_h,
                    IndexStyleEnum& style) override {
    n = (p_.intervals + 1) * node;
    m = p_.intervals * nx;
    nnz_jac = p_.intervals * nx * 2 * node;  // each defect reads both nodes' x and u
    nnz_h = 0;
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index, Ipopt::Number* lower, Ipopt::Number* upper, Ipopt::Index m,
                       Ipopt::Number* g_lower, Ipopt::Number* g_upper) override {
    for (int k = 0; k <= p_.intervals; ++k) {
      for (int i = 0; i < node; ++i) {
        const double limit = i < nx ? p_.state_limit[i] : p_.input_limit[i - nx];
        lower[k * node + i] = -limit;
        upper[k * node + i] = limit;
      }
    }
    for (int i = 0; i < nx; ++i) {
      lower[i] = upper[i] = p_.start[i];
      lower[p_.intervals * node + i] = upper[p_.intervals * node + i] = p_.goal[i];
    }
    for (Ipopt::Index j = 0; j < m; ++j) g_lower[j] = g_upper[j] = 0.0;
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool, Ipopt::Number* z, bool, Ipopt::Number*,
                          Ipopt::Number*, Ipopt::Index, bool, Ipopt::Number*) override {
    for (int k = 0; k <= p_.intervals; ++k) {  // the straight line between the ends, no input
      const double a = double(k) / p_.intervals;
      Eigen::Map<X>(z + k * node) = (1 - a) * p_.start + a * p_.goal;
      Eigen::Map<U>(z + k * node + nx).setZero();
    }
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Number& value) override {
    value = 0.0;
    for (int k = 0; k < p_.intervals; ++k) {
      const U a = u(z, k), b = u(z, k + 1), c = 0.5 * (a + b);
      value += h_ / 6 * (a.squaredNorm() + 4 * c.squaredNorm() + b.squaredNorm());
      value += p_.velocity_weight * h_ / 2 *
               (x(z, k).template tail<M::nq>().squaredNorm() +
                x(z, k + 1).template tail<M::nq>().squaredNorm());
    }
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* z, bool, Ipopt::Number* grad) override {
    std::fill(grad, grad + n, 0.0);
    for (int k = 0; k < p_.intervals; ++k) {
      const U a = u(z, k), b = u(z, k + 1), c = 0.5 * (a + b);
      Eigen::Map<U>(grad + k * node + nx) += h_ / 6 * (2 * a + 4 * c);
      Eigen::Map<U>(grad + (k + 1) * node + nx) += h_ / 6 * (2 * b + 4 * c);
      using V = Eigen::Matrix<double, M::nq, 1>;
      Eigen::Map<V>(grad + k * node + M::nq) +=
          p_.velocity_weight * h_ * x(z, k).template tail<M::nq>();
      Eigen::Map<V>(grad + (k + 1) * node + M::nq) +=
          p_.velocity_weight * h_ * x(z, k + 1).template tail<M::nq>();
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Number* g) override {
    for (int k = 0; k < p_.intervals; ++k)
      Eigen::Map<X>(g + k * nx) = defect(z, k, nullptr, nullptr);
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* rows, Ipopt::Index* columns, Ipopt::Number* values) override {
    Ipopt::Index e = 0;
    for (int k = 0; k < p_.intervals; ++k) {
      NodeBlock left, right;
      if (values) defect(z, k, &left, &right);
      for (int r = 0; r < nx; ++r) {
        for (int c = 0; c < 2 * node; ++c, ++e) {
          if (values) {
            values[e] = c < node ? left(r, c) : right(r, c - node);
          } else {
            rows[e] = k * nx + r;
            columns[e] = k * node + c;
          }
        }
      }
    }
    return true;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index iteration, Ipopt::Number,
                             Ipopt::Number inf_pr, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Index,
                             const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    result.iterations = iteration;
    result.violation = inf_pr;
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index, const Ipopt::Number* z,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Index,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number objective,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    result.x.clear();
    result.u.clear();
    for (int k = 0; k <= p_.intervals; ++k) {
      result.x.push_back(Eigen::Map<const X>(z + k * node));
      result.u.push_back(u(z, k));
    }
    result.effort = objective;
  }

 private:
  static X x(const Ipopt::Number* z, int k) { return Eigen::Map<const X>(z + k * node); }
  static U u(const Ipopt::Number* z, int k) { return Eigen::Map<const U>(z + k * node + nx); }

  // f(x, u) and [df/dx, df/du]
  void rate(const X& x, const U& u, X* f, NodeBlock* J) const {
    const LinearizedDynamics linear =
        linearize<M>(p_.params, x.template head<M::nq>(), x.template tail<M::nq>(), u, 0.0);
    *f = linear.xdot;
    J->template leftCols<nx>() = linear.A;
    J->template rightCols<nu>() = linear.B;
  }

  // Hermite-Simpson: x_c = (x0 + x1)/2 + h/8 (f0 - f1), defect x1 - x0 - h/6 (f0 + 4 fc + f1);
  // with `left`, `right` its Jacobians in (x_k, u_k) and (x_{k+1}, u_{k+1})
  X defect(const Ipopt::Number* z, int k, NodeBlock* left, NodeBlock* right) const {
    const X x0 = x(z, k), x1 = x(z, k + 1);
    const U u0 = u(z, k), u1 = u(z, k + 1), uc = 0.5 * (u0 + u1);
    X f0, f1, fc;
    NodeBlock J0, J1, Jc;
    rate(x0, u0, &f0, &J0);
    rate(x1, u1, &f1, &J1);
    rate(0.5 * (x0 + x1) + h_ / 8 * (f0 - f1), uc, &fc, &Jc);
    if (left) {
      const NodeBlock I = NodeBlock::Identity();  // the x rows of d(x_k, u_k)
      // d x_c/d node 0 = I/2 + h/8 J0, d u_c/d u_0 = I/2; likewise for node 1
      NodeBlock fc_0 = Jc.template leftCols<nx>() * (0.5 * I + h_ / 8 * J0);
      NodeBlock fc_1 = Jc.template leftCols<nx>() * (0.5 * I - h_ / 8 * J1);
      fc_0.template rightCols<nu>() += 0.5 * Jc.template rightCols<nu>();
      fc_1.template rightCols<nu>() += 0.5 * Jc.template rightCols<nu>();
      *left = -I - h_ / 6 * (J0 + 4 * fc_0);
      *right = I - h_ / 6 * (4 * fc_1 + J1);
    }
    return x1 - x0 - h_ / 6 * (f0 + 4 * fc + f1);
  }

  Problem p_;
  double h_;
};

}  // namespace detail

/// Solves the problem with IPOPT (tolerance `tolerance`); `derivative_test` has IPOPT compare
/// the constraint Jacobian with its own finite differences first, to `derivative_tolerance`
/// relative, printing the verdict.
template <class M>
CollocationResult<M> optimize(const CollocationProblem<M>& problem, double tolerance = 1e-8,
                              bool derivative_test = false, double derivative_tolerance = 1e-6) {
  Ipopt::SmartPtr<detail::CollocationNlp<M>> nlp = new detail::CollocationNlp<M>(problem);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetNumericValue("tol", tolerance);
  app->Options()->SetStringValue("hessian_approximation", "limited-memory");
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetIntegerValue("max_iter", 3000);
  if (derivative_test) {
    app->Options()->SetStringValue("derivative_test", "first-order");
    app->Options()->SetNumericValue("derivative_test_tol", derivative_tolerance);
    app->Options()->SetIntegerValue("print_level", 4);
  }
  CollocationResult<M> result;
  if (app->Initialize() != Ipopt::Solve_Succeeded) return result;
  const auto begin = std::chrono::steady_clock::now();
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
  result = nlp->result;
  result.status = static_cast<int>(status);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
}

/// The inputs at time t: per interval the quadratic through u_k, u_c and u_{k+1} (Simpson's).
template <class M>
InputVec<M> input_at(const CollocationProblem<M>& p, const CollocationResult<M>& r, double t) {
  const double h = p.duration / p.intervals;
  const int k = std::min(p.intervals - 1, std::max(0, static_cast<int>(t / h)));
  const InputVec<M> a = r.u[k], b = r.u[k + 1], c = 0.5 * (a + b);
  const double s = t / h - k;
  return a * ((1 - s) * (1 - 2 * s)) + c * (4 * s * (1 - s)) + b * (s * (2 * s - 1));
}

/// The optimized inputs run open loop by RK4 at step dt from the start; `observe(s)` sees each
/// state. Returns the end state.
template <class M, class Observer>
State<M> replay(const CollocationProblem<M>& p, const CollocationResult<M>& r, double dt,
                Observer observe) {
  ControlledSystem<M> system(
      p.params, [&](double t, const QVec<M>&, const VVec<M>&) { return input_at(p, r, t); },
      LawKind::OpenLoop);
  if constexpr (has_joint_limits_v<M>) system.set_joint_limits(false);  // bounds are the NLP's
  State<M> initial;
  initial.q = p.start.template head<M::nq>();
  initial.v = p.start.template tail<M::nq>();
  return simulate(system, initial, {Integrator::RK4, dt, p.duration}, observe);
}

}  // namespace gencoord::apps
