// SPDX-License-Identifier: BSD-3-Clause
// Cost of a time step per spring against the floor, a bare loop over the same springs that
// only computes their forces: symplectic Euler, and backward Euler with conjugate gradients
// (warm started from the previous step's velocity change, and from zero) and with the sparse
// Cholesky factorization, each kept between steps (BackwardEulerStepper), plus backward Euler
// re-analysing its pattern every step (backward_euler_step()), on square sheets of about 1e3,
// 1e4, 1e5 and 1e6 springs. Google Benchmark interleaves the repetitions of every contender
// at random in this one process, pinned to core 0; each repetition starts from the same sheet.
// After its table comes one line per contender and size: ns per step per spring, minimum and
// median over the repetitions, their ratios to the floor's, and CG iterations per step.
//
//   taskset -c 0 build/deformable/bench_deformable_ratios --benchmark_repetitions=7
//       --benchmark_enable_random_interleaving=true --benchmark_min_time=0.2   (one line)
#include <benchmark/benchmark.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "gencoord/deformable/explicit_stepper.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gd = gencoord::deformable;
using Sheet = gd::MassSpringSystem<2>;

namespace {

const long kSizes[] = {1000, 10000, 100000, 1000000};
// the fresh backward Euler re-analyses a pattern each step: its largest size takes seconds
constexpr long kLargestFresh = 100000;

// A square sheet with about `springs` springs (3 per cell), pinned along its left edge, under
// gravity, as bench_deformable's; built once per size and copied for each repetition.
const Sheet& SheetOf(long springs) {
  static std::map<long, Sheet> sheets;
  auto it = sheets.find(springs);
  if (it == sheets.end()) {
    const int cells = static_cast<int>(std::lround(std::sqrt(springs / 3.0)));
    Sheet s = gd::make_mass_spring(gd::rectangle_mesh(1.0, 1.0, cells, cells),
                                   gd::Material{1e4, 1.0, 1.0});
    gd::pin_nodes_where(s, 0, 0.0);
    s.gravity << 0.0, -9.81;
    it = sheets.emplace(springs, std::move(s)).first;
  }
  return it->second;
}

void SetCounters(benchmark::State& state, const Sheet& s, double cg_iterations) {
  state.counters["springs"] = static_cast<double>(s.springs.size());
  state.counters["cg_iterations"] = cg_iterations;
}

// the floor: the springs' forces and nothing else
void BM_Floor(benchmark::State& state) {
  const Sheet& s = SheetOf(state.range(0));
  Sheet::Points f(2, s.num_nodes());
  for (auto _ : state) {
    f.setZero();
    for (const gd::Spring& sp : s.springs) {
      const gd::SpringForce<2> sf = gd::spring_force<2>(s.x.col(sp.i), s.x.col(sp.j), s.v.col(sp.i),
                                                        s.v.col(sp.j), sp.params);
      f.col(sp.i) += sf.f_i;
      f.col(sp.j) -= sf.f_i;
    }
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, s, 0.0);
}

void BM_SymplecticEuler(benchmark::State& state) {
  Sheet s = SheetOf(state.range(0));
  const double dt = 0.9 * gd::cfl_limit(s);
  for (auto _ : state) {
    gd::symplectic_euler_step(s, dt);
    benchmark::DoNotOptimize(s.x.data());
  }
  SetCounters(state, s, 0.0);
}

// the same steps by ExplicitStepper, which validates the sheet at its first step only
void BM_ExplicitStepper(benchmark::State& state) {
  Sheet s = SheetOf(state.range(0));
  const double dt = 0.9 * gd::cfl_limit(s);
  gd::ExplicitStepper<2> stepper;
  stepper.step(s, dt);
  for (auto _ : state) {
    stepper.step(s, dt);
    benchmark::DoNotOptimize(s.x.data());
  }
  SetCounters(state, s, 0.0);
}

// backward Euler at 10 x the CFL limit, the stepper's pattern built before the timing
void BM_BackwardEuler(benchmark::State& state, gd::LinearSolver solver, bool warm_start) {
  Sheet s = SheetOf(state.range(0));
  const double dt = 10.0 * gd::cfl_limit(s);
  gd::ImplicitOptions options;
  options.solver = solver;
  options.warm_start = warm_start;
  gd::BackwardEulerStepper<2> stepper(options);
  stepper.step(s, dt);
  long iterations = 0;
  for (auto _ : state) {
    iterations += stepper.step(s, dt).iterations;
    benchmark::DoNotOptimize(s.x.data());
  }
  SetCounters(state, s, static_cast<double>(iterations) / std::max<double>(1, state.iterations()));
}

// backward Euler as a fresh stepper every step (pattern and analysis rebuilt), Cholesky
void BM_BackwardEulerFresh(benchmark::State& state) {
  Sheet s = SheetOf(state.range(0));
  const double dt = 10.0 * gd::cfl_limit(s);
  gd::ImplicitOptions options;
  options.solver = gd::LinearSolver::kSparseCholesky;
  for (auto _ : state) {
    gd::backward_euler_step(s, dt, options);
    benchmark::DoNotOptimize(s.x.data());
  }
  SetCounters(state, s, 0.0);
}

// keeps the console table and records every repetition's time per step per spring
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  RecordingReporter() : ConsoleReporter(OO_Tabular) {}
  struct Entry {
    std::vector<double> ns_per_spring;
    double cg_iterations = 0.0;
  };
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      Entry& e = entries[run.run_name.function_name][run.run_name.args];
      const double springs = run.counters.at("springs").value;
      e.ns_per_spring.push_back(run.GetAdjustedRealTime() / springs);  // ns per iteration
      e.cg_iterations = run.counters.at("cg_iterations").value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  // by contender, then by size
  std::map<std::string, std::map<std::string, Entry>> entries;
};

