// SPDX-License-Identifier: BSD-3-Clause
// arm_reach: a point-to-point motion of the 7-joint KUKA iiwa 14 (apps/iiwa14_torques.py: the
// URDF arm with a motor torque on each joint) by trajectory optimization (apps/collocation.hpp:
// Hermite-Simpson collocation solved by IPOPT, every Jacobian of the dynamics from
// gencoord::linearize): from rest at the zero pose to rest at a reaching pose in 1 s under
// gravity, each torque within its joint's effort rating (the URDF's <limit effort>, 300 N m)
// and each joint within its URDF limits, with
// the least torque effort and a little of the joints' speeds; then the optimized torques
// replayed open loop by RK4. The wrist's damping on its light last links decays in about
// 2 ms, far below the 25 ms intervals: the first and last nodes carry wrist speeds that the
// replay's damping takes out at once, and the replay is held to the goal, not to every node.
//
//   arm_reach [--intervals K] [--duration T] [--derivative-test yes]
//
// Prints IPOPT's iterations, time and constraint violation, the replay's largest miss of the
// goal and the largest torque as a share of its joint's effort rating; exits 1 if IPOPT fails,
// the replay ends more than 0.05 from the goal or a torque exceeds its rating.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "collocation.hpp"
#include "gencoord/control/inputs.hpp"
#include "generated/iiwa14_torques.hpp"

namespace {

using M = gencoord::models::Iiwa14Torques;
using Problem = gencoord::apps::CollocationProblem<M>;

// The largest |generalized force of the inputs u at a joint| / its effort rating, at state x.
double effort_share(const Problem& problem, const Problem::X& x, const Problem::U& u) {
  gencoord::State<M> state;
  state.q = x.head<M::nq>();
  state.v = x.tail<M::nq>();
  const auto efforts =
      gencoord::input_efforts<M>(state, gencoord::with_inputs<M>(problem.params, u));
  double share = 0.0;
  for (int l = 0; l < M::num_limits; ++l)
    share = std::max(share, std::abs(efforts[l]) / M::effort_limits[l]);
  return share;
}

}  // namespace

int main(int argc, char** argv) {
  Problem problem;
  problem.intervals = 40;
  problem.duration = 1.0;
  problem.start.setZero();
  problem.goal.setZero();
  problem.goal.head<M::nq>() << 0.8, 0.6, -0.4, -1.2, 0.3, 0.9, 0.5;  // rad
  // each motor's bound: the effort rating of the joint whose speed its unit torque drives
  for (int k = 0; k < M::num_inputs; ++k) {
    const auto efforts = gencoord::input_efforts<M>(
        gencoord::State<M>{}, gencoord::with_inputs<M>(problem.params, Problem::U::Unit(k)));
    for (int l = 0; l < M::num_limits; ++l)
      if (efforts[l] == 1.0) problem.input_limit[k] = M::effort_limits[l];
  }
  problem.velocity_weight = 10.0;          // (N m)^2 per (rad/s)^2: no whipping of the light wrist
  for (int l = 0; l < M::num_limits; ++l)  // the URDF's ranges, symmetric about 0 here
    problem.state_limit[M::limited_coordinates[l]] =
        std::min(-M::lower_limits[l], M::upper_limits[l]);
  bool derivative_test = false;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--intervals") problem.intervals = std::atoi(argv[i + 1]);
    else if (option == "--duration") problem.duration = std::atof(argv[i + 1]);
    else if (option == "--derivative-test") derivative_test = std::string(argv[i + 1]) == "yes";
    else {
      std::fprintf(stderr, "arm_reach: unknown option %s\n", option.c_str());
      return 2;
    }
  }
  if (problem.intervals < 2 || !(problem.duration > 0)) {
    std::fprintf(stderr, "arm_reach: need --intervals >= 2 and --duration > 0\n");
    return 2;
  }

  // the checker's forward differences (step 1e-8) err by up to 9e-5 relative here, at 40
  // intervals: the wrist is light and damped, its rates' second derivatives large (central
  // differences of linearize agree with it to 1e-10)
  const auto result = gencoord::apps::optimize(problem, 1e-8, derivative_test, 1e-4);
  std::printf(
      "arm_reach: iiwa14, %d Hermite-Simpson intervals over %g s, |tau| within the joints' "
      "effort ratings (%g to %g N m)\n",
      problem.intervals, problem.duration, problem.input_limit.minCoeff(),
      problem.input_limit.maxCoeff());
  std::printf("IPOPT: status %d, %d iterations, %.3f s, constraint violation %.2e\n", result.status,
              result.iterations, result.seconds, result.violation);
  if (!result.solved()) return 1;

  const double h = problem.duration / problem.intervals;
  double gap = 0.0;  // the replay's largest distance from the optimized nodes
  const gencoord::State<M> end =
      gencoord::apps::replay(problem, result, 1e-3, [&](const gencoord::State<M>& s) {
        const double node = s.t / h;
        const int k = static_cast<int>(std::lround(node));
        if (std::abs(node - k) > 1e-6) return;
        Problem::X x;
        x << s.q, s.v;
        gap = std::max(gap, (x - result.x[k]).cwiseAbs().maxCoeff());
      });
  const double miss = std::max((end.q - problem.goal.head<M::nq>()).cwiseAbs().maxCoeff(),
                               end.v.cwiseAbs().maxCoeff());
  double peak = 0.0, share = 0.0;
  for (std::size_t k = 0; k < result.u.size(); ++k) {
    peak = std::max(peak, result.u[k].cwiseAbs().maxCoeff());
    share = std::max(share, effort_share(problem, result.x[k], result.u[k]));
  }
  std::printf(
      "replay (RK4, dt = 1 ms, open loop): largest miss of the goal %.2e (rad, rad/s), "
      "of a node %.2e; largest torque %.1f N m, %.0f%% of its joint's effort rating\n",
      miss, gap, peak, 100.0 * share);
  return miss < 0.05 && share <= 1.0 + 1e-9 ? 0 : 1;
}
