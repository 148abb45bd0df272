// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The check of the mesh readers' refusals, shared by their tests.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>

#include "gencoord/deformable/errors.hpp"

namespace gencoord::deformable::testing {

/// Runs `read`, expects a MeshFileError at `line` whose message contains `text`.
inline void ExpectRefused(const std::function<void()>& read, int line, const std::string& text) {
  try {
    read();
    ADD_FAILURE() << "accepted; expected a refusal containing: " << text;
  } catch (const MeshFileError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_THAT(e.what(), ::testing::HasSubstr(text));
    std::printf("[ refused ] %s\n", e.what());
  }
}

}  // namespace gencoord::deformable::testing
