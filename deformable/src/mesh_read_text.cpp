// SPDX-License-Identifier: BSD-3-Clause
// Numbered lines and their words, the checks and clean-up shared by the mesh readers, and
// read_mesh's choice of reader (an .obj surface is filled with tetrahedra by TetGen).
#include "mesh_read_text.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/tetrahedralize.hpp"
#include "gencoord/deformable/validate.hpp"
#include "simplex_shape.hpp"

namespace gencoord::deformable::detail {

TextLines::TextLines(std::istream& in, std::string name, char comment)
    : in_(in), name_(std::move(name)), comment_(comment) {}

bool TextLines::next() {
  while (std::getline(in_, text_)) {
    ++line_;
    if (comment_ != '\0') {
      const size_t at = text_.find(comment_);
      if (at != std::string::npos) text_.erase(at);
    }
    words_.clear();
    std::istringstream split(text_);
    for (std::string w; split >> w;) words_.push_back(w);
    if (!words_.empty()) return true;
  }
  words_.clear();
  return false;
}

void TextLines::expect_next(const std::string& where) {
  if (!next()) fail("the file ends " + where + "; it is truncated (write it again)");
}

void TextLines::fail(const std::string& what, int element, int node) const {
  fail_at(line_, what, element, node);
}

void TextLines::fail_at(int line, const std::string& what, int element, int node) const {
  throw MeshFileError(name_ + ":" + std::to_string(line) + ": " + what, name_, line, element, node);
}

void TextLines::expect_words(size_t count, const std::string& what,
                             const std::string& names) const {
  if (words_.size() != count) {
    fail(what + ": expected " + std::to_string(count) + (count == 1 ? " number" : " numbers") +
         " (" + names + "), got " + std::to_string(words_.size()));
  }
}

long long TextLines::integer(size_t k, const std::string& what) const {
  const std::string& w = words_.at(k);
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(w.c_str(), &end, 10);
  if (end == w.c_str() || *end != '\0' || errno == ERANGE) {
    fail(what + ": expected an integer, got '" + w + "'");
  }
  return value;
}

long long TextLines::count(size_t k, const std::string& what) const {
  const long long n = integer(k, what);
  if (n < 0) fail(what + ": " + std::to_string(n) + " is negative");
  return n;
}

double TextLines::real(size_t k, const std::string& what) const {
  const std::string& w = words_.at(k);
  char* end = nullptr;
  const double value = std::strtod(w.c_str(), &end);
  if (end == w.c_str() || *end != '\0') fail(what + ": expected a number, got '" + w + "'");
  if (!std::isfinite(value)) fail(what + ": " + w + " is not a finite number");
  return value;
}

template <int Dim>
SimplexMesh<Dim> finish_mesh(RawMesh<Dim> raw, const std::string& name) {
  auto fail_at = [&name](int line, const std::string& what, int element, int node) {
    throw MeshFileError(name + ":" + std::to_string(line) + ": " + what, name, line, element, node);
  };
  for (size_t e = 0; e < raw.elements.size(); ++e) {
    auto& el = raw.elements[e];
    const int line = raw.element_lines[e];
    const std::string label = "element " + std::to_string(raw.element_labels[e]);
    for (int a = 0; a <= Dim; ++a) {
      for (int b = 0; b < a; ++b) {
        if (el[a] == el[b]) {
          fail_at(line,
                  label + " uses node " + std::to_string(raw.node_labels[el[a]]) +
                      " twice; every corner must be a different node (fix the mesh)",
                  static_cast<int>(e), el[a]);
        }
      }
    }
    Eigen::Matrix<double, Dim, Dim> edges;
    for (int c = 0; c < Dim; ++c) edges.col(c) = raw.nodes[el[c + 1]] - raw.nodes[el[0]];
    const std::string problem = detail::shape_problem(detail::simplex_shape<Dim>(edges), "nodes",
                                                      " (remove it or mesh again)");
    if (!problem.empty()) fail_at(line, label + " " + problem, static_cast<int>(e), -1);
    const double signed_measure = edges.determinant();
    if (signed_measure < 0.0) std::swap(el[Dim - 1], el[Dim]);
  }

  // keep the nodes some element uses, in file order
  std::vector<int> index(raw.nodes.size(), -1);
  for (const auto& el : raw.elements) {
    for (int a = 0; a <= Dim; ++a) index[el[a]] = 0;
  }
  int count = 0;
  for (int& i : index) {
    if (i == 0) i = count++;
  }
  SimplexMesh<Dim> mesh;
  mesh.nodes.resize(Dim, count);
  for (size_t n = 0; n < raw.nodes.size(); ++n) {
    if (index[n] >= 0) mesh.nodes.col(index[n]) = raw.nodes[n];
  }
  mesh.elements.reserve(raw.elements.size());
  for (const auto& el : raw.elements) {
    std::array<int, Dim + 1> renumbered;
    for (int a = 0; a <= Dim; ++a) renumbered[a] = index[el[a]];
    mesh.elements.push_back(renumbered);
  }
  return mesh;
}

template SimplexMesh<2> finish_mesh<2>(RawMesh<2>, const std::string&);
template SimplexMesh<3> finish_mesh<3>(RawMesh<3>, const std::string&);

}  // namespace gencoord::deformable::detail

namespace gencoord::deformable {

template <int Dim>
SimplexMesh<Dim> read_mesh(const std::string& path) {
  auto ends_with = [&path](const std::string& tail) {
    return path.size() >= tail.size() &&
           path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (ends_with(".msh")) return read_gmsh<Dim>(path);
  if (ends_with(".node") || ends_with(".ele")) {
    return read_tetgen<Dim>(path.substr(0, path.rfind('.')));
  }
  if (ends_with(".obj")) {
    if constexpr (Dim == 2) {
      throw MeshFileError(path +
                              ": an .obj file holds a surface in 3D, which a 2D read cannot "
                              "take; read it with read_mesh<3> to fill it with tetrahedra, or "
                              "with read_obj as a sheet",
                          path, 0);
    } else {
      ObjSource source;
      const TriangleSurface surface = read_obj(path, &source);
      return tetrahedralize(surface, path, TetgenOptions{}, &source);
    }
  }
  throw MeshFileError(path +
                          ": unknown mesh file extension; give a Gmsh .msh file, a TetGen / "
                          "Triangle .node or .ele file, or (3D) a Wavefront .obj surface",
                      path, 0);
}

template SimplexMesh<2> read_mesh<2>(const std::string&);
template SimplexMesh<3> read_mesh<3>(const std::string&);

}  // namespace gencoord::deformable
