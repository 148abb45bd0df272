// SPDX-License-Identifier: BSD-3-Clause
// Cost of contact: the forces of a tetrahedral cube with its surface's self-contact and a box
// obstacle under it (the spatial hash rebuilt, every surface node tested against the
// triangles near it) against the same forces without contact, on cubes of about 1e3, 1e4 and
// 1e5 nodes. Google Benchmark interleaves the repetitions of both contenders at random in
// this one process, pinned to core 0. After its table comes one line per size: ns per
// evaluation of each (minimum and median over the repetitions), the contact's extra cost per
// surface triangle, and the ratio of the two.
//
//   taskset -c 0 build/deformable/bench_deformable_contact --benchmark_repetitions=7
//       --benchmark_enable_random_interleaving=true --benchmark_min_time=0.2   (one line)
#include <benchmark/benchmark.h>
#include <sched.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "gencoord/deformable/collision.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"

namespace gd = gencoord::deformable;
using Solid = gd::MassSpringSystem<3>;

namespace {

const int kCells[] = {9, 21, 46};  // (cells + 1)^3 nodes: 1000, 10648, 103823

// a unit cube of cells^3 Kuhn cells, resting 1% of a cell deep in a box obstacle, with its
// boundary's self-contact on or off; built once per size
const Solid& CubeOf(int cells, bool contact) {
  static std::map<std::pair<int, bool>, Solid> cubes;
  auto it = cubes.find({cells, contact});
  if (it == cubes.end()) {
    const gd::SimplexMesh<3> mesh = gd::box_mesh(1.0, 1.0, 1.0, cells, cells, cells);
    Solid s = gd::make_mass_spring(mesh, gd::Material{1e5, 1000.0, 10.0});
    s.gravity << 0.0, 0.0, -9.81;
    if (contact) {
      auto& c = gd::enable_collisions<3>(s, gd::boundary_triangles(mesh), 0.5, 0.3);
      c.boxes.push_back({Eigen::Vector3d(-1.0, -1.0, -1.0),
                         Eigen::Vector3d(2.0, 2.0, 0.01 / static_cast<double>(cells))});
    }
    it = cubes.emplace(std::make_pair(cells, contact), std::move(s)).first;
  }
  return it->second;
}

void BM_Forces(benchmark::State& state, bool contact) {
  const Solid& s = CubeOf(static_cast<int>(state.range(0)), contact);
  Solid::Points f(3, s.num_nodes());
  for (auto _ : state) {
    f.setZero();
    gd::accumulate_forces(s, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = s.num_nodes();
  state.counters["triangles"] = static_cast<double>(
      CubeOf(static_cast<int>(state.range(0)), true).collisions->surface.size());
}

// keeps the console table and records every repetition's time per evaluation
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  RecordingReporter() : ConsoleReporter(OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      auto& e = entries[run.run_name.function_name][run.run_name.args];
      e.first.push_back(run.GetAdjustedRealTime());  // ns per evaluation
      e.second = run.counters.at("triangles").value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  // by contender, then by size: the repetitions' times and the surface triangles
  std::map<std::string, std::map<std::string, std::pair<std::vector<double>, double>>> entries;
};

std::pair<double, double> MinAndMedian(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  cpu_set_t one_core;
  CPU_ZERO(&one_core);
  CPU_SET(0, &one_core);
  if (sched_setaffinity(0, sizeof one_core, &one_core) != 0)
    std::fprintf(stderr, "bench_deformable_contact: could not pin to core 0\n");
  for (int cells : kCells) {
    benchmark::RegisterBenchmark("forces", BM_Forces, false)->Arg(cells);
    benchmark::RegisterBenchmark("forces_with_contact", BM_Forces, true)->Arg(cells);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  std::printf("\n%6s %9s %14s %14s %14s %14s %12s %10s\n", "cells", "triangles", "forces min ns",
              "median", "contact min ns", "median", "extra ns/tri", "min ratio");
  for (int cells : kCells) {
    const std::string size = std::to_string(cells);
    const auto& plain = reporter.entries["forces"][size];
    const auto& contact = reporter.entries["forces_with_contact"][size];
    if (plain.first.empty() || contact.first.empty()) continue;
    const auto p = MinAndMedian(plain.first), c = MinAndMedian(contact.first);
    std::printf("%6d %9.0f %14.0f %14.0f %14.0f %14.0f %12.1f %10.2f\n", cells, contact.second,
                p.first, p.second, c.first, c.second, (c.first - p.first) / contact.second,
                c.first / p.first);
  }
  return 0;
}
