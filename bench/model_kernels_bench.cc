// SPDX-License-Identifier: BSD-3-Clause
// ns per generated qddot (Mt, Ft + Fi and a fixed-size Cholesky) and per RK4 step, for every
// built-in model (python/gencoord/tool/model_list.py --benchmarks: models/ and
// models/variants.txt). Run: scripts/bench.sh (or build/bench/bench_model_kernels
// --benchmark_min_time=0.2s).
#include <random>

#include <benchmark/benchmark.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "model_list.hpp"  // every built-in model, written at build time

namespace {

template <class M>
gencoord::State<M> bench_state() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.3, 1.3), rate(-1.0, 1.0);
  gencoord::State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = angle(rng);
    s.v[i] = rate(rng);
  }
  return s;
}

template <class M>
void BM_qddot(benchmark::State& state) {
  const typename M::Params p;
  auto s = bench_state<M>();
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.q.data());
    benchmark::DoNotOptimize(s.v.data());
    auto a = M::qddot(s.q, s.v, s.t, p);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["nq"] = M::nq;
}

template <class M>
void BM_rk4_step(benchmark::State& state) {
  const typename M::Params p;
  auto s = bench_state<M>();
  const auto start = s;
  for (auto _ : state) {
    s = gencoord::step(gencoord::ReducedSystem<M>(p), gencoord::Integrator::RK4, s, 1e-4);
    benchmark::DoNotOptimize(s.q.data());
    benchmark::ClobberMemory();
    if (s.t > 1.0) s = start;  // stay near the benchmark state
  }
  state.counters["nq"] = M::nq;
}

template <class... Models>
void register_all(gencoord::model_list::List<Models...>) {
  (benchmark::RegisterBenchmark((std::string("qddot/") + Models::name).c_str(), BM_qddot<Models>),
   ...);
  (benchmark::RegisterBenchmark((std::string("rk4_step/") + Models::name).c_str(),
                                BM_rk4_step<Models>),
   ...);
}

}  // namespace

int main(int argc, char** argv) {
  register_all(gencoord::model_list::Models{});
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
