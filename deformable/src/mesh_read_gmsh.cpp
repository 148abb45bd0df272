// SPDX-License-Identifier: BSD-3-Clause
// Gmsh .msh reader: ASCII format 2.x and 4.1, triangles (type 2) or tetrahedra (type 4).
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "gencoord/deformable/mesh_io.hpp"
#include "mesh_read_text.hpp"

namespace gencoord::deformable {

namespace {

using detail::RawMesh;
using detail::TextLines;

// The nodes of a .msh by tag, before the elements say which are used.
struct GmshNodes {
  std::vector<Eigen::Vector3d> x;
  std::vector<long long> tags;
  std::vector<int> lines;
  std::unordered_map<long long, int> index;  // tag -> position in x
  bool read = false;
};

void add_node(TextLines& lines, GmshNodes& nodes, long long tag, const Eigen::Vector3d& x,
              const std::string& section) {
  const auto [it, inserted] = nodes.index.emplace(tag, static_cast<int>(nodes.x.size()));
  if (!inserted) {
    lines.fail(section + ": node tag " + std::to_string(tag) + " is defined twice (first on line " +
               std::to_string(nodes.lines[it->second]) + "); node tags must be unique");
  }
  nodes.x.push_back(x);
  nodes.tags.push_back(tag);
  nodes.lines.push_back(lines.line());
}

// Reads the line after the last node or element of a section and checks that it ends it.
void expect_end(TextLines& lines, const std::string& section, long long count, int count_line) {
  const std::string end = "$End" + section.substr(1);
  lines.expect_next("inside " + section + ", before " + end);
  if (lines.words()[0] != end) {
    lines.fail(section + ": expected " + end + " after the " + std::to_string(count) +
               " entries announced on line " + std::to_string(count_line) + ", got '" +
               lines.words()[0] + "'; the count and the entries disagree");
  }
}

// Reads the next entry line of a section, refusing a section that ends before its count.
void next_entry(TextLines& lines, const std::string& section, long long read, long long count,
                int count_line) {
  lines.expect_next("inside " + section + " after " + std::to_string(read) + " of its " +
                    std::to_string(count) + " entries");
  if (lines.words()[0][0] == '$') {
    lines.fail(section + ": '" + lines.words()[0] + "' after " + std::to_string(read) +
               " entries, but line " + std::to_string(count_line) + " announces " +
               std::to_string(count) + "; the count and the entries disagree");
  }
}

Eigen::Vector3d coordinates(TextLines& lines, size_t first, const std::string& section) {
  return {lines.real(first, section + ": x"), lines.real(first + 1, section + ": y"),
          lines.real(first + 2, section + ": z")};
}

void read_nodes_v2(TextLines& lines, GmshNodes& nodes) {
  lines.expect_next("inside $Nodes");
  lines.expect_words(1, "$Nodes", "number of nodes");
  const int count_line = lines.line();
  const long long count = lines.count(0, "$Nodes: number of nodes");
  for (long long k = 0; k < count; ++k) {
    next_entry(lines, "$Nodes", k, count, count_line);
    lines.expect_words(4, "$Nodes", "tag x y z");
    add_node(lines, nodes, lines.integer(0, "$Nodes: node tag"), coordinates(lines, 1, "$Nodes"),
             "$Nodes");
  }
  expect_end(lines, "$Nodes", count, count_line);
}

void read_nodes_v4(TextLines& lines, GmshNodes& nodes) {
  lines.expect_next("inside $Nodes");
  lines.expect_words(4, "$Nodes", "entity blocks, nodes, smallest tag, largest tag");
  const int count_line = lines.line();
  const long long blocks = lines.count(0, "$Nodes: number of entity blocks");
  const long long count = lines.count(1, "$Nodes: number of nodes");
  long long read = 0;
  for (long long b = 0; b < blocks; ++b) {
    next_entry(lines, "$Nodes", read, count, count_line);
    lines.expect_words(4, "$Nodes block", "entity dimension, entity tag, parametric, nodes");
    const long long entity_dim = lines.integer(0, "$Nodes block: entity dimension");
    const bool parametric = lines.integer(2, "$Nodes block: parametric") != 0;
    const long long in_block = lines.count(3, "$Nodes block: number of nodes");
    if (in_block > count - read) {  // read <= count: no overflow
      lines.fail("$Nodes block: " + std::to_string(in_block) + " more nodes make more than the " +
                 std::to_string(count) + " announced on line " + std::to_string(count_line) +
                 "; the count and the entries disagree");
    }
    // the block lists its tags first, then their coordinates in the same order
    std::vector<long long> tags;
    for (long long k = 0; k < in_block; ++k) {
      next_entry(lines, "$Nodes", read + k, count, count_line);
      lines.expect_words(1, "$Nodes block", "node tag");
      tags.push_back(lines.integer(0, "$Nodes block: node tag"));
    }
    const size_t numbers = 3 + (parametric ? static_cast<size_t>(entity_dim) : 0);
    for (long long k = 0; k < in_block; ++k) {
      next_entry(lines, "$Nodes", read + in_block, count, count_line);
      lines.expect_words(numbers, "$Nodes block", parametric ? "x y z and parameters" : "x y z");
      add_node(lines, nodes, tags[k], coordinates(lines, 0, "$Nodes"), "$Nodes");
    }
    read += in_block;
  }
  if (read != count) {
    lines.fail_at(count_line, "$Nodes: announces " + std::to_string(count) + " nodes, but its " +
                                  std::to_string(blocks) + " blocks hold " + std::to_string(read));
  }
  expect_end(lines, "$Nodes", count, count_line);
}

template <int Dim>
struct ElementReader {
  static constexpr int kType = Dim == 2 ? 2 : 4;  // 3-node triangle, 4-node tetrahedron
  TextLines& lines;
  const GmshNodes& nodes;
  RawMesh<Dim>& raw;
  std::map<long long, long long> skipped;  // other element types and their counts

