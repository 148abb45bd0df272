// SPDX-License-Identifier: BSD-3-Clause
// Time per backward-Euler step with generated vs finite-difference Jacobians (the Newton
// iteration's da/dq, da/dv), Newton iterations per step for both, and their ratio, on the
// double pendulum, the 10-link chain and the stiff 10-link chain.
// Run: build/bench/bench_implicit [--benchmark_min_time=0.5s]
// After the Google Benchmark table it prints one line per model: ns per step with each source
// and the ratio fd / generated, all measured in this one run.
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_10.hpp"
#include "generated/stiff_chain_10.hpp"

namespace {

using gencoord::JacobianSource;

// random angles and rates, as bench/model_kernels_bench.cc; the stiff chain starts from its
// model file's state instead (phi1 = 0.3 rad, at rest): random relative angles would strain its
// k = 1000 N m/rad springs far beyond anything its model is meant for
template <class M>
gencoord::State<M> bench_state(bool stiff) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.3, 1.3), rate(-1.0, 1.0);
  gencoord::State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = stiff ? M::initial_q[static_cast<std::size_t>(i)] : angle(rng);
    s.v[i] = stiff ? M::initial_v[static_cast<std::size_t>(i)] : rate(rng);
  }
  return s;
}

template <class M>
void BM_backward_euler_step(benchmark::State& state, JacobianSource source, double h, bool stiff) {
  const typename M::Params p;
  gencoord::NewtonOptions options;
  options.jacobian = source;
  gencoord::StepStats stats;
  const auto start = bench_state<M>(stiff);
  auto s = start;
  for (auto _ : state) {
    s = gencoord::backward_euler_step(gencoord::ReducedSystem<M>(p), s, h, options, &stats);
    benchmark::DoNotOptimize(s.q.data());
    benchmark::ClobberMemory();
    if (s.t > 0.5) s = start;  // stay near the benchmark state
  }
  state.counters["nq"] = M::nq;
  state.counters["newton_iters_per_step"] =
      double(stats.newton_iterations) / double(std::max(1L, stats.newton_solves));
}

// keeps the console table and records ns per iteration and Newton iterations per benchmark
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  RecordingReporter() : ConsoleReporter(OO_Tabular) {}  // no colour codes in logs
  struct Entry {
    double ns = 0.0;
    double iterations = 0.0;
  };
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      Entry& e = entries[run.benchmark_name()];
      e.ns = run.GetAdjustedRealTime();  // per iteration, in the run's time unit (ns)
      const auto it = run.counters.find("newton_iters_per_step");
      if (it != run.counters.end()) e.iterations = it->second.value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, Entry> entries;
};

template <class M>
void register_model(double h, bool stiff = false) {
  const std::string base = std::string("backward_euler_step/") + M::name;
  benchmark::RegisterBenchmark((base + "/generated").c_str(), BM_backward_euler_step<M>,
                               JacobianSource::Generated, h, stiff);
  benchmark::RegisterBenchmark((base + "/finite_difference").c_str(), BM_backward_euler_step<M>,
                               JacobianSource::FiniteDifference, h, stiff);
}

}  // namespace

int main(int argc, char** argv) {
  register_model<gencoord::models::DoublePendulum>(0.01);
  register_model<gencoord::models::NLinkChain10>(0.01);
  register_model<gencoord::models::StiffChain10>(0.01, true);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  // side by side: generated vs finite differences, same run
  std::printf("\n%-18s %6s %14s %10s %14s %10s %8s\n", "model (h = 0.01)", "nq", "gen ns/step",
              "gen iters", "fd ns/step", "fd iters", "fd/gen");
  const std::pair<const char*, int> models[] = {
      {"double_pendulum", 2}, {"n_link_chain_10", 10}, {"stiff_chain_10", 10}};
  for (const auto& [name, nq] : models) {
    const std::string base = std::string("backward_euler_step/") + name;
    const auto g = reporter.entries.find(base + "/generated");
    const auto f = reporter.entries.find(base + "/finite_difference");
    if (g == reporter.entries.end() || f == reporter.entries.end()) continue;  // filtered out
    std::printf("%-18s %6d %14.0f %10.2f %14.0f %10.2f %7.2fx\n", name, nq, g->second.ns,
                g->second.iterations, f->second.ns, f->second.iterations,
                f->second.ns / g->second.ns);
  }
  return 0;
}
