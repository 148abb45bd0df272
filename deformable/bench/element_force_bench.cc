// SPDX-License-Identifier: BSD-3-Clause
// Cost of a co-rotated tetrahedron's forces (continuum_element_forces(), whose polar
// decomposition F = R S is the main cost) against Eigen's JacobiSVD of the same deformation
// gradients alone, per element, on a 10 x 10 x 10 block of 6000 tetrahedra stretched and
// sheared at random (a sixth of them inverted). Google Benchmark interleaves the repetitions
// of both contenders at random in this one process; pin it to one core:
//
//   taskset -c 0 build/deformable/bench_deformable_elements --benchmark_repetitions=9
//       --benchmark_enable_random_interleaving=true   (one line)
//
// Each reports the minimum, median and mean over the repetitions, in ns per element.
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <random>
#include <vector>

#include "gencoord/deformable/continuum_elements.hpp"
#include "gencoord/deformable/mesh.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"

namespace gd = gencoord::deformable;

namespace {

struct Block {
  gd::MassSpringSystem<3> object;
  std::vector<gd::Corners<3>> corners;
  std::vector<Eigen::Matrix3d> gradients;
};

const Block& TheBlock() {
  static const Block block = [] {
    gd::Material material{1e5, 1000.0, 0.0};
    material.poisson_ratio = 0.3;
    material.elasticity = gd::Elasticity::kCorotated;
    Block b{gd::make_mass_spring(gd::box_mesh(1.0, 1.0, 1.0, 10, 10, 10), material), {}, {}};
    std::mt19937 random(7);
    std::normal_distribution<double> move(0.0, 0.04);
    for (int n = 0; n < b.object.num_nodes(); ++n)
      for (int d = 0; d < 3; ++d) b.object.x(d, n) += move(random);
    for (const gd::ContinuumElement<3>& e : b.object.elements) {
      b.corners.push_back(gd::corners_of(e, b.object.x));
      b.gradients.push_back(gd::deformation_gradient(e, b.corners.back()));
    }
    return b;
  }();
  return block;
}

void PerElement(benchmark::State& state, const Block& b) {
  state.counters["ns_per_element"] =
      benchmark::Counter(static_cast<double>(state.iterations() * b.object.elements.size()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["elements"] = static_cast<double>(b.object.elements.size());
  state.counters["inverted"] = static_cast<double>(std::count_if(
      b.gradients.begin(), b.gradients.end(), [](const auto& f) { return f.determinant() < 0; }));
}

void BM_ElementForces(benchmark::State& state) {
  const Block& b = TheBlock();
  const gd::Corners<3> still{};
  for (auto _ : state) {
    for (std::size_t e = 0; e < b.corners.size(); ++e) {
      const gd::Corners<3> f =
          gd::continuum_element_forces(b.object.elements[e], b.corners[e], still);
      benchmark::DoNotOptimize(f);
    }
  }
  PerElement(state, b);
}

void BM_JacobiSvdAlone(benchmark::State& state) {
  const Block& b = TheBlock();
  for (auto _ : state) {
    for (const Eigen::Matrix3d& f : b.gradients) {
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
      benchmark::DoNotOptimize(svd.singularValues().data());
      benchmark::DoNotOptimize(svd.matrixU().data());
      benchmark::DoNotOptimize(svd.matrixV().data());
    }
  }
  PerElement(state, b);
}

double Minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

}  // namespace

BENCHMARK(BM_ElementForces)->ComputeStatistics("min", Minimum);
BENCHMARK(BM_JacobiSvdAlone)->ComputeStatistics("min", Minimum);
BENCHMARK_MAIN();
