// SPDX-License-Identifier: BSD-3-Clause
// pi, for the library's sources (C++17 has no std::numbers). Private to the library.
#pragma once

namespace gencoord::deformable::detail {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace gencoord::deformable::detail
