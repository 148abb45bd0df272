// SPDX-License-Identifier: BSD-3-Clause
// What the interleaved comparisons of bench/ share: pinning the process to one core, the time
// per call of a contender over a set of states, and the minimum and median over rounds.
#pragma once

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

namespace gencoord::bench {

/// Pins the process to core 0, or says on stderr that `program`'s figures may be noisier.
inline void pin_to_one_core(const char* program) {
  cpu_set_t one_core;
  CPU_ZERO(&one_core);
  CPU_SET(0, &one_core);
  if (sched_setaffinity(0, sizeof one_core, &one_core) != 0)
    std::fprintf(stderr, "%s: could not pin to core 0; figures may be noisier\n", program);
}

/// Nanoseconds per call of `call(k)` over k = 0 .. count - 1.
inline double ns_per_call(int count, const std::function<void(int)>& call) {
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < count; ++k) call(k);
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(stop - start).count() / count;
}

/// `result` (an Eigen object) with every entry computed and stored: reading one entry of an
/// inlined kernel's result lets the compiler drop the work of the others (mass_matrix(0, 0)
/// of a legged robot needs one leg's), which would time a fraction of the kernel.
template <class Result>
inline const Result& kept(const Result& result) {
  asm volatile("" : : "r"(result.data()) : "memory");
  return result;
}

struct Summary {
  double min, median;
};

/// The minimum and the median of a contender's times over the rounds.
inline Summary summarize(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2]};
}

}  // namespace gencoord::bench
