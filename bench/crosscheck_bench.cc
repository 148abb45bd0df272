// SPDX-License-Identifier: BSD-3-Clause
// Reduced vs maximal (penalty) model at equal accuracy: the wall time to simulate 5 s of the
// double pendulum and the planar n-link chain (n = 5, 10, 20) with the largest particle-position
// error at most 1e-3 (and, to show the trend, 1e-5) against a fine reference (reduced RK4,
// dt = 5e-5), and their ratio.
//
// Set-up (not timed): the reduced model gets the largest RK4 step that divides the 0.05 s sample
// interval and meets the accuracy; the maximal model gets the smallest kappa on a quarter-decade
// grid that meets it with RK4 at 0.9 x its stability limit (the error is ~ C / kappa and the
// stable step ~ kappa^-1/2, so the smallest kappa is the cheapest). Then Google Benchmark times
// both runs; a table with the ratio follows.
// Run: build/bench/bench_crosscheck [--benchmark_min_time=0.5s]
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/maximal/crosscheck.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_10.hpp"
#include "generated/n_link_chain_20.hpp"
#include "generated/n_link_chain_5.hpp"

namespace {

constexpr double kDuration = 5.0;
constexpr int kSamples = 100;
constexpr double kTolerances[] = {1e-3, 1e-5};

struct Setting {
  std::string model;
  double tolerance = 0;
  double reduced_dt = 0, reduced_error = 0;
  double kappa = 0, maximal_dt = 0, maximal_error = 0;
  bool found_reduced = false, found_maximal = false;
};
std::vector<Setting> settings;

// largest position error of a reduced RK4 run at step dt against the reference samples
template <class M>
double reduced_error(const typename M::Params& p, const gencoord::ReducedReference<M>& ref,
                     double dt) {
  const double interval = kDuration / kSamples;
  const long long per = std::llround(interval / dt);
  gencoord::State<M> s = ref.samples.front();
  double error = 0;
  try {
    for (int k = 1; k <= kSamples; ++k) {
      for (long long j = 0; j < per; ++j)
        s = gencoord::step(gencoord::ReducedSystem<M>(p), gencoord::Integrator::RK4, s, dt);
      const auto& r = ref.samples[static_cast<std::size_t>(k)];
      error = std::max(error, gencoord::max_particle_distance<M>(M::positions(s.q, r.t, p),
                                                                 M::positions(r.q, r.t, p)));
    }
  } catch (const std::exception&) {
    return INFINITY;
  }
  return std::isfinite(error) ? error : INFINITY;
}

template <class M>
void register_model(double tolerance) {
  const typename M::Params p;
  gencoord::State<M> s0;
  s0.q = gencoord::initial_q_of<M>();
  s0.v = gencoord::initial_v_of<M>();
  gencoord::CrosscheckOptions o;
  o.duration = kDuration;
  o.points = kSamples;
  o.reference_dt = 5e-5;
  const auto ref = gencoord::reduced_reference<M>(p, s0, o);

  Setting set;
  set.model = M::name;
  set.tolerance = tolerance;
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "/tol:%g", tolerance);
  // reduced: the largest step interval / n meeting the tolerance
  for (int n : {1,  2,  3,  4,   5,   6,   8,   10,  12,  16,  20,  25,  32,  40,
                50, 64, 80, 100, 125, 160, 200, 250, 320, 400, 500, 640, 800, 1000}) {
    const double dt = kDuration / kSamples / n;
    const double e = reduced_error<M>(p, ref, dt);
    if (e <= tolerance) {
      set.reduced_dt = dt;
      set.reduced_error = e;
      set.found_reduced = true;
      break;
    }
  }
  // maximal: the smallest kappa meeting it with RK4 at its stability limit
  o.max_dt = 1.0;
  o.safety = 0.9;
  for (int k = 0; k <= 36 && !set.found_maximal; ++k) {
    const double kappa = std::pow(10.0, 2.0 + 0.25 * k);
    try {
      const gencoord::CrosscheckRow row = gencoord::crosscheck_at<M>(p, ref, kappa, o);
      if (row.max_position_error <= tolerance) {
        set.kappa = kappa;
        set.maximal_dt = row.dt;
        set.maximal_error = row.max_position_error;
        set.found_maximal = true;
      }
    } catch (const std::exception&) {
    }
  }
  settings.push_back(set);

