// SPDX-License-Identifier: BSD-3-Clause
// mpc_swing_up: the cart-pole swung up and balanced by model-predictive control, iLQR
// (apps/ilqr.hpp) re-solved at every control period from the measured state, every Jacobian
// from gencoord::rk4_transition (gencoord::linearize at each RK4 stage).
//
//   mpc_swing_up [--mass-error E] [--duration T] [--output-dir out]
//
// First iLQR plans the swing-up from hanging (2.5 s, 20 ms steps) to convergence. Then the
// closed loop runs: every 20 ms the controller takes the plant's state, warm-starts iLQR with
// its last plan shifted by one step, runs at most kMpcIterations iterations over a 2 s horizon
// and holds the first input for the period. The plant is the same model with the pole's mass
// off by the factor 1 + E (default 0.2), integrated by RK4 at 1 ms: the feedback, not the plan,
// must bring the pole up (the plan alone, open loop, misses; it prints by how much). Prints the
// plan's iterations and time, the controller's time per period (median and worst, against the 20 ms
// it has), and the state at the end; writes <output-dir>/mpc_swing_up.csv (t, s, theta, s', theta',
// u every period). Exits 1 unless the plant ends within 0.05 of upright at rest.
#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "generated/cart_pole.hpp"
#include "ilqr.hpp"

