// SPDX-License-Identifier: BSD-3-Clause
// The generated headers' gencoord_kernel_math::sin_cos (the sines and cosines of a kernel's
// coordinates in one call) against std::sin and std::cos, for every count up to 9 (whole
// vectors and the padded rest); included by a test compiled for AVX2 where the machine has
// it (tests/simd) and by one at the baseline instruction set (tests/models).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>  // std::integer_sequence

#include "generated/double_pendulum.hpp"  // a small header that defines the helper
#include "ulp_distance.hpp"

namespace gencoord::testing {

/// The worst distance so far, in ulp and absolute, from std::sin and std::cos (near a zero
/// of sin or cos an ulp of the result is tiny: the ulp count skips results below 1e-3).
struct KernelSinCosError {
  std::int64_t ulps = 0;
  double absolute = 0.0;
  int inexact = 0;  // results not equal to std::'s: none when the helper calls std::sin, cos
};

/// `rounds` random argument lists of count n through the generated headers' sin_cos.
template <int n>
void check_kernel_sin_cos(std::mt19937& rng, int rounds, KernelSinCosError* worst) {
  std::uniform_real_distribution<double> angle(-50.0, 50.0);
  for (int round = 0; round < rounds; ++round) {
    double x[n], s[n], c[n];
    for (double& a : x) a = angle(rng);
    gencoord_kernel_math::sin_cos(x, s, c);
    for (int i = 0; i < n; ++i) {
      const double fs = std::sin(x[i]), fc = std::cos(x[i]);
      if (std::abs(fs) > 1e-3) worst->ulps = std::max(worst->ulps, ulp_distance(s[i], fs));
      if (std::abs(fc) > 1e-3) worst->ulps = std::max(worst->ulps, ulp_distance(c[i], fc));
      worst->absolute = std::max({worst->absolute, std::abs(s[i] - fs), std::abs(c[i] - fc)});
      worst->inexact += (s[i] != fs) + (c[i] != fc);
    }
  }
}

template <int... n>
void check_kernel_sin_cos_counts(std::integer_sequence<int, n...>, std::mt19937& rng, int rounds,
                                 KernelSinCosError* worst) {
  (check_kernel_sin_cos<n + 1>(rng, rounds, worst), ...);
}

/// Every count from 1 to 9: whole vectors of 2 and 4 lanes and the padded rest.
inline KernelSinCosError worst_kernel_sin_cos(int rounds) {
  std::mt19937 rng(5);
  KernelSinCosError worst;
  check_kernel_sin_cos_counts(std::make_integer_sequence<int, 9>{}, rng, rounds, &worst);
  return worst;
}

}  // namespace gencoord::testing
