// SPDX-License-Identifier: BSD-3-Clause
// Where the robot tests find the URDF files they load. The folders are in test_files.cc,
// which CMake writes at configure time: as compile definitions they would be in every test
// file's compile command, and ccache would compile them all again in each checkout.
#pragma once

#include <string>

namespace gencoord::robot_testing {

/// `relative` under the source checkout, e.g. "models/iiwa14.urdf".
std::string source_file(const std::string& relative);
/// `relative` under tests/robots of the build folder (files the build makes).
std::string build_file(const std::string& relative);

}  // namespace gencoord::robot_testing
