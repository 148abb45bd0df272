// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the mesh readers on arbitrary bytes. The first byte picks the reader (Gmsh
// .msh in 2D or 3D, TetGen/Triangle .node + .ele in 2D or 3D, the two files split at the first
// '@', or Wavefront .obj); the rest is the file. Each input must give a mesh or a MeshError,
// the readers' documented refusal; another exception, a crash or a sanitizer report
// (AddressSanitizer, UndefinedBehaviorSanitizer: signed overflow, bad shifts, out-of-range
// conversions) is a finding. Built and run by scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mesh_io.hpp"

namespace {

namespace deformable = gencoord::deformable;

template <int Dim>
void read_pair(const std::string& text) {
  const std::size_t split = text.find('@');
  std::istringstream node(text.substr(0, split));
  std::istringstream ele(split == std::string::npos ? std::string() : text.substr(split + 1));
  deformable::read_tetgen<Dim>(node, "fuzz.node", ele, "fuzz.ele");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::istringstream in(text);
  try {
    switch (data[0] % 5) {
      case 0:
        deformable::read_gmsh<2>(in, "fuzz.msh");
        break;
      case 1:
        deformable::read_gmsh<3>(in, "fuzz.msh");
        break;
      case 2:
        read_pair<2>(text);
        break;
      case 3:
        read_pair<3>(text);
        break;
      default:
        deformable::read_obj(in, "fuzz.obj");
        break;
    }
  } catch (const deformable::MeshError&) {
    // the documented refusal of a file that is no mesh
  }
  return 0;
}
