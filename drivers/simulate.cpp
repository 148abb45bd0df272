// SPDX-License-Identifier: BSD-3-Clause
// simulate: integrates one generated model and writes its trajectory as CSV.
//
//   simulate [--integrator rk4] [--dt 1e-3] [--duration 10] [--output FILE.csv]
//            [--q a,b,...] [--v a,b,...] [--set name=value ...] [--baumgarte RATE]
//            [--no-limits]
//
// The model is chosen when the program is compiled (driver_model.hpp, written by
// gencoord_add_driver()); `gencoord simulate MODEL.py` builds and runs it for any model file.
// Prints a short summary: steps, wall time, energy drift (for a dissipative model also the
// balance E - E(0) - W, W the work of its dampers and friction), final state. --v takes nv
// values: the generalized speeds of a model that has them (free and ball joints), whose unit
// quaternions in --q are normalized before the run. A model with kinematic constraints starts
// from --q and --v projected onto its constraints, and the summary gives the largest
// constraint residuals of the run; each step's end state is projected too, or, with
// --baumgarte, Baumgarte's feedback keeps the drift down instead. A model with joint limits
// keeps its limited coordinates in their ranges (gencoord/model/joint_limits.hpp) unless
// --no-limits; the summary names the limits the run reached and the speed and effort ratings it
// exceeded (the effort: the generalized force of the control inputs, which --set gives, at the
// joint), and the CSV has a limit:<name> column for each (-1, 0, +1: lower end, inside, upper
// end).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command_line.hpp"
#include "driver_model.hpp"
#include "gencoord/gencoord.hpp"
#include "initial_state.hpp"

namespace {

using M = gencoord::drivers::Model;

struct Options {
  std::string integrator = "rk4";
  double dt = 1e-3;
  double duration = 10.0;
  std::string output;
  std::vector<double> q, v;
  std::vector<std::pair<std::string, double>> parameters;
  double baumgarte = 0.0;  // 1/s; 0: each step's end state projected onto the constraints
  bool joint_limits = true;
};

[[noreturn]] void usage(int status) {
  std::cerr << "usage: simulate [--integrator NAME] [--dt DT] [--duration T]\n"
               "                [--output FILE.csv] [--q a,b,...] [--v a,b,...]\n"
               "                [--set param=value ...] [--baumgarte RATE] [--no-limits]\n"
               "  model:       "
            << M::name << " (nq = " << M::nq << ", nv = " << gencoord::nv_of_v<M> << ")"
            << "\n  integrators: " << gencoord::integrator_names()
            << "\n  defaults:    rk4, dt 1e-3, duration 10, the model file's initial state"
            << "\n  --baumgarte: a model with kinematic constraints kept on them by Baumgarte's"
               "\n               feedback at RATE (1/s) instead of projecting each step"
               "\n  --no-limits: a model with joint limits run without them\n";
  std::exit(status);
}

double parse_number(const std::string& text, const std::string& what) {
  return gencoord::drivers::parse_number("simulate", text, what);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] { return gencoord::drivers::option_value("simulate", argc, argv, i); };
    if (arg == "-h" || arg == "--help") usage(0);
    else if (arg == "--integrator") o.integrator = value();
    else if (arg == "--dt") o.dt = parse_number(value(), arg);
    else if (arg == "--duration") o.duration = parse_number(value(), arg);
    else if (arg == "--output" || arg == "-o") o.output = value();
    else if (arg == "--q") o.q = gencoord::drivers::parse_list("simulate", value(), arg);
    else if (arg == "--v") o.v = gencoord::drivers::parse_list("simulate", value(), arg);
    else if (arg == "--baumgarte") o.baumgarte = parse_number(value(), arg);
    else if (arg == "--no-limits") o.joint_limits = false;
    else if (arg == "--set") {
      const std::string pair = value();
      const auto eq = pair.find('=');
      if (eq == std::string::npos) {
        std::cerr << "simulate: error: --set expects name=value, got '" << pair << "'\n";
        std::exit(2);
      }
      o.parameters.emplace_back(pair.substr(0, eq), parse_number(pair.substr(eq + 1), pair));
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "simulate: error: unknown option " << arg << "\n";
      usage(2);
    } else {
      std::cerr << "simulate: error: unexpected argument '" << arg << "'\n";
      usage(2);
    }
  }
  return o;
}

// The system to integrate: a constrained model kept on its constraints by projection, or by
// Baumgarte's feedback at `baumgarte` (1/s, critically damped) where that is positive.
template <class Model>
gencoord::ReducedSystem<Model> system_of(const typename Model::Params& p, double baumgarte) {
  if constexpr (gencoord::has_kinematic_constraints_v<Model>) {
    if (baumgarte > 0) return gencoord::ReducedSystem<Model>(p, {false, {baumgarte, baumgarte}});
  } else {
    (void)baumgarte;
  }
  return gencoord::ReducedSystem<Model>(p);
}

