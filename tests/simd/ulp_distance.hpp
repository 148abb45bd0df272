// SPDX-License-Identifier: BSD-3-Clause
// The distance in units in the last place between two doubles, for the tests that compare
// vector math (libmvec) with std::.
#pragma once

#include <cstdint>
#include <cstring>

namespace gencoord::testing {

/// Distance in units in the last place between two finite doubles of the same sign.
inline std::int64_t ulp_distance(double a, double b) {
  std::int64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x > y ? x - y : y - x;
}

}  // namespace gencoord::testing
