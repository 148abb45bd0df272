// SPDX-License-Identifier: BSD-3-Clause
// crosscheck: the maximal-coordinate penalty model against the reduced model, as kappa grows.
//
//   crosscheck [--kappa 1e2:1e8] [--points N] [--t 5] [--samples 100]
//              [--integrator rk4|symplectic_euler|backward_euler] [--max-dt 1e-4]
//              [--safety 0.9] [--damping 0] [--reference-dt 1e-4] [--set name=value ...]
//              [--q a,b,...] [--v a,b,...] [--csv FILE] [--svg FILE] [--trajectory FILE]
//              [--min-slope S]
//
// The model is chosen when the program is compiled (driver_model.hpp, written by
// gencoord_add_driver()); `gencoord crosscheck MODEL.py` builds and runs it for any model file.
// Runs the reduced model (RK4) as the reference and the maximal model from the same consistent
// initial state (the model file's, or --q and --v as simulate takes them) for N log-spaced kappa
// (default: one per decade), prints one row per kappa (step, largest particle-position error,
// energy drift, largest constraint violation, wall time), the fitted log-log slopes of error and
// violation against kappa, and writes a CSV and an SVG plot. Exit status: 0 when the error falls
// with a slope at least as steep as --min-slope (-0.8, or -0.4 for a model with velocity
// constraints, whose viscous penalty converges like kappa^-1/2; or, for a model without declared
// constraints whose maximal model is the reduced one in other coordinates, when the error sits
// at the integration floor for every kappa); 1 when it does not; 2 for bad usage.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command_line.hpp"
#include "driver_model.hpp"
#include "gencoord/io/csv_writer.hpp"
#include "gencoord/maximal/crosscheck.hpp"
#include "initial_state.hpp"
#include "loglog_svg.hpp"

