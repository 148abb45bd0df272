// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Random values for the fuzz tests: mostly ordinary, sometimes extreme or invalid (0,
// negative, tiny, huge, NaN, inf), from a seeded generator so every run is the same.

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace gencoord::fuzz {

class Values {
 public:
  explicit Values(std::uint64_t seed) : rng_(seed) {}

  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }

  /// A value in [-scale, scale], or with probability `odd` an extreme or invalid one.
  double maybe_bad(double scale, double odd = 0.1) {
    if (!chance(odd)) return uniform(-scale, scale);
    static constexpr double kOdd[] = {0.0,
                                      -0.0,
                                      1e-300,
                                      -1e-300,
                                      1e300,
                                      -1e300,
                                      1e154,
                                      1e-12,
                                      -1.0,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity()};
    return kOdd[integer(0, sizeof kOdd / sizeof kOdd[0] - 1)];
  }

  /// A positive quantity of typical size `typical` (log-uniform over 4 decades around it),
  /// or with probability `odd` an extreme or invalid one.
  double maybe_bad_positive(double typical, double odd = 0.1) {
    if (!chance(odd)) return typical * std::pow(10.0, uniform(-2.0, 2.0));
    return maybe_bad(typical, 1.0);
  }

  /// A step size: log-uniform from 1e-300 to 1e300 with probability `wild`, else from 1e-6 to
  /// 1; sometimes 0, negative, NaN or inf.
  double step_size(double wild = 0.3) {
    if (chance(0.1)) return maybe_bad(1.0, 1.0);
    return chance(wild) ? std::pow(10.0, uniform(-300.0, 300.0))
                        : std::pow(10.0, uniform(-6.0, 0.0));
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace gencoord::fuzz
