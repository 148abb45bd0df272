// SPDX-License-Identifier: BSD-3-Clause
// Where the tests find the mesh files of tests/meshes. The folder is in mesh_files.cc, which
// CMake writes at configure time: as a compile definition it would be in every test file's
// compile command, and ccache would compile them all again in each checkout.
#pragma once

#include <string>

namespace gencoord::deformable {

/// The folder of the test meshes (Gmsh .msh, .obj), without a trailing '/'.
std::string test_meshes_dir();

/// test_meshes_dir(), for the tests' paths.
inline const std::string kMeshes = test_meshes_dir();

}  // namespace gencoord::deformable