namespace {

using M = gencoord::drivers::Model;
static_assert(gencoord::has_maximal_v<M>,
              "gencoord: the model has no struct Maximal; generate it with --maximal "
              "(gencoord_add_model(... MAXIMAL))");

struct Options {
  double kappa_lo = 1e2, kappa_hi = 1e8;
  int count = 0;  // kappa values; 0: one per decade
  gencoord::CrosscheckOptions run;
  std::string csv, svg;
  std::string trajectory;  // both models at the smallest kappa, sample by sample
  double min_slope = gencoord::expected_error_slope<M>();
  std::vector<std::pair<std::string, double>> parameters;
  std::vector<double> q, v;  // initial state; empty: the model file's
};

[[noreturn]] void usage(int status) {
  std::cerr
      << "usage: crosscheck [--kappa LO:HI] [--points N] [--t T] [--samples S]\n"
         "                  [--integrator rk4|symplectic_euler|backward_euler] [--max-dt DT]\n"
         "                  [--safety F] [--damping C] [--reference-dt DT]\n"
         "                  [--set param=value ...] [--q a,b,...] [--v a,b,...]\n"
         "                  [--csv FILE] [--svg FILE] [--trajectory FILE] [--min-slope S]\n"
         "  --kappa      penalty stiffness range, log-spaced (or one value); default 1e2:1e8\n"
         "  --points     number of kappa values; default one per decade\n"
         "  --t          simulated time; default 5\n"
         "  --samples    sample intervals compared; default 100\n"
         "  --max-dt     largest maximal step (accuracy); default 1e-4\n"
         "  --safety     fraction of the explicit stability limit; default 0.9\n"
         "  --min-slope  exit 1 if the fitted error slope is shallower; default -0.8, or\n"
         "               -0.4 for a model with velocity constraints (rolling: kappa^-1/2)\n"
         "  --trajectory the reduced and the maximal model at the smallest kappa, at every\n"
         "               sample (CSV: the simulate layout, then maximal:<particle>_x, ...)\n"
         "  --q, --v     the initial coordinates (nq) and velocities (nv: a model's generalized\n"
         "               speeds); default the model file's initial state\n"
         "  model:       "
      << M::name << '\n';
  std::exit(status);
}

double number(const std::string& text, const std::string& what) {
  return gencoord::drivers::parse_number("crosscheck", text, what);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] { return gencoord::drivers::option_value("crosscheck", argc, argv, i); };
    if (arg == "-h" || arg == "--help") usage(0);
    else if (arg == "--kappa") {
      const std::string range = value();
      const auto colon = range.find(':');
      o.kappa_lo = number(range.substr(0, colon), arg);
      o.kappa_hi = colon == std::string::npos ? o.kappa_lo : number(range.substr(colon + 1), arg);
    } else if (arg == "--points") o.count = static_cast<int>(number(value(), arg));
    else if (arg == "--t") o.run.duration = number(value(), arg);
    else if (arg == "--samples") o.run.points = static_cast<int>(number(value(), arg));
    else if (arg == "--max-dt") o.run.max_dt = number(value(), arg);
    else if (arg == "--safety") o.run.safety = number(value(), arg);
    else if (arg == "--damping") o.run.penalty_damping = number(value(), arg);
    else if (arg == "--reference-dt") o.run.reference_dt = number(value(), arg);
    else if (arg == "--min-slope") o.min_slope = number(value(), arg);
    else if (arg == "--csv") o.csv = value();
    else if (arg == "--svg") o.svg = value();
    else if (arg == "--trajectory") o.trajectory = value();
    else if (arg == "--q") o.q = gencoord::drivers::parse_list("crosscheck", value(), arg);
    else if (arg == "--v") o.v = gencoord::drivers::parse_list("crosscheck", value(), arg);
    else if (arg == "--integrator") {
      try {
        o.run.integrator = gencoord::parse_integrator(value());
      } catch (const std::invalid_argument& e) {
        std::cerr << "crosscheck: error: " << e.what() << '\n';
        std::exit(2);
      }
      if (!gencoord::includes(gencoord::CrosscheckIntegrators{}, o.run.integrator)) {
        std::cerr << "crosscheck: error: --integrator " << gencoord::to_string(o.run.integrator)
                  << ": the maximal model runs with rk4, symplectic_euler or backward_euler\n";
        std::exit(2);
      }
    } else if (arg == "--set") {
      const std::string pair = value();
      const auto eq = pair.find('=');
      if (eq == std::string::npos) {
        std::cerr << "crosscheck: error: --set expects name=value, got '" << pair << "'\n";
        std::exit(2);
      }
      o.parameters.emplace_back(pair.substr(0, eq), number(pair.substr(eq + 1), arg));
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "crosscheck: error: unknown option " << arg << '\n';
      usage(2);
    } else {
      std::cerr << "crosscheck: error: unexpected argument '" << arg << "'\n";
      usage(2);
    }
  }
  if (!(o.kappa_lo > 0) || !(o.kappa_hi >= o.kappa_lo)) {
    std::cerr << "crosscheck: error: --kappa needs 0 < LO <= HI\n";
    std::exit(2);
  }
  if (o.count <= 0)
    o.count = 1 + static_cast<int>(std::lround(std::log10(o.kappa_hi / o.kappa_lo)));
  if (o.csv.empty()) o.csv = std::string("crosscheck_") + M::name + ".csv";
  if (o.svg.empty()) o.svg = std::string("crosscheck_") + M::name + ".svg";
  return o;
}

void write_csv(const std::string& path, const std::vector<gencoord::CrosscheckRow>& rows) {
  gencoord::OutputFile file(path);
  std::ostream& f = file.stream();
  f.precision(10);
  f << "kappa,omega_max,dt,steps,max_position_error,energy_drift,max_constraint_violation,"
       "wall_seconds\n";
  for (const auto& r : rows)
    f << r.kappa << ',' << r.omega_max << ',' << r.dt << ',' << r.steps << ','
      << r.max_position_error << ',' << r.energy_drift << ',' << r.max_constraint_violation << ','
      << r.wall_seconds << '\n';
  file.close();
}

