// SPDX-License-Identifier: BSD-3-Clause
// atlas_pendulum: a spherical pendulum looping over its poles, integrated in one chart
// (theta, phi) with a conditioning monitor, then with the two-chart atlas.
//
//   atlas_pendulum [--dt 1e-3] [--duration 6] [--speed 7] [--ratio 4]
//
// The bob starts at theta = 0.8 in the x-z plane with theta_dot = -speed (rad/s): it loops
// over the top and passes close to both poles of the (theta, phi) chart every turn. Prints
// the monitor's warning, each chart switch and both runs' energy errors. --ratio sets the
// atlas' switch threshold (AtlasOptions::switch_ratio).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "command_line.hpp"
#include "gencoord/atlas/atlas.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/conditioning.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/spherical_pendulum.hpp"

namespace {

using gencoord::models::SphericalPendulum;
using gencoord::models::SphericalPendulumAtlas;

struct Options {
  double dt = 1e-3;
  double duration = 6.0;
  double speed = 7.0;
  double ratio = gencoord::AtlasOptions{}.switch_ratio;
};

Options parse(int argc, char** argv) {
  Options options;
  const char* program = "atlas_pendulum";
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    double* target = flag == "--dt"         ? &options.dt
                     : flag == "--duration" ? &options.duration
                     : flag == "--speed"    ? &options.speed
                     : flag == "--ratio"    ? &options.ratio
                                            : nullptr;
    if (!target) {
      std::fprintf(stderr, "%s: error: unknown option '%s' (--dt, --duration, --speed, --ratio)\n",
                   program, argv[i]);
      std::exit(2);
    }
    const std::string value = gencoord::drivers::option_value(program, argc, argv, i);
    *target = gencoord::drivers::parse_number(program, value, flag);
  }
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  const SphericalPendulum::Params p;
  gencoord::State<SphericalPendulum> start;
  start.q << 0.8, 0.02;
  start.v << -options.speed, 0.03;
  const double e0 = SphericalPendulum::energy(start.q, start.v, 0.0, p);
  const double scale = p.m * p.g * p.l;
  std::printf("spherical pendulum, RK4, dt = %g, %g s, E0 = %.6f J\n\n", options.dt,
              options.duration, e0);

  std::printf("one chart (theta, phi), ConditioningMonitor(warn once, threshold 1e3):\n");
  std::fflush(stdout);  // the monitor warns on stderr: keep the two in order
  gencoord::ConditioningMonitor<SphericalPendulum> monitor(
      p, gencoord::ConditioningPolicy::WarnOnce, 1e3);
  double single_error = 0.0;
  try {
    gencoord::simulate(gencoord::ReducedSystem<SphericalPendulum>(p), start,
                       {gencoord::Integrator::RK4, options.dt, options.duration},
                       [&](const gencoord::State<SphericalPendulum>& s) {
                         monitor(s);
                         single_error =
                             std::max(single_error,
                                      std::abs(SphericalPendulum::energy(s.q, s.v, s.t, p) - e0));
                       });
  } catch (const std::exception& error) {
    std::printf("  stopped: %s\n", error.what());
  }
  std::printf("  worst cond(Mt) estimate %.3g at t = %.3f; max |E - E0| / (m g l) = %.3g\n\n",
              monitor.worst(), monitor.worst_time(), single_error / scale);
  std::fflush(stdout);

  std::printf("atlas (pole_down, pole_x):\n");
  gencoord::AtlasOptions atlas_options;
  atlas_options.switch_ratio = options.ratio;
  gencoord::AtlasSimulation<SphericalPendulumAtlas> atlas(p, start, atlas_options);
  double atlas_error = 0.0, worst_condition = 0.0;
  atlas.simulate(gencoord::Integrator::RK4, options.dt, options.duration, [&](const auto& a) {
    atlas_error = std::max(atlas_error, std::abs(a.energy() - e0));
    worst_condition = std::max(worst_condition, a.condition());
  });
  std::printf("  switch threshold: cond(Mt) > %.3g\n", atlas.threshold());
  const auto& switches = atlas.switches();
  for (std::size_t k = 0; k < switches.size(); ++k) {
    if (k == 4 && switches.size() > 6) {
      std::printf("  ... %zu more ...\n", switches.size() - 6);
      k = switches.size() - 2;
    }
    const gencoord::ChartSwitch& s = switches[k];
    std::printf("  t = %6.3f  %-9s -> %-9s  cond %.3g -> %.3g\n", s.t,
                SphericalPendulumAtlas::chart_names[s.from],
                SphericalPendulumAtlas::chart_names[s.to], s.estimate_from, s.estimate_to);
  }
  std::printf("  %zu switches; worst cond(Mt) estimate %.3g; max |E - E0| / (m g l) = %.3g\n",
              switches.size(), worst_condition, atlas_error / scale);
  return 0;
}
