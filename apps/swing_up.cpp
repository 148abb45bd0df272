// SPDX-License-Identifier: BSD-3-Clause
// swing_up: the cart-pole swung up from hanging to upright by trajectory optimization
// (apps/collocation.hpp: Hermite-Simpson collocation solved by IPOPT, every Jacobian of the
// dynamics from gencoord::linearize), the cart within 1 m of the middle and the force within
// 20 N, then the optimized force replayed open loop by RK4.
//
//   swing_up [--intervals K] [--duration T] [--force-limit F] [--output-dir out]
//            [--derivative-test yes]   (IPOPT checks the Jacobians by finite differences)
//
// Prints IPOPT's iterations, time and constraint violation, and the replay's end state;
// writes <output-dir>/swing_up.csv (t, q, v, u of the replay every 10 ms). Exits 1 if IPOPT
// fails or the replay ends more than 0.05 from the upright state.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "collocation.hpp"
#include "generated/cart_pole.hpp"

int main(int argc, char** argv) {
  using M = gencoord::models::CartPole;
  gencoord::apps::CollocationProblem<M> problem;
  problem.intervals = 60;
  problem.duration = 2.0;
  problem.start << 0.0, M_PI, 0.0, 0.0;  // hanging (theta from the upward vertical)
  problem.goal.setZero();                // upright, the cart back in the middle
  problem.state_limit[0] = 1.0;          // the track
  problem.input_limit[0] = 20.0;
  std::string output_dir = "out";
  bool derivative_test = false;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--intervals") problem.intervals = std::atoi(argv[i + 1]);
    else if (option == "--duration") problem.duration = std::atof(argv[i + 1]);
    else if (option == "--force-limit") problem.input_limit[0] = std::atof(argv[i + 1]);
    else if (option == "--output-dir") output_dir = argv[i + 1];
    else if (option == "--derivative-test") derivative_test = std::string(argv[i + 1]) == "yes";
    else {
      std::fprintf(stderr, "swing_up: unknown option %s\n", option.c_str());
      return 2;
    }
  }
  if (problem.intervals < 2 || !(problem.duration > 0) || !(problem.input_limit[0] > 0)) {
    std::fprintf(stderr, "swing_up: need --intervals >= 2, --duration > 0, --force-limit > 0\n");
    return 2;
  }

  const auto result = gencoord::apps::optimize(problem, 1e-8, derivative_test);
  std::printf("swing_up: cart-pole, %d Hermite-Simpson intervals over %g s, |u| <= %g N\n",
              problem.intervals, problem.duration, problem.input_limit[0]);
  std::printf("IPOPT: status %d, %d iterations, %.3f s, constraint violation %.2e\n", result.status,
              result.iterations, result.seconds, result.violation);
  if (!result.solved()) return 1;

  std::filesystem::create_directories(output_dir);
  std::ofstream csv(output_dir + "/swing_up.csv");
  csv << "t,s,theta,s_dot,theta_dot,u\n";
  long step = 0;
  const gencoord::State<M> end =
      gencoord::apps::replay(problem, result, 1e-3, [&](const gencoord::State<M>& s) {
        if (step++ % 10) return;
        csv << s.t << ',' << s.q[0] << ',' << s.q[1] << ',' << s.v[0] << ',' << s.v[1] << ','
            << gencoord::apps::input_at(problem, result, s.t)[0] << '\n';
      });
  const double miss = std::max(end.q.cwiseAbs().maxCoeff(), end.v.cwiseAbs().maxCoeff());
  std::printf(
      "replay (RK4, dt = 1 ms, open loop): end state s = %.4f m, theta = %.4f rad, "
      "s' = %.4f m/s, theta' = %.4f rad/s; largest miss %.2e\n",
      end.q[0], end.q[1], end.v[0], end.v[1], miss);
  return miss < 0.05 ? 0 : 1;
}