  if (set.found_reduced)
    benchmark::RegisterBenchmark((std::string("reduced_5s/") + M::name + suffix).c_str(),
                                 [p, s0, set](benchmark::State& state) {
                                   for (auto _ : state) {
                                     auto s = gencoord::simulate(
                                         gencoord::ReducedSystem<M>(p), s0,
                                         {gencoord::Integrator::RK4, set.reduced_dt, kDuration},
                                         [](const gencoord::State<M>&) {});
                                     benchmark::DoNotOptimize(s.q.data());
                                   }
                                   state.counters["dt"] = set.reduced_dt;
                                   state.counters["error"] = set.reduced_error;
                                 })
        ->Unit(benchmark::kMillisecond);
  if (set.found_maximal)
    benchmark::RegisterBenchmark((std::string("maximal_5s/") + M::name + suffix).c_str(),
                                 [p, s0, set](benchmark::State& state) {
                                   const gencoord::MaximalModel<M> model(p, set.kappa);
                                   const auto x0 = gencoord::to_maximal<M>(p, s0);
                                   for (auto _ : state) {
                                     auto s = gencoord::simulate(
                                         model, x0,
                                         {gencoord::Integrator::RK4, set.maximal_dt, kDuration},
                                         [](const gencoord::MaximalState<M>&) {});
                                     benchmark::DoNotOptimize(s.q.data());
                                   }
                                   state.counters["kappa"] = set.kappa;
                                   state.counters["dt"] = set.maximal_dt;
                                   state.counters["error"] = set.maximal_error;
                                 })
        ->Unit(benchmark::kMillisecond);
}

// console output plus each run's real time, for the ratio table
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs)
      if (run.run_type == Run::RT_Iteration && !run.error_occurred)
        times_[run.benchmark_name()] = run.GetAdjustedRealTime();  // in the run's time unit (ms)
    ConsoleReporter::ReportRuns(runs);
  }
  double time(const std::string& name) const {
    const auto it = times_.find(name);
    return it == times_.end() ? NAN : it->second;
  }

 private:
  std::map<std::string, double> times_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (double tolerance : kTolerances) {
    register_model<gencoord::models::DoublePendulum>(tolerance);
    register_model<gencoord::models::NLinkChain5>(tolerance);
    register_model<gencoord::models::NLinkChain10>(tolerance);
    register_model<gencoord::models::NLinkChain20>(tolerance);
  }
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf(
      "\n5 s of motion at a largest particle-position error <= tol (vs reduced RK4, "
      "dt 5e-5); reduced and maximal both RK4:\n");
  std::printf("%-16s %6s | %9s %9s %9s | %8s %9s %9s %9s | %8s\n", "model", "tol", "red_dt",
              "red_err", "red_ms", "kappa", "max_dt", "max_err", "max_ms", "max/red");
  for (const Setting& s : settings) {
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, "/tol:%g", s.tolerance);
    const double tr = reporter.time("reduced_5s/" + s.model + suffix);
    const double tm = reporter.time("maximal_5s/" + s.model + suffix);
    std::printf("%-16s %6.0e | %9.3g %9.2e %9.3f | %8.2g %9.3g %9.2e %9.3f | %8.2f\n",
                s.model.c_str(), s.tolerance, s.reduced_dt, s.reduced_error, tr, s.kappa,
                s.maximal_dt, s.maximal_error, tm, tm / tr);
  }
  benchmark::Shutdown();
  return 0;
}
