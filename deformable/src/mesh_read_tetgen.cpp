// SPDX-License-Identifier: BSD-3-Clause
// TetGen / Triangle reader: a .node file of points and a .ele file of tetrahedra or triangles.
#include <fstream>

#include "gencoord/deformable/mesh_io.hpp"
#include "mesh_read_text.hpp"

namespace gencoord::deformable {

namespace {

using detail::RawMesh;
using detail::TextLines;

// Attributes per line: a count no line holds would overflow the words expected of a line.
long long attributes_at(TextLines& lines, size_t k) {
  constexpr long long kMost = 1 << 20;
  const long long n = lines.count(k, "attributes");
  if (n > kMost)
    lines.fail("attributes: " + std::to_string(n) + ", more than the " + std::to_string(kMost) +
               " a line may have");
  return n;
}

// After the last entry of a file only comments and blank lines may follow.
void expect_no_more(TextLines& lines, long long count, int count_line) {
  if (lines.next()) {
    lines.fail("more entries than the " + std::to_string(count) + " announced on line " +
               std::to_string(count_line) + "; the count and the entries disagree");
  }
}

// Reads the .node file; returns the number of the first point (0 or 1), which the .ele
// file's indices start from too.
template <int Dim>
long long read_node_file(TextLines& lines, RawMesh<Dim>& raw) {
  const std::string names = "points, dimension, attributes, boundary markers";
  if (!lines.next()) lines.fail("the file is empty; expected the line " + names);
  if (lines.words().size() < 2 || lines.words().size() > 4) {
    lines.fail("expected 2 to 4 numbers (" + names + "), got " +
               std::to_string(lines.words().size()));
  }
  const int count_line = lines.line();
  const long long count = lines.count(0, "number of points");
  const long long dim = lines.integer(1, "dimension");
  const long long attributes = lines.words().size() > 2 ? attributes_at(lines, 2) : 0;
  const long long markers = lines.words().size() > 3 ? lines.count(3, "boundary markers") : 0;
  if (dim != Dim) {
    lines.fail("the points are " + std::to_string(dim) + "-dimensional, but a " +
               std::to_string(Dim) + "D mesh was asked for; read it as " + std::to_string(dim) +
               "D");
  }
  if (markers > 1) lines.fail("boundary markers: " + std::to_string(markers) + ", expected 0 or 1");
  if (count == 0) lines.fail("no points; the mesh must have nodes");
  const size_t words = static_cast<size_t>(1 + Dim + attributes + markers);
  const std::string what = "point";
  const std::string point_names =
      std::string(Dim == 2 ? "number x y" : "number x y z") +
      (attributes > 0 ? ", " + std::to_string(attributes) + " attributes" : "") +
      (markers > 0 ? ", boundary marker" : "");
  long long base = 0;
  for (long long k = 0; k < count; ++k) {
    lines.expect_next("after " + std::to_string(k) + " of the " + std::to_string(count) +
                      " points announced on line " + std::to_string(count_line));
    lines.expect_words(words, what, point_names);
    const long long number = lines.integer(0, "point number");
    if (k == 0) {
      if (number != 0 && number != 1) {
        lines.fail("the first point is numbered " + std::to_string(number) + "; expected 0 or 1");
      }
      base = number;
    } else if (number != base + k) {
      lines.fail("point number " + std::to_string(number) + ", expected " +
                 std::to_string(base + k) + " (points are numbered in order from the first)");
    }
    Eigen::Matrix<double, Dim, 1> x;
    for (int c = 0; c < Dim; ++c) x(c) = lines.real(1 + c, std::string("point ") + "xyz"[c]);
    raw.nodes.push_back(x);
    raw.node_labels.push_back(number);
  }
  expect_no_more(lines, count, count_line);
  return base;
}

template <int Dim>
void read_ele_file(TextLines& lines, long long base, RawMesh<Dim>& raw) {
  const char* kind = Dim == 2 ? "triangles" : "tetrahedra";
  const std::string names = std::string(kind) + ", nodes per element, attributes";
  if (!lines.next()) lines.fail("the file is empty; expected the line " + names);
  if (lines.words().size() < 2 || lines.words().size() > 3) {
    lines.fail("expected 2 or 3 numbers (" + names + "), got " +
               std::to_string(lines.words().size()));
  }
  const int count_line = lines.line();
  const long long count = lines.count(0, std::string("number of ") + kind);
  const long long corners = lines.integer(1, "nodes per element");
  const long long attributes = lines.words().size() > 2 ? attributes_at(lines, 2) : 0;
  const long long second_order = Dim == 2 ? 6 : 10;
  if (corners != Dim + 1 && corners != second_order) {
    lines.fail("nodes per element: " + std::to_string(corners) + "; " + kind + " have " +
               std::to_string(Dim + 1) + " (or " + std::to_string(second_order) +
               ", second order)");
  }
  if (count == 0) lines.fail(std::string("no ") + kind + "; the mesh must have elements");
  const size_t words = static_cast<size_t>(1 + corners + attributes);
  const std::string element_names =
      "number, " + std::to_string(corners) + " node indices" +
      (attributes > 0 ? ", " + std::to_string(attributes) + " attributes" : "");
  const long long points = static_cast<long long>(raw.nodes.size());
  for (long long k = 0; k < count; ++k) {
    lines.expect_next("after " + std::to_string(k) + " of the " + std::to_string(count) + " " +
                      kind + " announced on line " + std::to_string(count_line));
    lines.expect_words(words, "element", element_names);
    const long long number = lines.integer(0, "element number");
    std::array<int, Dim + 1> el;
    for (int a = 0; a <= Dim; ++a) {  // the corners come first, also in second order
      const long long index = lines.integer(1 + a, "node index");
      if (index < base || index >= base + points) {
        lines.fail("element " + std::to_string(number) + " refers to node " +
                       std::to_string(index) + ", out of range: the .node file has points " +
                       std::to_string(base) + " to " + std::to_string(base + points - 1),
                   static_cast<int>(raw.elements.size()), -1);
      }
      el[a] = static_cast<int>(index - base);
    }
    raw.elements.push_back(el);
    raw.element_lines.push_back(lines.line());
    raw.element_labels.push_back(number);
  }
  expect_no_more(lines, count, count_line);
}

std::ifstream open(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MeshFileError(path + ": cannot be opened for reading (does it exist?)", path, 0);
  return in;
}

}  // namespace

template <int Dim>
SimplexMesh<Dim> read_tetgen(std::istream& node, const std::string& node_name, std::istream& ele,
                             const std::string& ele_name) {
  RawMesh<Dim> raw;
  TextLines node_lines(node, node_name, '#');
  const long long base = read_node_file(node_lines, raw);
  TextLines ele_lines(ele, ele_name, '#');
  read_ele_file(ele_lines, base, raw);
  return detail::finish_mesh<Dim>(std::move(raw), ele_name);
}

template <int Dim>
SimplexMesh<Dim> read_tetgen(const std::string& base) {
  std::ifstream node = open(base + ".node");
  std::ifstream ele = open(base + ".ele");
  return read_tetgen<Dim>(node, base + ".node", ele, base + ".ele");
}

template SimplexMesh<2> read_tetgen<2>(const std::string&);
template SimplexMesh<3> read_tetgen<3>(const std::string&);
template SimplexMesh<2> read_tetgen<2>(std::istream&, const std::string&, std::istream&,
                                       const std::string&);
template SimplexMesh<3> read_tetgen<3>(std::istream&, const std::string&, std::istream&,
                                       const std::string&);

}  // namespace gencoord::deformable
