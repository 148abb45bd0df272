// SPDX-License-Identifier: BSD-3-Clause
// Wavefront .obj reader: the v and f lines of a polygon surface, as triangles in 3D.
#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/validate.hpp"
#include "mesh_read_text.hpp"
#include "simplex_shape.hpp"

namespace gencoord::deformable {

namespace {

using detail::TextLines;

// Statements that do not change the surface's shape: texture and normal vertices, groups,
// smoothing, materials, lines, points and display settings.
const std::set<std::string> kSkipped = {
    "vt", "vn",    "vp",       "g",        "o",   "s",      "usemtl", "mtllib",     "l",        "p",
    "mg", "bevel", "c_interp", "d_interp", "lod", "usemap", "maplib", "shadow_obj", "trace_obj"};
// Free-form geometry: curves and surfaces given by control points, not polygons.
const std::set<std::string> kFreeForm = {"cstype", "deg",  "bmat", "step", "curv", "curv2", "surf",
                                         "parm",   "trim", "hole", "scrv", "sp",   "end",   "con"};

// A face's vertex: its index as written (from 1, or back from -1), and the 0-based v line it
// names (a positive index may name a line further down: checked when the file is read).
struct FaceVertex {
  long long written;
  long long resolved;
};

struct Face {
  int line;
  std::vector<FaceVertex> vertices;
};

bool parse_integer(const std::string& text, long long& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return *end == '\0' && errno != ERANGE;
}

// The vertex index of "i", "i/t", "i//n" or "i/t/n"; the texture and normal indices are
// checked to be integers and not used.
long long vertex_index(const TextLines& lines, size_t k) {
  const std::string& word = lines.words()[k];
  std::vector<std::string> parts;
  for (size_t at = 0;;) {
    const size_t slash = word.find('/', at);
    parts.push_back(word.substr(at, slash - at));
    if (slash == std::string::npos) break;
    at = slash + 1;
  }
  long long index = 0, other = 0;
  const bool ok = parts.size() <= 3 && parse_integer(parts[0], index) &&
                  (parts.size() < 2 || parts[1].empty() || parse_integer(parts[1], other)) &&
                  (parts.size() < 3 || parse_integer(parts[2], other));
  if (!ok) {
    lines.fail("f: vertex " + std::to_string(k) + " is '" + word +
               "', not a vertex reference; write i, i/t, i//n or i/t/n with integers (i counts "
               "the v lines from 1)");
  }
  return index;
}

void read_vertex(const TextLines& lines, std::vector<Eigen::Vector3d>& vertices) {
  const size_t numbers = lines.words().size() - 1;
  if (numbers != 3 && numbers != 4 && numbers != 6) {
    lines.fail("v: expected 3 numbers (x y z), or 4 (x y z w) or 6 (x y z r g b), got " +
               std::to_string(numbers));
  }
  Eigen::Vector3d x;
  for (int c = 0; c < 3; ++c) x(c) = lines.real(1 + c, std::string("v: ") + "xyz"[c]);
  for (size_t k = 4; k <= numbers; ++k) lines.real(k, numbers == 4 ? "v: w" : "v: colour");
  vertices.push_back(x);
}

Face read_face(const TextLines& lines, long long defined) {
  const size_t count = lines.words().size() - 1;
  if (count < 3) {
    lines.fail("f: a face needs at least 3 vertices, got " + std::to_string(count) +
               " (remove the line)");
  }
  Face face{lines.line(), {}};
  for (size_t k = 1; k <= count; ++k) {
    const long long index = vertex_index(lines, k);
    if (index == 0) {
      lines.fail(
          "f: vertex index 0 names no v line; indices count the v lines from 1 (or back "
          "from -1, the last v line above)");
    }
    if (index < 0 && index < -defined) {  // -index overflows for the smallest long long
      lines.fail("f: vertex index " + std::to_string(index) +
                 " counts back past the first v line: only " + std::to_string(defined) +
                 " v lines are above this line");
    }
    face.vertices.push_back({index, index < 0 ? defined + index : index - 1});
  }
  return face;
}

// The face's fan of triangles, checked: vertices that exist, no vertex twice, an area.
void add_triangles(const TextLines& lines, const Face& face,
                   const std::vector<Eigen::Vector3d>& vertices,
                   std::vector<std::array<long long, 3>>& triangles, std::vector<int>& face_lines) {
  const long long count = static_cast<long long>(vertices.size());
  for (const FaceVertex& v : face.vertices) {
    if (v.resolved >= count) {
      lines.fail_at(face.line, "f: vertex index " + std::to_string(v.written) +
                                   " names no v line: the file has " + std::to_string(count) +
                                   (count == 1 ? " vertex" : " vertices"));
    }
  }
  const size_t n = face.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (face.vertices[i].resolved == face.vertices[j].resolved) {
        lines.fail_at(face.line, "f: the face uses vertex " +
                                     std::to_string(face.vertices[i].resolved + 1) +
                                     " twice (as its vertex " + std::to_string(j + 1) + " and " +
                                     std::to_string(i + 1) +
                                     "); every corner must be a different vertex (remove the "
                                     "face or fix it)");
      }
    }
  }
  for (size_t j = 1; j + 1 < n; ++j) {
    const std::array<long long, 3> tri = {face.vertices[0].resolved, face.vertices[j].resolved,
                                          face.vertices[j + 1].resolved};
    const Eigen::Vector3d a = vertices[tri[0]], b = vertices[tri[1]], c = vertices[tri[2]];
    const std::string problem = detail::shape_problem(
        detail::triangle_shape(b - a, c - a), "vertices", " (remove the face or fix its vertices)");
    if (!problem.empty()) {
      std::ostringstream what;
      what << "f: the triangle of vertices " << tri[0] + 1 << " " << tri[1] + 1 << " "
           << tri[2] + 1;
      if (n > 3) what << " (cut from this face of " << n << " vertices)";
      what << " " << problem;
      lines.fail_at(face.line, what.str());
    }
    triangles.push_back(tri);
    face_lines.push_back(face.line);
  }
}

}  // namespace

