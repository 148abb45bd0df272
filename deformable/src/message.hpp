// SPDX-License-Identifier: BSD-3-Clause
// An error message from its parts, numbers written with 17 significant digits so that the
// value at fault reads back exactly. Private to the library.
#pragma once

#include <sstream>
#include <string>

namespace gencoord::deformable::detail {

template <class... Parts>
std::string message(const Parts&... parts) {
  std::ostringstream os;
  os.precision(17);
  (os << ... << parts);
  return os.str();
}

}  // namespace gencoord::deformable::detail
