// SPDX-License-Identifier: BSD-3-Clause
// Test-property formatting for the tests' measured figures (RecordProperty).
#pragma once

#include <cstdio>
#include <string>

namespace gencoord::testing {

/// A figure for RecordProperty, three significant digits (std::to_string prints 6 fixed
/// decimals, which hides 1e-11).
inline std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace gencoord::testing