// the largest constraint residual at s (0 for a model without constraints)
template <class Model>
double drift_of(const typename Model::Params& p, const gencoord::State<Model>& s) {
  if constexpr (gencoord::has_kinematic_constraints_v<Model>) {
    return gencoord::constraint_residual<Model>(p, s);
  } else {
    (void)p;
    (void)s;
    return 0.0;
  }
}

// the drift of a constrained model's run
template <class Model>
void print_constraint_residual(double worst, double baumgarte) {
  if constexpr (gencoord::has_kinematic_constraints_v<Model>) {
    std::printf("constraints %d, max |C| and |A v + b| over the run = %.3e", Model::num_constraints,
                worst);
    if (baumgarte > 0) std::printf(" (Baumgarte at %g 1/s, no projection)", baumgarte);
    std::printf("\n");
  } else {
    (void)worst;
    (void)baumgarte;
  }
}

template <class Model>
constexpr int num_limits_of() {
  if constexpr (gencoord::has_joint_limits_v<Model>) {
    return Model::num_limits;
  } else {
    return 0;
  }
}

// false, with the error printed, where the start puts a limited coordinate outside its range
template <class Model>
bool start_within_limits(const gencoord::State<Model>& s) {
  if constexpr (gencoord::has_joint_limits_v<Model>) {
    for (int i = 0; i < Model::num_limits; ++i) {
      const double q = s.q[Model::limited_coordinates[i]];
      if (q < Model::lower_limits[i] || q > Model::upper_limits[i]) {
        std::cerr << "simulate: error: the start puts " << Model::limit_names[i] << " at " << q
                  << ", outside its limits [" << Model::lower_limits[i] << ", "
                  << Model::upper_limits[i] << "]; give --q inside them, or --no-limits\n";
        return false;
      }
    }
  } else {
    (void)s;
  }
  return true;
}

// What the run did at each joint limit: the steps that ended with the coordinate on an end of
// its range (or beyond it, with --no-limits), the largest |v| of its speed and the largest
// generalized force of the control inputs at it.
template <class Model>
class LimitReport {
 public:
  explicit LimitReport(const typename Model::Params& params) : params_(params) {}

  void operator()(const gencoord::State<Model>& state) {
    if constexpr (gencoord::has_joint_limits_v<Model>) {
      const auto efforts = gencoord::input_efforts<Model>(state, params_);
      for (int i = 0; i < Model::num_limits; ++i) {
        if (gencoord::limit_side<Model>(state.q, i) != 0) ++steps_[i];
        fastest_[i] = std::max(fastest_[i], std::abs(state.v[Model::limited_speeds[i]]));
        strongest_[i] = std::max(strongest_[i], std::abs(efforts[i]));
      }
    } else {
      (void)state;
    }
  }
  // the limits the run reached, and the speed and effort ratings it exceeded
  void print(bool enforced) const {
    if constexpr (gencoord::has_joint_limits_v<Model>) {
      std::printf("limits      %d%s", Model::num_limits,
                  enforced ? "" : ", ranges not enforced (--no-limits)");
      int reached = 0;
      for (int i = 0; i < Model::num_limits; ++i) {
        if (steps_[i] == 0) continue;
        std::printf("%s %s (%lld step%s)", reached++ ? "," : ", reached by", Model::limit_names[i],
                    steps_[i], steps_[i] == 1 ? "" : "s");
      }
      if (reached == 0) std::printf(", none reached");
      int exceeded = 0;
      for (int i = 0; i < Model::num_limits; ++i) {
        if (!(fastest_[i] > Model::velocity_limits[i])) continue;
        std::printf("%s %s (|v| up to %.4g, rated %.4g)",
                    exceeded++ ? "," : "; speed rating exceeded by", Model::limit_names[i],
                    fastest_[i], Model::velocity_limits[i]);
      }
      exceeded = 0;
      for (int i = 0; i < Model::num_limits; ++i) {
        if (!(strongest_[i] > Model::effort_limits[i])) continue;
        std::printf("%s %s (inputs' force up to %.4g, rated %.4g)",
                    exceeded++ ? "," : "; effort rating exceeded by", Model::limit_names[i],
                    strongest_[i], Model::effort_limits[i]);
      }
      std::printf("\n");
    } else {
      (void)enforced;
    }
  }

 private:
  const typename Model::Params& params_;
  std::array<long long, num_limits_of<Model>()> steps_{};
  std::array<double, num_limits_of<Model>()> fastest_{};
  std::array<double, num_limits_of<Model>()> strongest_{};
};

// the final speeds of a model that has them (its q are not its velocities' integrals)
template <class Model>
void print_speeds(const gencoord::State<Model>& end) {
  if constexpr (gencoord::has_generalized_speeds_v<Model>) {
    std::printf("final v    ");
    for (int i = 0; i < gencoord::nv_of_v<Model>; ++i)
      std::printf(" %s = %.6f", Model::speed_names[i], end.v[i]);
    std::printf("\n");
  } else {
    (void)end;
  }
}