struct Summary {
  double min = 0.0, median = 0.0;
};

Summary Summarize(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  cpu_set_t one_core;
  CPU_ZERO(&one_core);
  CPU_SET(0, &one_core);
  if (sched_setaffinity(0, sizeof one_core, &one_core) != 0)
    std::fprintf(stderr, "bench_deformable_ratios: could not pin to core 0\n");
  const char* contenders[] = {"floor",
                              "symplectic_euler",
                              "explicit_stepper",
                              "backward_euler_cg",
                              "backward_euler_cg_cold",
                              "backward_euler_cholesky",
                              "backward_euler_cholesky_fresh"};
  for (long n : kSizes) {
    benchmark::RegisterBenchmark(contenders[0], BM_Floor)->Arg(n);
    benchmark::RegisterBenchmark(contenders[1], BM_SymplecticEuler)->Arg(n);
    benchmark::RegisterBenchmark(contenders[2], BM_ExplicitStepper)->Arg(n);
    benchmark::RegisterBenchmark(contenders[3], BM_BackwardEuler,
                                 gd::LinearSolver::kConjugateGradient, true)
        ->Arg(n);
    benchmark::RegisterBenchmark(contenders[4], BM_BackwardEuler,
                                 gd::LinearSolver::kConjugateGradient, false)
        ->Arg(n);
    benchmark::RegisterBenchmark(contenders[5], BM_BackwardEuler, gd::LinearSolver::kSparseCholesky,
                                 true)
        ->Arg(n);
    if (n <= kLargestFresh)
      benchmark::RegisterBenchmark(contenders[6], BM_BackwardEulerFresh)->Arg(n);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  std::printf("\n%-30s %9s %12s %12s %10s %10s %8s\n", "contender", "springs", "min ns/spr",
              "median", "min/floor", "med/floor", "CG its");
  for (long n : kSizes) {
    const std::string size = std::to_string(n);
    const auto floor = reporter.entries["floor"].find(size);
    if (floor == reporter.entries["floor"].end()) continue;
    const Summary f = Summarize(floor->second.ns_per_spring);
    for (const char* name : contenders) {
      const auto it = reporter.entries[name].find(size);
      if (it == reporter.entries[name].end()) continue;
      const Summary c = Summarize(it->second.ns_per_spring);
      std::printf("%-30s %9ld %12.2f %12.2f %10.1f %10.1f %8.1f\n", name, n, c.min, c.median,
                  c.min / f.min, c.median / f.median, it->second.cg_iterations);
    }
  }
  return 0;
}
