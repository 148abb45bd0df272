// SPDX-License-Identifier: BSD-3-Clause
// One backward Euler step at 10 times the CFL limit of large 3D blocks (1 x 0.5 x 0.5 m,
// pinned at one end, sagging under gravity): about 180k springs, and about 105k co-rotated
// tetrahedra (continuum_elements.hpp), with conjugate gradients (the default) and the
// stepper keeping its pattern. Time per step, CG iterations per step; run pinned to one core:
//
//   taskset -c 0 build-bench/deformable/bench_deformable_large --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_counters_tabular=true
// (one command line)
#include <benchmark/benchmark.h>

#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gd = gencoord::deformable;

namespace {

gd::MassSpringSystem<3> MakeBlock(bool continuum) {
  gd::Material material{1e5, 1000.0, 10.0};
  if (continuum) {
    material.poisson_ratio = 0.3;
    material.elasticity = gd::Elasticity::kCorotated;
  }
  // 46 x 23 x 23 cells: 178,365 springs; 50 x 25 x 14: 105,000 tetrahedra
  gd::MassSpringSystem<3> s =
      continuum ? gd::make_mass_spring(gd::box_mesh(1.0, 0.5, 0.5, 50, 25, 14), material)
                : gd::make_mass_spring(gd::box_mesh(1.0, 0.5, 0.5, 46, 23, 23), material);
  gd::pin_nodes_where(s, 0, 0.0);
  s.gravity << 0.0, 0.0, -9.81;
  return s;
}

void BM_BackwardEulerStep(benchmark::State& state, bool continuum) {
  gd::MassSpringSystem<3> s = MakeBlock(continuum);
  const double dt = 10.0 * gd::cfl_limit(s);
  gd::BackwardEulerStepper<3> stepper;
  stepper.step(s, dt);  // the pattern, built once
  long iterations = 0;
  for (auto _ : state) {
    iterations += stepper.step(s, dt).iterations;
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["springs"] = static_cast<double>(s.springs.size());
  state.counters["tetrahedra"] = static_cast<double>(s.elements.size());
  state.counters["cg_iterations"] =
      static_cast<double>(iterations) / static_cast<double>(state.iterations());
}

BENCHMARK_CAPTURE(BM_BackwardEulerStep, springs, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BackwardEulerStep, corotated, true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