TriangleSurface read_obj(std::istream& in, const std::string& name, ObjSource* source) {
  TextLines lines(in, name, '#');
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  while (lines.next()) {
    const std::string& word = lines.words()[0];
    const std::string& last = lines.words().back();
    if (last.back() == '\\') {
      lines.fail(
          "the line is continued with '\\', which this reader does not read; join it "
          "with the next line");
    }
    if (word == "v") {
      read_vertex(lines, vertices);
    } else if (word == "f") {
      faces.push_back(read_face(lines, static_cast<long long>(vertices.size())));
    } else if (kFreeForm.count(word) != 0) {
      lines.fail("'" + word +
                 "': free-form curves and surfaces are not read; export the surface as "
                 "polygons (triangles or quads)");
    } else if (kSkipped.count(word) == 0) {
      lines.fail("unknown statement '" + word +
                 "'; an .obj surface is read from its v and f lines (fix or remove the line)");
    }
  }
  if (faces.empty()) {
    lines.fail("the file has no faces (f lines) after " + std::to_string(vertices.size()) +
               " vertices; export the surface with its faces");
  }

  std::vector<std::array<long long, 3>> triangles;
  std::vector<int> face_lines;
  for (const Face& face : faces) add_triangles(lines, face, vertices, triangles, face_lines);

  // keep the vertices some face uses, in file order
  std::vector<int> index(vertices.size(), -1);
  for (const auto& tri : triangles) {
    for (const long long v : tri) index[v] = 0;
  }
  int count = 0;
  for (int& i : index) {
    if (i == 0) i = count++;
  }
  TriangleSurface surface;
  surface.nodes.resize(3, count);
  std::vector<long long> vertex_numbers(count);
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (index[v] < 0) continue;
    surface.nodes.col(index[v]) = vertices[v];
    vertex_numbers[index[v]] = static_cast<long long>(v) + 1;
  }
  surface.triangles.reserve(triangles.size());
  for (const auto& tri : triangles) {
    surface.triangles.push_back({index[tri[0]], index[tri[1]], index[tri[2]]});
  }
  if (source != nullptr) {
    source->face_lines = std::move(face_lines);
    source->vertex_numbers = std::move(vertex_numbers);
  }
  return surface;
}

TriangleSurface read_obj(const std::string& path, ObjSource* source) {
  std::ifstream in(path);
  if (!in) throw MeshFileError(path + ": cannot be opened for reading (does it exist?)", path, 0);
  return read_obj(in, path, source);
}

}  // namespace gencoord::deformable
