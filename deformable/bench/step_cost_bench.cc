// SPDX-License-Identifier: BSD-3-Clause
// Cost of one time step per spring, explicit (symplectic Euler) and implicit (backward Euler
// with conjugate gradient, the stepper keeping its pattern), on 2D sheets of about 1e3, 1e4
// and 1e5 springs. The per-spring cost ("per_spring") should stay flat as the size grows:
// stepping is linear in the springs. bench_deformable_ratios compares the steps with the
// springs' forces alone.
//
//   bench_deformable --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gd = gencoord::deformable;

namespace {

// A square sheet with about `springs` springs (3 per cell), pinned along its left edge,
// under gravity and slightly perturbed so every step does real work.
gd::MassSpringSystem<2> MakeSheet(int springs) {
  const int cells = static_cast<int>(std::lround(std::sqrt(springs / 3.0)));
  gd::MassSpringSystem<2> s =
      gd::make_mass_spring(gd::rectangle_mesh(1.0, 1.0, cells, cells), gd::Material{1e4, 1.0, 1.0});
  gd::pin_nodes_where(s, 0, 0.0);
  s.gravity << 0.0, -9.81;
  return s;
}

void SetCounters(benchmark::State& state, const gd::MassSpringSystem<2>& s) {
  const double springs = static_cast<double>(s.springs.size());
  state.counters["springs"] = springs;
  // seconds per step per spring
  state.counters["per_spring"] = benchmark::Counter(
      springs, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SymplecticEulerStep(benchmark::State& state) {
  gd::MassSpringSystem<2> s = MakeSheet(static_cast<int>(state.range(0)));
  const double dt = 0.9 * gd::cfl_limit(s);
  for (auto _ : state) {
    gd::symplectic_euler_step(s, dt);
    benchmark::DoNotOptimize(s.x.data());
  }
  SetCounters(state, s);
}

void BM_BackwardEulerStep(benchmark::State& state) {
  gd::MassSpringSystem<2> s = MakeSheet(static_cast<int>(state.range(0)));
  // a fixed multiple of each mesh's CFL limit keeps the CG iteration count size-independent
  const double dt = 10.0 * gd::cfl_limit(s);
  gd::BackwardEulerStepper<2> stepper;
  int iterations = 0;
  for (auto _ : state) {
    iterations = stepper.step(s, dt).iterations;
    benchmark::DoNotOptimize(s.x.data());
  }
  SetCounters(state, s);
  state.counters["cg_iterations"] = iterations;
}

}  // namespace

BENCHMARK(BM_SymplecticEulerStep)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BackwardEulerStep)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
