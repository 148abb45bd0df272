// SPDX-License-Identifier: BSD-3-Clause
// Batch throughput of qddot on one core: the scalar batch (batch_qddot, one state per kernel
// call) against batch_qddot_simd with 4 and 8 lanes (Pack<4>, Pack<8>: the generated kernel
// instantiated on a pack of doubles), over the same 1024 random states, interleaved, pinned to
// one core. The table gives the minimum and the median over the rounds of the time per state,
// and the ratios.
//   build/bench/bench_simd [rounds]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <vector>

#include "gencoord/parallel/batch.hpp"
#include "gencoord/simd/batch.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/iiwa14.hpp"
#include "generated/n_link_chain_10.hpp"

#include "interleaved.hpp"

namespace {

using gencoord::State;

constexpr int kStates = 1024;
volatile double sink = 0.0;  // keeps the results alive

using gencoord::bench::summarize;
using gencoord::bench::Summary;

template <class M>
void compare(const char* name, int rounds) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<State<M>> states(kStates);
  for (auto& s : states) {
    for (int i = 0; i < M::nq; ++i) s.q[i] = 3.0 * unit(rng);
    for (int i = 0; i < gencoord::nv_of_v<M>; ++i) s.v[i] = 2.0 * unit(rng);
    if constexpr (gencoord::has_generalized_speeds_v<M>)
      for (const int start : M::quaternion_starts) s.q.template segment<4>(start).normalize();
  }
  const typename M::Params p;
  std::vector<gencoord::VVec<M>> out;
  struct Contender {
    const char* name;
    std::function<void()> run;
    std::vector<double> ns;
  };
  std::vector<Contender> contenders = {
      {"batch_qddot (scalar)", [&] { gencoord::batch_qddot<M>(states, {p}, &out, 1); }, {}},
      {"batch_qddot_simd, 4 lanes",
       [&] { gencoord::batch_qddot_simd<M, 4>(states, p, &out, 1); },
       {}},
      {"batch_qddot_simd, 8 lanes",
       [&] { gencoord::batch_qddot_simd<M, 8>(states, p, &out, 1); },
       {}},
  };
  for (int round = 0; round < rounds; ++round) {
    for (auto& c : contenders) {
      const auto start = std::chrono::steady_clock::now();
      c.run();
      const auto stop = std::chrono::steady_clock::now();
      sink = sink + out[0][0];
      c.ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / kStates);
    }
  }
  std::printf("\n%s (nq = %d), ns per state over %d rounds of %d states, one thread\n", name, M::nq,
              rounds, kStates);
  std::printf("%-40s %10s %10s\n", "contender", "min", "median");
  std::vector<Summary> summaries;
  for (auto& c : contenders) {
    summaries.push_back(summarize(c.ns));
    std::printf("%-40s %10.1f %10.1f\n", c.name, summaries.back().min, summaries.back().median);
  }
  for (int k = 1; k < 3; ++k)
    std::printf("ratio scalar / %-25s %10.2f %10.2f\n", contenders[k].name + 12,
                summaries[0].min / summaries[k].min, summaries[0].median / summaries[k].median);
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 51;
  gencoord::bench::pin_to_one_core("bench_simd");
  std::printf("Pack<4>: %s; sin and cos: %s\n",
#if defined(__AVX2__)
              "one AVX2 register",
#else
              "two SSE2 registers",
#endif
              GENCOORD_HAVE_LIBMVEC ? "libmvec" : "std::sin, std::cos lane by lane");
  compare<gencoord::models::DoublePendulum>("double_pendulum", rounds);
  compare<gencoord::models::NLinkChain10>("n_link_chain_10", rounds);
  compare<gencoord::models::Iiwa14>("iiwa14", rounds);
  compare<gencoord::models::FloatingQuadruped>("floating_quadruped", rounds);
}