int run(const Options& o) {
  typename M::Params p;
  for (const auto& [name, value] : o.parameters) {
    double* slot = p.find(name);
    if (!slot) {
      std::cerr << "crosscheck: error: model " << M::name << " has no parameter '" << name << "'\n";
      return 2;
    }
    *slot = value;
  }
  gencoord::State<M> s0;
  if (!gencoord::drivers::initial_state<M>("crosscheck", o.q, o.v, &s0)) return 2;
  gencoord::ReducedSystem<M> system(p);
  if constexpr (gencoord::has_joint_limits_v<M>)
    system.set_joint_limits(false);  // as the reference
  if (!gencoord::drivers::put_on_manifold<M>("crosscheck", system, &s0)) return 2;

  const auto ref = gencoord::reduced_reference<M>(p, s0, o.run);
  std::printf("model       %s (nq = %d%s, nx = %d, %d declared constraints%s%s)\n", M::name, M::nq,
              gencoord::has_generalized_speeds_v<M>
                  ? (", nv = " + std::to_string(gencoord::nv_of_v<M>)).c_str()
                  : "",
              M::nx, M::Maximal::num_constraints,
              M::Maximal::has_generalized_forces ? ", generalized forces mapped by M J Mt^-1" : "",
              gencoord::uses_manifold_spring_v<M> ? ", manifold spring" : "");
  std::printf(
      "reference   reduced RK4, dt = %g, %lld steps to t = %g, %.3f ms; max |C(X(q))| = %.3g\n",
      ref.reference_dt, ref.steps, o.run.duration, 1e3 * ref.wall_seconds,
      ref.max_constraint_violation);
  std::printf("maximal     %s, dt <= min(%g x stability limit, %g), %d samples, damping %g\n\n",
              gencoord::to_string(o.run.integrator), o.run.safety, o.run.max_dt, o.run.points,
              o.run.penalty_damping);
  std::printf("%10s %10s %10s %9s %12s %12s %12s %10s\n", "kappa", "omega_max", "dt", "steps",
              "pos_error", "energy_drift", "violation", "wall_ms");

  std::vector<gencoord::CrosscheckRow> rows;
  std::vector<double> kappas, errors, violations;
  int failed = 0;
  // the smallest kappa's run, beside the reduced one: where they differ most
  std::unique_ptr<gencoord::TrajectoryCsvWriter<M>> trajectory;
  auto new_trajectory = [&] {
    return std::make_unique<gencoord::TrajectoryCsvWriter<M>>(o.trajectory, p, "maximal:");
  };
  if (!o.trajectory.empty()) trajectory = new_trajectory();
  double trajectory_kappa = 0.0;
  for (double kappa : gencoord::log_spaced(o.kappa_lo, o.kappa_hi, o.count)) {
    gencoord::CrosscheckRow r;
    try {
      // one observer type for every run: each type instantiates every integrator once more
      r = gencoord::crosscheck_at<M>(
          p, ref, kappa, o.run,
          [&](const gencoord::State<M>& reduced, const gencoord::MaximalState<M>& maximal) {
            if (trajectory) trajectory->write(reduced, maximal.q);
          });
      if (trajectory) {
        trajectory->close();
        trajectory.reset();
        trajectory_kappa = kappa;
      }
    } catch (const std::exception& e) {
      // e.g. a soft penalty lets the state stray so far that the inverse map has no unique
      // closest point: report the row, fit the others
      std::printf("%10.3g  failed: %s\n", kappa, e.what());
      if (trajectory) trajectory = new_trajectory();  // the next kappa's run, from the start
      ++failed;
      continue;
    }
    std::printf("%10.3g %10.4g %10.3g %9lld %12.4e %12.4e %12.4e %10.2f\n", r.kappa, r.omega_max,
                r.dt, r.steps, r.max_position_error, r.energy_drift, r.max_constraint_violation,
                1e3 * r.wall_seconds);
    rows.push_back(r);
    kappas.push_back(r.kappa);
    errors.push_back(r.max_position_error);
    violations.push_back(r.max_constraint_violation);
  }
  write_csv(o.csv, rows);
  if (trajectory_kappa > 0)
    std::printf("trajectory  %s: reduced and maximal at kappa = %g\n", o.trajectory.c_str(),
                trajectory_kappa);
  const auto error_fit = gencoord::fit_loglog(kappas, errors);
  const auto violation_fit = gencoord::fit_loglog(kappas, violations);
  char note[160];
  if constexpr (gencoord::kappa_independent_v<M>)
    std::snprintf(note, sizeof note,
                  "no declared constraints, nv = nx: error at the integration floor");
  else
    std::snprintf(note, sizeof note, "fitted slopes: position error %.3f, violation %.3f",
                  error_fit.slope, violation_fit.slope);
  const std::vector<gencoord::drivers::LogLogSeries> series{
      {"max position error", "#1f77b4", kappas, errors},
      {"max constraint violation", "#d62728", kappas, violations}};
  if (!gencoord::drivers::write_loglog_svg(o.svg,
                                           std::string("cross-check: ") + M::name + ", maximal " +
                                               gencoord::to_string(o.run.integrator) +
                                               " vs reduced RK4",
                                           "penalty stiffness kappa", "error (m)", series, note))
    std::cerr << "crosscheck: warning: no point to plot, " << o.svg << " not written\n";

  std::printf("\n");
  if (rows.empty()) {
    std::printf("FAIL: every maximal run failed\n");
    return 1;
  }
  if (failed > 0)
    std::printf("warning: %d of %d maximal runs failed; the fit uses the other %zu\n", failed,
                o.count, rows.size());
  const double lo = *std::min_element(errors.begin(), errors.end());
  const double hi = *std::max_element(errors.begin(), errors.end());
  if (gencoord::kappa_independent_v<M> || hi <= 1e-10) {
    // no declared constraints and nv == nx: the maximal model is the reduced one in other
    // coordinates, kappa acts on nothing; or nothing loads the constraints (no motion): the
    // error is the integrators' floor
    std::printf("%s: the error sits at the integration floor %.3e .. %.3e for every kappa\n",
                gencoord::kappa_independent_v<M>
                    ? "no declared constraints, nv = nx: kappa acts on nothing"
                    : "the constraints carry no load",
                lo, hi);
    std::printf("csv %s, plot %s\n", o.csv.c_str(), o.svg.c_str());
    const bool flat = hi <= 1.5 * lo || hi <= 1e-10;
    if (!flat) std::printf("FAIL: the error changes with kappa although nothing depends on it\n");
    return flat ? 0 : 1;
  } else {
    std::printf(
        "fitted slopes (log-log least squares over %d kappa): position error %.3f, "
        "constraint violation %.3f\n",
        error_fit.points, error_fit.slope, violation_fit.slope);
    std::printf("csv %s, plot %s\n", o.csv.c_str(), o.svg.c_str());
    if (rows.size() < 2) return 0;
    if (!(errors.back() < errors.front())) {
      std::printf(
          "FAIL: the position error does not fall with kappa (%.3e at kappa %.3g, "
          "%.3e at kappa %.3g)\n",
          errors.front(), kappas.front(), errors.back(), kappas.back());
      return 1;
    }
    if (!(error_fit.slope <= o.min_slope)) {
      std::printf("FAIL: the error slope %.3f is shallower than --min-slope %.3f\n",
                  error_fit.slope, o.min_slope);
      return 1;
    }
    return 0;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  try {
    return run(o);
  } catch (const std::exception& error) {
    std::cerr << "crosscheck: error: " << error.what() << '\n';
    return 1;
  }
}
