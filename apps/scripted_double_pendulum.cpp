// SPDX-License-Identifier: BSD-3-Clause
// scripted_double_pendulum: drives the double pendulum's first joint along a prescribed
// motion, theta1(t) = A sin(2 pi f t), lets the second joint swing freely, and writes the free
// joint's trajectory and the driving torque to CSV.
//
//   scripted_double_pendulum [--amplitude 0.5] [--frequency 0.8] [--integrator rk4]
//                            [--dt 1e-3] [--duration 10]
//                            [--output out/scripted_double_pendulum.csv]
//
// CSV columns: t, theta1, theta1_dot, theta2, theta2_dot, tau1 (the torque the first joint's
// actuator must supply, N m), energy. Prints a short summary.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include "command_line.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/io/output_file.hpp"
#include "gencoord/scripted/model.hpp"
#include "generated/double_pendulum.hpp"

namespace {

using DP = gencoord::models::DoublePendulum;

struct Options {
  double amplitude = 0.5;  // rad
  double frequency = 0.8;  // Hz
  std::string integrator = "rk4";
  double dt = 1e-3;
  double duration = 10.0;
  std::string output = "out/scripted_double_pendulum.csv";
};

[[noreturn]] void usage(int status) {
  std::cerr << "usage: scripted_double_pendulum [--amplitude A] [--frequency F] "
               "[--integrator NAME]\n"
               "                                [--dt DT] [--duration T] [--output FILE.csv]\n"
               "  theta1(t) = A sin(2 pi F t) is scripted, theta2 is free; defaults A = 0.5 rad,\n"
               "  F = 0.8 Hz, rk4, dt 1e-3 s, 10 s, out/scripted_double_pendulum.csv\n"
               "  integrators: "
            << gencoord::integrator_names() << '\n';
  std::exit(status);
}

double parse_number(const char* text, const char* what) {
  return gencoord::drivers::parse_number("scripted_double_pendulum", text, what);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") usage(0);
    if (i + 1 >= argc) usage(2);
    const char* value = argv[++i];
    if (arg == "--amplitude") o.amplitude = parse_number(value, "--amplitude");
    else if (arg == "--frequency") o.frequency = parse_number(value, "--frequency");
    else if (arg == "--integrator") o.integrator = value;
    else if (arg == "--dt") o.dt = parse_number(value, "--dt");
    else if (arg == "--duration") o.duration = parse_number(value, "--duration");
    else if (arg == "--output") o.output = value;
    else usage(2);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  using namespace gencoord;
  const Options o = parse(argc, argv);
  const Integrator integrator = parse_integrator(o.integrator);
  const double A = o.amplitude, w = 2.0 * M_PI * o.frequency;

  // theta1 scripted (coordinate 0), theta2 free
  const Script script = Script::from_function({0}, [A, w](double t) {
    ScriptSample s{Eigen::VectorXd(1), Eigen::VectorXd(1), Eigen::VectorXd(1)};
    s.q[0] = A * std::sin(w * t);
    s.v[0] = A * w * std::cos(w * t);
    s.a[0] = -A * w * w * std::sin(w * t);
    return s;
  });
  const DP::Params p;
  const ScriptedModel<DP> sm(p, script);

  OutputFile file(o.output);  // throws OutputError (with the path) if it cannot be written
  std::ostream& csv = file.stream();
  csv.precision(17);
  csv << "t,theta1,theta1_dot,theta2,theta2_dot,tau1,energy\n";
  double max_tau = 0.0, max_theta2 = 0.0, work = 0.0, previous_power = 0.0;
  long rows = 0;
  State<DP> initial;  // hanging at rest; theta1 and its rate come from the script
  StepStats stats;
  const auto start = std::chrono::steady_clock::now();
  const State<DP> end =
      simulate(sm, initial, {integrator, o.dt, o.duration, {}, &stats}, [&](const State<DP>& s) {
        const double tau = sm.driving_force(s)[0];
        csv << s.t << ',' << s.q[0] << ',' << s.v[0] << ',' << s.q[1] << ',' << s.v[1] << ',' << tau
            << ',' << DP::energy(s.q, s.v, s.t, p) << '\n';
        // work done by the actuator, trapezoidal rule on the power tau * theta1_dot
        const double power = tau * s.v[0];
        if (rows > 0) work += 0.5 * o.dt * (power + previous_power);
        previous_power = power;
        max_tau = std::max(max_tau, std::abs(tau));
        max_theta2 = std::max(max_theta2, std::abs(s.q[1]));
        file.check();
        ++rows;
      });
  file.close();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const double E0 = DP::energy(sm.imposed(initial).q, sm.imposed(initial).v, 0.0, p);
  const double E1 = DP::energy(end.q, end.v, end.t, p);
  std::printf("scripted    theta1(t) = %g sin(2 pi %g t) rad; theta2 free\n", A, o.frequency);
  std::printf("integrator  %s, dt = %g s, %ld steps to t = %g s (%.3f ms wall, CSV included)\n",
              to_string(integrator), o.dt, rows - 1, o.duration, 1e3 * wall);
  std::printf("free joint  max |theta2| = %.4f rad, final theta2 = %.6f rad\n", max_theta2,
              end.q[1]);
  std::printf("torque      max |tau1| = %.4f N m\n", max_tau);
  std::printf(
      "energy      E(end) - E(0) = %.6f J, actuator work = %.6f J: the difference "
      "%.2e J is the integrator's energy error\n",
      E1 - E0, work, E1 - E0 - work);
  if (is_implicit(integrator))
    std::printf("newton      %.2f iterations per solve (max %d)\n",
                double(stats.newton_iterations) / std::max(1L, stats.newton_solves),
                stats.max_newton_iterations);
  std::printf("trajectory  %s (%ld rows)\n", o.output.c_str(), rows);
  return 0;
} catch (const std::exception& e) {
  std::cerr << "scripted_double_pendulum: error: " << e.what() << '\n';
  return 1;
}
