// SPDX-License-Identifier: BSD-3-Clause
// swing_up: the cart-pole swung up from hanging to upright by trajectory optimization, direct
// collocation solved by IPOPT, every Jacobian of the dynamics from the generated derivatives.
//
// The states x_k = (s, theta, s', theta') and forces u_k at K + 1 nodes over T seconds are the
// unknowns; the dynamics x' = f(x, u) hold between nodes by Hermite-Simpson collocation (the
// cubic through both nodes' states and rates, its midpoint's rate f(x_c, u_c) with u_c the
// mean force), which is fourth-order accurate; the cost is the force's effort, the integral of
// u^2 by Simpson's rule. f's Jacobians [df/dx, df/du] come from gencoord::linearize (the
// generated residual Jacobians and input matrix: exact), chained through the midpoint by hand;
// IPOPT approximates the Lagrangian's Hessian by L-BFGS. The optimized forces, a piecewise
// quadratic in time, are then replayed open loop by the runtime's RK4 (ControlledSystem),
// which must reach the upright state: the test that the optimum is a motion of the model and
// not of the collocation alone.
//
//   swing_up [--nodes K] [--duration T] [--force-limit F] [--output-dir out]
//            [--derivative-test yes]   (IPOPT checks the Jacobians by finite differences)
//
// Prints IPOPT's iterations, time and constraint violation, and the replay's end state;
// writes <output-dir>/swing_up.csv (t, q, v, u of the replay every 10 ms). Exits 1 if IPOPT
// fails or the replay ends more than 0.05 from the upright state.
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <Eigen/Core>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gencoord/control/controlled_system.hpp"
#include "gencoord/control/linearize.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "generated/cart_pole.hpp"

namespace {

using M = gencoord::models::CartPole;
constexpr int kStates = 2 * M::nq;  // x = (q, v)
using Vec = Eigen::Matrix<double, kStates, 1>;
using Jac = Eigen::Matrix<double, kStates, kStates + 1>;  // [df/dx, df/du]

struct Problem {
  int nodes = 60;             // K intervals
  double duration = 2.0;      // T (s)
  double force_limit = 20.0;  // |u| <= F (N)
  double track = 1.0;         // |s| <= track (m)
};

// f(x, u) and its Jacobian from the generated kernels
struct Dynamics {
  M::Params params;
  Vec f(const Vec& x, double u) const {
    const auto linear = gencoord::linearize<M>(params, x.head<M::nq>(), x.tail<M::nq>(),
                                               gencoord::InputVec<M>::Constant(u), 0.0);
    return linear.xdot;
  }
  void f_and_jacobian(const Vec& x, double u, Vec* f, Jac* J) const {
    const auto linear = gencoord::linearize<M>(params, x.head<M::nq>(), x.tail<M::nq>(),
                                               gencoord::InputVec<M>::Constant(u), 0.0);
    *f = linear.xdot;
    J->leftCols<kStates>() = linear.A;
    J->rightCols<1>() = linear.B;
  }
};

/// The NLP: z = (x_0, u_0, x_1, u_1, ..., x_K, u_K); one collocation defect of kStates rows
/// per interval, and the two end states fixed by bounds.
class SwingUp : public Ipopt::TNLP {
 public:
  SwingUp(const Problem& problem, const Vec& start, const Vec& goal)
      : p_(problem), start_(start), goal_(goal), h_(problem.duration / problem.nodes) {}

  std::vector<double> solution;
  int iterations = 0;
  double violation = 0.0;

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac, Ipopt::Index& nnz_h,
                    IndexStyleEnum& style) override {
    n = (p_.nodes + 1) * kNode;
    m = p_.nodes * kStates;
    nnz_jac = p_.nodes * kStates * 2 * kNode;  // each defect reads both nodes' x and u
    nnz_h = 0;
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* lower, Ipopt::Number* upper, Ipopt::Index m,
                       Ipopt::Number* g_lower, Ipopt::Number* g_upper) override {
    for (Ipopt::Index i = 0; i < n; ++i) {
      lower[i] = -2e19;
      upper[i] = 2e19;
    }
    for (int k = 0; k <= p_.nodes; ++k) {
      lower[k * kNode] = -p_.track;  // the cart stays on its track
      upper[k * kNode] = p_.track;
      lower[k * kNode + kStates] = -p_.force_limit;
      upper[k * kNode + kStates] = p_.force_limit;
    }
    for (int i = 0; i < kStates; ++i) {
      lower[i] = upper[i] = start_[i];
      lower[p_.nodes * kNode + i] = upper[p_.nodes * kNode + i] = goal_[i];
    }
    for (Ipopt::Index j = 0; j < m; ++j) g_lower[j] = g_upper[j] = 0.0;
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool, Ipopt::Number* z, bool, Ipopt::Number*,
                          Ipopt::Number*, Ipopt::Index, bool, Ipopt::Number*) override {
    for (int k = 0; k <= p_.nodes; ++k) {  // the straight line between the ends, no force
      const double a = double(k) / p_.nodes;
      for (int i = 0; i < kStates; ++i) z[k * kNode + i] = (1 - a) * start_[i] + a * goal_[i];
      z[k * kNode + kStates] = 0.0;
    }
    return true;
  }

