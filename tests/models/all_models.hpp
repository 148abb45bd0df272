// SPDX-License-Identifier: BSD-3-Clause
// The generated models every model test runs on, as a GoogleTest type list: every model that
// python/gencoord/tool/model_list.py lists (model_list.hpp, written at build time), atlas charts
// included.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "model_list.hpp"

namespace gencoord::testing {

template <class List>
struct TypesOf;
template <class... M>
struct TypesOf<model_list::List<M...>> {
  using type = ::testing::Types<M...>;
};

using AllModels = TypesOf<model_list::Models>::type;

/// Prints a model type as its name in test output (TypedTest/pendulum, ...).
struct ModelNames {
  template <class M>
  static std::string GetName(int) {
    return M::name;
  }
};

}  // namespace gencoord::testing