  // Adds the element of the current line: its tag is word 0, its node tags start at word
  // `first_node`.
  void add(size_t first_node) {
    const long long tag = lines.integer(0, "$Elements: element tag");
    std::array<int, Dim + 1> el;
    for (int a = 0; a <= Dim; ++a) {
      const long long node = lines.integer(first_node + a, "$Elements: node tag");
      const auto it = nodes.index.find(node);
      if (it == nodes.index.end()) {
        lines.fail("$Elements: element " + std::to_string(tag) + " refers to node tag " +
                       std::to_string(node) + ", which $Nodes does not define",
                   static_cast<int>(raw.elements.size()), -1);
      }
      el[a] = it->second;
    }
    raw.elements.push_back(el);
    raw.element_lines.push_back(lines.line());
    raw.element_labels.push_back(tag);
  }
};

template <int Dim>
void read_elements_v2(ElementReader<Dim>& r) {
  TextLines& lines = r.lines;
  lines.expect_next("inside $Elements");
  lines.expect_words(1, "$Elements", "number of elements");
  const int count_line = lines.line();
  const long long count = lines.count(0, "$Elements: number of elements");
  for (long long k = 0; k < count; ++k) {
    next_entry(lines, "$Elements", k, count, count_line);
    if (lines.words().size() < 3) {
      lines.expect_words(3, "$Elements", "at least tag, type, number of tags");
    }
    const long long type = lines.integer(1, "$Elements: element type");
    const long long tags = lines.count(2, "$Elements: number of tags");
    if (type != ElementReader<Dim>::kType) {
      ++r.skipped[type];
      continue;
    }
    const long long words = static_cast<long long>(lines.words().size());
    if (tags > words) {  // before 3 + tags + ..., which could overflow
      lines.fail("$Elements: " + std::to_string(tags) + " tags announced, but the line has " +
                 std::to_string(words) + " numbers in all");
    }
    lines.expect_words(3 + tags + Dim + 1, "$Elements",
                       "tag, type, number of tags, " + std::to_string(tags) + " tags, " +
                           std::to_string(Dim + 1) + " node tags");
    r.add(3 + static_cast<size_t>(tags));  // the node tags follow the element's tags
  }
  expect_end(lines, "$Elements", count, count_line);
}

template <int Dim>
void read_elements_v4(ElementReader<Dim>& r) {
  TextLines& lines = r.lines;
  lines.expect_next("inside $Elements");
  lines.expect_words(4, "$Elements", "entity blocks, elements, smallest tag, largest tag");
  const int count_line = lines.line();
  const long long blocks = lines.count(0, "$Elements: number of entity blocks");
  const long long count = lines.count(1, "$Elements: number of elements");
  long long read = 0;
  for (long long b = 0; b < blocks; ++b) {
    next_entry(lines, "$Elements", read, count, count_line);
    lines.expect_words(4, "$Elements block",
                       "entity dimension, entity tag, element type, elements");
    const long long type = lines.integer(2, "$Elements block: element type");
    const long long in_block = lines.count(3, "$Elements block: number of elements");
    if (in_block > count - read) {  // read <= count: no overflow
      lines.fail("$Elements block: " + std::to_string(in_block) +
                 " more elements make more than the " + std::to_string(count) +
                 " announced on line " + std::to_string(count_line) +
                 "; the count and the entries disagree");
    }
    for (long long k = 0; k < in_block; ++k) {
      next_entry(lines, "$Elements", read + k, count, count_line);
      if (type != ElementReader<Dim>::kType) continue;
      lines.expect_words(Dim + 2, "$Elements", "tag and " + std::to_string(Dim + 1) + " node tags");
      r.add(1);
    }
    if (type != ElementReader<Dim>::kType) r.skipped[type] += in_block;
    read += in_block;
  }
  if (read != count) {
    lines.fail_at(count_line, "$Elements: announces " + std::to_string(count) +
                                  " elements, but its " + std::to_string(blocks) + " blocks hold " +
                                  std::to_string(read));
  }
  expect_end(lines, "$Elements", count, count_line);
}

}  // namespace

template <int Dim>
SimplexMesh<Dim> read_gmsh(std::istream& in, const std::string& name) {
  TextLines lines(in, name);
  if (!lines.next() || lines.words()[0] != "$MeshFormat") {
    lines.fail("expected $MeshFormat; this is not a Gmsh .msh file (or it is empty)");
  }
  lines.expect_next("inside $MeshFormat");
  lines.expect_words(3, "$MeshFormat", "version, file type, data size");
  const std::string version = lines.words()[0];
  const bool v2 = version == "2" || version.rfind("2.", 0) == 0;
  if (version == "4" || version == "4.0") {
    lines.fail("$MeshFormat: format version " + version +
               " is not read; save the mesh as format 4.1 or 2.2 (Gmsh: File > Export, or "
               "-format msh41)");
  }
  if (!v2 && version != "4.1") {
    lines.fail("$MeshFormat: unknown format version " + version +
               "; this reader reads 2.2 and 4.1 (Gmsh: File > Export, or -format msh41)");
  }
  if (lines.integer(1, "$MeshFormat: file type") != 0) {
    lines.fail(
        "$MeshFormat: the file is binary; save it as ASCII (Gmsh: uncheck \"Save in "
        "binary format\" when exporting, or leave out -bin)");
  }
  lines.expect_next("inside $MeshFormat");
  if (lines.words()[0] != "$EndMeshFormat") {
    lines.fail("$MeshFormat: expected $EndMeshFormat, got '" + lines.words()[0] + "'");
  }

  GmshNodes nodes;
  RawMesh<Dim> raw;
  ElementReader<Dim> elements{lines, nodes, raw, {}};
  int elements_line = 0;
  while (lines.next()) {
    const std::string section = lines.words()[0];
    if (section == "$Nodes") {
      if (nodes.read) lines.fail("a second $Nodes section; a mesh has one");
      v2 ? read_nodes_v2(lines, nodes) : read_nodes_v4(lines, nodes);
      nodes.read = true;
    } else if (section == "$Elements") {
      if (!nodes.read) lines.fail("$Elements before $Nodes; the nodes must come first");
      if (elements_line != 0) lines.fail("a second $Elements section; a mesh has one");
      elements_line = lines.line();
      v2 ? read_elements_v2(elements) : read_elements_v4(elements);
    } else if (section.size() > 1 && section[0] == '$') {
      // another section ($PhysicalNames, $Entities, $NodeData, ...): not needed here
      const std::string end = "$End" + section.substr(1);
      const int start = lines.line();
      do {
        lines.expect_next("inside " + section + " (started on line " + std::to_string(start) + ")");
      } while (lines.words()[0] != end);
    } else {
      lines.fail("expected a section such as $Nodes or $Elements, got '" + section + "'");
    }
  }
  if (!nodes.read || elements_line == 0) {
    lines.fail(std::string("the file has no ") + (nodes.read ? "$Elements" : "$Nodes") +
               " section; save the mesh again");
  }
  if (Dim == 2 && elements.skipped.count(4) != 0) {
    lines.fail_at(elements_line, "$Elements: the file has " + std::to_string(elements.skipped[4]) +
                                     " tetrahedra (type 4): it is a 3D mesh; read it as 3D");
  }
  if (raw.elements.empty()) {
    std::string other;
    for (const auto& [type, n] : elements.skipped) {
      other += (other.empty() ? "" : ", ") + std::to_string(n) + " of type " + std::to_string(type);
    }
    lines.fail_at(elements_line,
                  std::string("$Elements: no ") +
                      (Dim == 2 ? "triangles (3-node, type 2)" : "tetrahedra (4-node, type 4)") +
                      (other.empty() ? "" : " among its elements (" + other + ")") +
                      (Dim == 2 ? "; mesh the surface in Gmsh (Mesh > 2D) and save again"
                                : "; mesh the volume in Gmsh (Mesh > 3D) and save again"));
  }

  // the nodes the elements use, in the plane z = constant for a 2D read
  const int first_used = raw.elements[0][0];
  double scale = 1.0;
  for (const auto& el : raw.elements) {
    for (int a = 0; a <= Dim; ++a) scale = std::max(scale, nodes.x[el[a]].cwiseAbs().maxCoeff());
  }
  for (const auto& el : raw.elements) {
    for (int a = 0; a <= Dim; ++a) {
      const int n = el[a];
      if (Dim == 2 && std::abs(nodes.x[n].z() - nodes.x[first_used].z()) > 1e-12 * scale) {
        std::ostringstream what;
        what.precision(17);
        what << "$Nodes: node " << nodes.tags[n] << " has z = " << nodes.x[n].z() << ", node "
             << nodes.tags[first_used] << " has z = " << nodes.x[first_used].z()
             << "; a 2D mesh must lie in a plane z = constant (read it as 3D, or mesh a plane "
                "surface)";
        lines.fail_at(nodes.lines[n], what.str(), -1, n);
      }
    }
  }
  for (size_t n = 0; n < nodes.x.size(); ++n) {
    raw.nodes.push_back(nodes.x[n].head<Dim>());
    raw.node_labels.push_back(nodes.tags[n]);
  }
  return detail::finish_mesh<Dim>(std::move(raw), name);
}

template <int Dim>
SimplexMesh<Dim> read_gmsh(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw MeshFileError(path + ": cannot be opened for reading (does it exist?)", path, 0);
  }
  return read_gmsh<Dim>(in, path);
}

template SimplexMesh<2> read_gmsh<2>(const std::string&);
template SimplexMesh<3> read_gmsh<3>(const std::string&);
template SimplexMesh<2> read_gmsh<2>(std::istream&, const std::string&);
template SimplexMesh<3> read_gmsh<3>(std::istream&, const std::string&);

}  // namespace gencoord::deformable