  // effort: Simpson's rule on u^2 over each interval, u_c = (u_k + u_{k+1}) / 2
  bool eval_f(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Number& value) override {
    value = 0.0;
    for (int k = 0; k < p_.nodes; ++k) {
      const double a = u(z, k), b = u(z, k + 1), c = 0.5 * (a + b);
      value += h_ / 6 * (a * a + 4 * c * c + b * b);
    }
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* z, bool, Ipopt::Number* grad) override {
    for (Ipopt::Index i = 0; i < n; ++i) grad[i] = 0.0;
    for (int k = 0; k < p_.nodes; ++k) {
      const double a = u(z, k), b = u(z, k + 1), c = 0.5 * (a + b);
      grad[k * kNode + kStates] += h_ / 6 * (2 * a + 4 * c);
      grad[(k + 1) * kNode + kStates] += h_ / 6 * (2 * b + 4 * c);
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Number* g) override {
    for (int k = 0; k < p_.nodes; ++k) {
      Eigen::Map<Vec>(g + k * kStates) = defect(z, k, nullptr, nullptr);
    }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* rows, Ipopt::Index* columns, Ipopt::Number* values) override {
    Ipopt::Index e = 0;
    for (int k = 0; k < p_.nodes; ++k) {
      Eigen::Matrix<double, kStates, kNode> left, right;
      if (values) defect(z, k, &left, &right);
      for (int r = 0; r < kStates; ++r) {
        for (int c = 0; c < 2 * kNode; ++c, ++e) {
          if (values) {
            values[e] = c < kNode ? left(r, c) : right(r, c - kNode);
          } else {
            rows[e] = k * kStates + r;
            columns[e] = k * kNode + c;
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
    iterations = iteration;
    violation = inf_pr;
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* z,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Index,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution.assign(z, z + n);
  }

 private:
  static constexpr int kNode = kStates + 1;  // x_k, u_k

  static Vec x(const Ipopt::Number* z, int k) { return Eigen::Map<const Vec>(z + k * kNode); }
  static double u(const Ipopt::Number* z, int k) { return z[k * kNode + kStates]; }

  // Hermite-Simpson: x_c = (x0 + x1)/2 + h/8 (f0 - f1), defect x1 - x0 - h/6 (f0 + 4 fc + f1);
  // with `left`, `right` its Jacobians in (x_k, u_k) and (x_{k+1}, u_{k+1})
  Vec defect(const Ipopt::Number* z, int k, Eigen::Matrix<double, kStates, kNode>* left,
             Eigen::Matrix<double, kStates, kNode>* right) const {
    const Vec x0 = x(z, k), x1 = x(z, k + 1);
    const double u0 = u(z, k), u1 = u(z, k + 1), uc = 0.5 * (u0 + u1);
    Vec f0, f1, fc;
    Jac J0, J1, Jc;
    dynamics_.f_and_jacobian(x0, u0, &f0, &J0);
    dynamics_.f_and_jacobian(x1, u1, &f1, &J1);
    const Vec xc = 0.5 * (x0 + x1) + h_ / 8 * (f0 - f1);
    dynamics_.f_and_jacobian(xc, uc, &fc, &Jc);
    if (left) {
      using Block = Eigen::Matrix<double, kStates, kNode>;
      const Block I = Block::Identity();  // d(x_k, u_k)/d(x_k, u_k) restricted to x
      // d x_c / d(node 0) = I/2 + h/8 J0 (its x rows), du_c/du_0 = 1/2; likewise for node 1
      Block xc_0 = 0.5 * I + h_ / 8 * J0, xc_1 = 0.5 * I - h_ / 8 * J1;
      Block fc_0 = Jc.leftCols<kStates>() * xc_0, fc_1 = Jc.leftCols<kStates>() * xc_1;
      fc_0.col(kStates) += 0.5 * Jc.col(kStates);
      fc_1.col(kStates) += 0.5 * Jc.col(kStates);
      *left = -I - h_ / 6 * (J0 + 4 * fc_0);
      *right = I - h_ / 6 * (4 * fc_1 + J1);
    }
    return x1 - x0 - h_ / 6 * (f0 + 4 * fc + f1);
  }

  Problem p_;
  Vec start_, goal_;
  double h_;
  Dynamics dynamics_;
};

// the force at time t of the piecewise quadratic through u_k, u_c, u_{k+1} (Simpson's nodes)
double force_at(const std::vector<double>& z, const Problem& p, double t) {
  constexpr int node = kStates + 1;
  const double h = p.duration / p.nodes;
  const int k = std::min(p.nodes - 1, std::max(0, static_cast<int>(t / h)));
  const double a = z[k * node + kStates], b = z[(k + 1) * node + kStates];
  const double c = 0.5 * (a + b), s = t / h - k;
  return a * (1 - s) * (1 - 2 * s) + 4 * c * s * (1 - s) + b * s * (2 * s - 1);
}

}  // namespace

int main(int argc, char** argv) {
  Problem problem;
  std::string output_dir = "out";
  bool derivative_test = false;  // IPOPT compares eval_jac_g with its own finite differences
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--nodes") problem.nodes = std::atoi(argv[i + 1]);
    else if (option == "--duration") problem.duration = std::atof(argv[i + 1]);
    else if (option == "--force-limit") problem.force_limit = std::atof(argv[i + 1]);
    else if (option == "--output-dir") output_dir = argv[i + 1];
    else if (option == "--derivative-test") derivative_test = std::string(argv[i + 1]) == "yes";
    else {
      std::fprintf(stderr, "swing_up: unknown option %s\n", option.c_str());
      return 2;
    }
  }
  if (problem.nodes < 2 || !(problem.duration > 0) || !(problem.force_limit > 0)) {
    std::fprintf(stderr, "swing_up: need --nodes >= 2, --duration > 0, --force-limit > 0\n");
    return 2;
  }
  Vec start, goal;
  start << 0.0, M_PI, 0.0, 0.0;  // hanging (theta from the upward vertical)
  goal.setZero();                // upright, the cart back at 0

  Ipopt::SmartPtr<SwingUp> nlp = new SwingUp(problem, start, goal);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetNumericValue("tol", 1e-8);
  app->Options()->SetStringValue("hessian_approximation", "limited-memory");
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetIntegerValue("max_iter", 1000);
  if (derivative_test) {
    app->Options()->SetStringValue("derivative_test", "first-order");
    app->Options()->SetNumericValue("derivative_test_tol", 1e-6);
    app->Options()->SetIntegerValue("print_level", 4);
  }
  if (app->Initialize() != Ipopt::Solve_Succeeded) return 1;
  const auto begin = std::chrono::steady_clock::now();
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  std::printf("swing_up: cart-pole, %d Hermite-Simpson intervals over %g s, |u| <= %g N\n",
              problem.nodes, problem.duration, problem.force_limit);
  std::printf("IPOPT: status %d, %d iterations, %.3f s, constraint violation %.2e\n",
              static_cast<int>(status), nlp->iterations, seconds, nlp->violation);
  if (status != Ipopt::Solve_Succeeded && status != Ipopt::Solved_To_Acceptable_Level) return 1;

  // the optimized forces replayed open loop by RK4
  const std::vector<double> z = nlp->solution;
  const gencoord::ControlledSystem<M> system(
      M::Params{},
      [&](double t, const gencoord::QVec<M>&, const gencoord::VVec<M>&) {
        return gencoord::InputVec<M>::Constant(force_at(z, problem, t));
      },
      gencoord::LawKind::OpenLoop);
  gencoord::State<M> initial;
  initial.q = start.head<M::nq>();
  initial.v = start.tail<M::nq>();
  std::filesystem::create_directories(output_dir);
  std::ofstream csv(output_dir + "/swing_up.csv");
  csv << "t,s,theta,s_dot,theta_dot,u\n";
  long step = 0;
  const gencoord::State<M> end =
      gencoord::simulate(system, initial, {gencoord::Integrator::RK4, 1e-3, problem.duration},
                         [&](const gencoord::State<M>& s) {
                           if (step++ % 10) return;
                           csv << s.t << ',' << s.q[0] << ',' << s.q[1] << ',' << s.v[0] << ','
                               << s.v[1] << ',' << force_at(z, problem, s.t) << '\n';
                         });
  Vec last;
  last << end.q, end.v;
  const double miss = (last - goal).lpNorm<Eigen::Infinity>();
  std::printf(
      "replay (RK4, dt = 1 ms, open loop): end state s = %.4f m, theta = %.4f rad, "
      "s' = %.4f m/s, theta' = %.4f rad/s; largest miss %.2e\n",
      end.q[0], end.q[1], end.v[0], end.v[1], miss);
  return miss < 0.05 ? 0 : 1;
}