namespace {

using M = gencoord::models::CartPole;
constexpr double kPeriod = 0.02;     // control period and iLQR step (s)
constexpr int kPlanSteps = 125;      // the offline plan: 2.5 s
constexpr int kHorizonSteps = 100;   // the controller's horizon: 2 s
constexpr int kMpcIterations = 3;    // iLQR iterations per control period
constexpr double kPlantStep = 1e-3;  // the plant's RK4 step (s)
constexpr double kReached = 0.05;    // largest |x - upright| allowed at the end

gencoord::apps::IlqrProblem<M> swing_up_problem(int steps) {
  gencoord::apps::IlqrProblem<M> p;
  p.steps = steps;
  p.dt = kPeriod;
  p.goal = Eigen::VectorXd::Zero(4);                       // upright, the cart in the middle
  p.Q = Eigen::Vector4d(1.0, 1.0, 0.1, 0.1).asDiagonal();  // s, theta, s', theta'
  p.R = Eigen::MatrixXd::Constant(1, 1, 0.01);
  p.Qf = Eigen::Vector4d(100.0, 1000.0, 100.0, 100.0).asDiagonal();
  return p;
}

// the next period's first guess: this period's plan one step on, its last step repeated
gencoord::apps::IlqrSolution shifted(const gencoord::apps::IlqrSolution& plan) {
  gencoord::apps::IlqrSolution next;
  next.x.assign(plan.x.begin() + 1, plan.x.end());
  next.x.push_back(plan.x.back());
  next.u.assign(plan.u.begin() + 1, plan.u.end());
  next.u.push_back(plan.u.back());
  if (!plan.K.empty()) {
    next.K.assign(plan.K.begin() + 1, plan.K.end());
    next.K.push_back(plan.K.back());
  }
  return next;
}

// the plant over one control period, the input held: RK4 steps of kPlantStep
Eigen::VectorXd plant_period(const M::Params& plant, Eigen::VectorXd x, const Eigen::VectorXd& u) {
  for (int j = 0; j * kPlantStep < kPeriod - 1e-12; ++j)
    x = gencoord::rk4_transition<M>(plant, x, gencoord::InputVec<M>(u), 0.0, kPlantStep).x;
  return x;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  double mass_error = 0.2, duration = 5.0;
  std::string output_dir = "out";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--mass-error") mass_error = std::atof(argv[i + 1]);
    else if (option == "--duration") duration = std::atof(argv[i + 1]);
    else if (option == "--output-dir") output_dir = argv[i + 1];
    else {
      std::fprintf(stderr, "mpc_swing_up: unknown option %s\n", option.c_str());
      return 2;
    }
  }
  if (!(mass_error > -1) || !(duration > 0)) {
    std::fprintf(stderr, "mpc_swing_up: need --mass-error > -1 and --duration > 0\n");
    return 2;
  }
  try {
    const Eigen::Vector4d hanging(0.0, M_PI, 0.0, 0.0);
    const auto planned_problem = swing_up_problem(kPlanSteps);
    const auto plan_start = std::chrono::steady_clock::now();
    gencoord::apps::IlqrSolution rest;  // the first guess: no force
    rest.u.assign(kPlanSteps, Eigen::VectorXd::Zero(1));
    const gencoord::apps::IlqrSolution plan = gencoord::apps::ilqr(planned_problem, hanging, rest);
    const double plan_seconds = seconds_since(plan_start);
    double largest_force = 0.0;
    for (const auto& u : plan.u) largest_force = std::max(largest_force, std::abs(u[0]));
    std::printf(
        "plan: iLQR, %d steps of %g s, %d iterations%s, %.3f s; cost %.6g, end state off upright "
        "by %.2e, largest |u| %.2f N\n",
        kPlanSteps, kPeriod, plan.iterations, plan.converged ? " (converged)" : " (NOT converged)",
        plan_seconds, plan.cost, (plan.x.back() - planned_problem.goal).cwiseAbs().maxCoeff(),
        largest_force);
    if (!plan.converged) return 1;

    // the closed loop: the controller's model has the nominal parameters, the plant does not
    auto controller = swing_up_problem(kHorizonSteps);
    M::Params plant = controller.params;
    plant.m_pole *= 1 + mass_error;
    gencoord::apps::IlqrSolution warm;  // the plan's first horizon, its policy included
    warm.x.assign(plan.x.begin(), plan.x.begin() + kHorizonSteps + 1);
    warm.u.assign(plan.u.begin(), plan.u.begin() + kHorizonSteps);
    warm.K.assign(plan.K.begin(), plan.K.begin() + kHorizonSteps);
    gencoord::apps::IlqrOptions options;
    options.max_iterations = kMpcIterations;
    std::filesystem::create_directories(output_dir);
    std::ofstream csv(output_dir + "/mpc_swing_up.csv");
    csv << "t,s,theta,s_dot,theta_dot,u\n";
    Eigen::VectorXd x = hanging;
    // the plan alone, open loop on the plant: what the feedback has to make up for
    Eigen::VectorXd open_loop = hanging;
    for (const Eigen::VectorXd& u : plan.u) open_loop = plant_period(plant, open_loop, u);
    std::printf("the plan open loop on the plant: off upright by %.2e at t = %g s\n",
                open_loop.cwiseAbs().maxCoeff(), kPlanSteps * kPeriod);
    std::vector<double> solve_seconds;
    const int periods = static_cast<int>(std::lround(duration / kPeriod));
    for (int k = 0; k < periods; ++k) {
      const auto solve_start = std::chrono::steady_clock::now();
      const gencoord::apps::IlqrSolution now = gencoord::apps::ilqr(controller, x, warm, options);
      solve_seconds.push_back(seconds_since(solve_start));
      const Eigen::VectorXd u = now.u[0];
      csv << k * kPeriod << ',' << x[0] << ',' << x[1] << ',' << x[2] << ',' << x[3] << ',' << u[0]
          << '\n';
      x = plant_period(plant, x, u);
      warm = shifted(now);
    }
    std::sort(solve_seconds.begin(), solve_seconds.end());
    const double miss = x.cwiseAbs().maxCoeff();
    std::printf(
        "closed loop: pole mass off by %+.0f%%, %d periods of %g s, at most %d iLQR iterations "
        "over %d steps each; controller time per period: median %.2f ms, worst %.2f ms\n",
        100 * mass_error, periods, kPeriod, kMpcIterations, kHorizonSteps,
        1e3 * solve_seconds[solve_seconds.size() / 2], 1e3 * solve_seconds.back());
    std::printf(
        "end (t = %g s): s = %.4f m, theta = %.4f rad, s' = %.4f m/s, theta' = %.4f rad/s; "
        "largest |x| %.2e\n",
        periods * kPeriod, x[0], x[1], x[2], x[3], miss);
    return miss < kReached ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "mpc_swing_up: %s\n", error.what());
    return 1;
  }
}