int run(const Options& o) {
  using gencoord::State;
  typename M::Params params;
  for (const auto& [name, value] : o.parameters) {
    double* slot = params.find(name);
    if (!slot) {
      std::cerr << "simulate: error: model " << M::name << " has no parameter '" << name << "'\n";
      return 2;
    }
    *slot = value;
  }
  State<M> s;
  if (!gencoord::drivers::initial_state<M>("simulate", o.q, o.v, &s)) return 2;
  if (!(o.baumgarte >= 0) || !std::isfinite(o.baumgarte)) {
    std::cerr << "simulate: error: --baumgarte needs a rate of 0 or more (1/s), got " << o.baumgarte
              << "\n";
    return 2;
  }
  if (o.baumgarte > 0 && !gencoord::has_kinematic_constraints_v<M>) {
    std::cerr << "simulate: error: --baumgarte is for models with kinematic constraints; "
              << M::name << " has none\n";
    return 2;
  }
  gencoord::ReducedSystem<M> system = system_of<M>(params, o.baumgarte);
  if constexpr (gencoord::has_joint_limits_v<M>) system.set_joint_limits(o.joint_limits);
  if (o.joint_limits && !start_within_limits<M>(s)) return 2;
  if (!gencoord::drivers::put_on_manifold<M>("simulate", system, &s)) return 2;
  const gencoord::Integrator integrator = gencoord::parse_integrator(o.integrator);

  const double e0 = M::energy(s.q, s.v, s.t, params);
  double max_energy_error = 0.0, max_drift = 0.0, max_balance_error = 0.0;
  std::unique_ptr<gencoord::TrajectoryCsvWriter<M>> csv;
  if (!o.output.empty()) csv = std::make_unique<gencoord::TrajectoryCsvWriter<M>>(o.output, params);
  // W of the dampers and friction up to the latest state: the CSV's work column sums it
  // where there is a CSV, this sum where there is none
  std::optional<gencoord::DissipatedWork<M>> own_work;
  if (gencoord::is_dissipative_v<M> && !csv) own_work.emplace(params);
  [[maybe_unused]] double work = 0.0;
  LimitReport<M> limits(params);
  auto observer = [&](const State<M>& state) {
    if (csv) (*csv)(state);
    const double change = M::energy(state.q, state.v, state.t, params) - e0;
    max_energy_error = std::max(max_energy_error, std::abs(change));
    if constexpr (gencoord::is_dissipative_v<M>) {
      work = csv ? csv->work() : (*own_work)(state);
      max_balance_error = std::max(max_balance_error, std::abs(change - work));
    }
    max_drift = std::max(max_drift, drift_of<M>(params, state));
    limits(state);
  };
  const auto start = std::chrono::steady_clock::now();
  State<M> end;
  try {
    end = gencoord::simulate(system, s, {integrator, o.dt, o.duration}, observer);
    if (csv) csv->close();  // throws gencoord::OutputError if a row did not reach the file
  } catch (const gencoord::OutputError& error) {
    // only the CSV's writes throw OutputError: a partial trajectory is no result
    const bool removed = csv && csv->discard();
    std::cerr << "simulate: error: " << error.what() << (removed ? "; removed it" : "") << "\n";
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long long steps = gencoord::step_count(o.dt, o.duration);

  constexpr int nv = gencoord::nv_of_v<M>;
  const std::string speeds = nv != M::nq ? ", nv = " + std::to_string(nv) : "";
  std::printf("model       %s (nq = %d%s, %d particles in %dD)\n", M::name, M::nq, speeds.c_str(),
              M::num_particles, M::dim);
  std::printf("integrator  %s, dt = %g s, %lld steps to t = %g s\n",
              gencoord::to_string(integrator), o.dt, steps, end.t);
  std::printf("wall time   %.3f ms (%.1f ns per step, CSV output included)\n", seconds * 1e3,
              seconds * 1e9 / static_cast<double>(steps > 0 ? steps : 1));
  std::printf("energy      E(0) = %.10g J, E(end) = %.10g J, max |E - E(0)| = %.3e J\n", e0,
              M::energy(end.q, end.v, end.t, params), max_energy_error);
  if constexpr (gencoord::is_dissipative_v<M>) {
    std::printf(
        "balance     W(end) = %.10g J by dampers and friction, max |E - E(0) - W| = %.3e J\n", work,
        max_balance_error);
  }
  print_constraint_residual<M>(max_drift, o.baumgarte);
  limits.print(o.joint_limits);
  std::printf("final q    ");
  for (int i = 0; i < M::nq; ++i) std::printf(" %s = %.6f", M::coordinate_names[i], end.q[i]);
  std::printf("\n");
  print_speeds<M>(end);
  if (!o.output.empty()) std::printf("trajectory  %s (%lld rows)\n", o.output.c_str(), steps + 1);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  try {
    return run(options);
  } catch (const std::exception& error) {
    std::cerr << "simulate: error: " << error.what() << "\n";
    return 1;
  }
}
