// SPDX-License-Identifier: BSD-3-Clause
// Long-run energy drift of every integrator on the generated double pendulum, released from
// theta = (pi/2, 0) at rest. Not a test: it prints a
// table, for each integrator and step size, of
//   max |E - E0| / (E0 - E_rest)   over the run,
//   the secular drift rate: the least-squares slope of E(t), per second and relative to
//   E0 - E_rest (positive: energy gained),
//   Newton iterations per implicit (half) step solve, and the wall time of the run
//   (the steps plus one energy evaluation per step).
// A run that diverges (non-finite dynamics) or whose Newton iteration fails is reported as
// such, with the time it got to.
// Usage: energy_drift [duration_s = 100] [dt ...]   (default step sizes 1e-3 and 1e-2)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "gencoord/errors.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/double_pendulum.hpp"

namespace {

using gencoord::Integrator;
using gencoord::State;
using gencoord::models::DoublePendulum;

struct DriftRow {
  Integrator integrator;
  double dt = 0;
  double max_relative_error = 0;  // max |E - E0| / (E0 - E_rest)
  double drift_rate = 0;          // least-squares slope of E(t) / (E0 - E_rest), 1/s
  double newton_per_solve = 0;    // mean Newton updates per implicit solve (0: explicit)
  double wall_seconds = 0;
  double reached = 0;   // time the run got to
  std::string failure;  // empty if the run completed
};

// the initial state: the first rod horizontal, the second hanging straight down, at rest
State<DoublePendulum> initial_state() {
  State<DoublePendulum> s;
  s.q << M_PI / 2, 0.0;
  return s;
}

// E0 - E_rest: the energy available to the motion, the scale of the relative errors
double energy_scale(const DoublePendulum::Params& p) {
  const State<DoublePendulum> s = initial_state();
  const gencoord::QVec<DoublePendulum> zero = gencoord::QVec<DoublePendulum>::Zero();
  return DoublePendulum::energy(s.q, s.v, s.t, p) - DoublePendulum::energy(zero, zero, 0.0, p);
}

DriftRow measure(Integrator integrator, double dt, double duration) {
  const DoublePendulum::Params p;
  const State<DoublePendulum> s = initial_state();
  const double e0 = DoublePendulum::energy(s.q, s.v, s.t, p);
  const double scale = energy_scale(p);

  DriftRow row;
  row.integrator = integrator;
  row.dt = dt;
  // sums of the least-squares line through (t, E - E0), centred on the middle of the run
  double n = 0, st = 0, se = 0, stt = 0, ste = 0, worst = 0;
  gencoord::StepStats stats;
  const auto start = std::chrono::steady_clock::now();
  try {
    gencoord::simulate(gencoord::ReducedSystem<DoublePendulum>(p), s,
                       {integrator, dt, duration, gencoord::NewtonOptions{}, &stats},
                       [&](const State<DoublePendulum>& x) {
                         const double de = DoublePendulum::energy(x.q, x.v, x.t, p) - e0;
                         const double tc = x.t - 0.5 * duration;
                         worst = std::max(worst, std::abs(de));
                         n += 1;
                         st += tc;
                         se += de;
                         stt += tc * tc;
                         ste += tc * de;
                         row.reached = x.t;
                       });
  } catch (const std::exception& e) {
    row.failure = e.what();
  }
  row.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.max_relative_error = worst / scale;
  row.drift_rate = n > 1 ? (n * ste - st * se) / (n * stt - st * st) / scale : 0.0;
  if (stats.newton_solves > 0)
    row.newton_per_solve =
        static_cast<double>(stats.newton_iterations) / static_cast<double>(stats.newton_solves);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const double duration = argc > 1 ? std::atof(argv[1]) : 100.0;
  std::vector<double> dts;
  for (int i = 2; i < argc; ++i) dts.push_back(std::atof(argv[i]));
  if (dts.empty()) dts = {1e-3, 1e-2};
  if (!(duration > 0) || std::any_of(dts.begin(), dts.end(), [](double d) { return !(d > 0); })) {
    std::fprintf(stderr, "usage: energy_drift [duration_s > 0] [dt > 0 ...]\n");
    return 2;
  }
  const Integrator integrators[] = {Integrator::ForwardEuler, Integrator::SymplecticEuler,
                                    Integrator::RK4,          Integrator::BackwardEuler,
                                    Integrator::Trapezoidal,  Integrator::ImplicitMidpoint};

  std::printf("double pendulum from theta = (pi/2, 0) at rest, %g s; E0 - E_rest = %.4f J\n",
              duration, energy_scale(DoublePendulum::Params{}));
  std::printf("%-18s %8s %16s %22s %12s %10s\n", "integrator", "dt", "max|dE|/(E0-Er)",
              "drift rate (1/s)", "newton/solve", "wall (s)");
  for (double dt : dts) {
    for (Integrator integrator : integrators) {
      const DriftRow r = measure(integrator, dt, duration);
      std::printf("%-18s %8.0e %16.3e %+22.3e %12.2f %10.3f", gencoord::to_string(integrator), r.dt,
                  r.max_relative_error, r.drift_rate, r.newton_per_solve, r.wall_seconds);
      if (!r.failure.empty()) std::printf("   FAILED at t = %.3f s", r.reached);
      std::printf("\n");
      if (!r.failure.empty()) std::printf("    %s\n", r.failure.c_str());
    }
  }
  return 0;
}
