// SPDX-License-Identifier: BSD-3-Clause
// Tetrahedra filling a closed surface, made by the TetGen program. TetGen is AGPL: it is run
// as a program, never linked (libtet), so none of its code enters our binaries.
#include "gencoord/deformable/tetrahedralize.hpp"

#include <stdlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <system_error>
#include <vector>

#include "gencoord/deformable/closed_surface.hpp"
#include "gencoord/deformable/errors.hpp"
#include "mesh_read_text.hpp"
#include "run_program.hpp"

namespace gencoord::deformable {

namespace {

namespace fs = std::filesystem;
using detail::ProgramRun;

// How messages name the surface's lines and nodes: the file's, when it was read from one.
class Names {
 public:
  Names(const std::string& name, const TriangleSurface& surface, const ObjSource* source)
      : name_(name) {
    if (source != nullptr && source->face_lines.size() == surface.triangles.size() &&
        static_cast<long long>(source->vertex_numbers.size()) == surface.nodes.cols()) {
      source_ = source;
    }
  }
  int line(int triangle) const { return source_ != nullptr ? source_->face_lines[triangle] : 0; }
  std::string node(int n) const {
    return source_ != nullptr ? "vertex " + std::to_string(source_->vertex_numbers[n])
                              : "node " + std::to_string(n);
  }
  // "this face" when the message is at the triangle's line, else its index
  std::string face(int triangle) const {
    return source_ != nullptr ? "this face" : "triangle " + std::to_string(triangle);
  }
  std::string other_face(int triangle) const {
    return source_ != nullptr ? "the face on line " + std::to_string(line(triangle))
                              : "triangle " + std::to_string(triangle);
  }
  [[noreturn]] void fail(int line, const std::string& what, int element = -1, int node = -1) const {
    const std::string where = line > 0 ? name_ + ":" + std::to_string(line) + ": " : name_ + ": ";
    throw MeshFileError(where + what, name_, line, element, node);
  }

 private:
  std::string name_;
  const ObjSource* source_ = nullptr;
};

void check_options(const TetgenOptions& options) {
  const double q = options.radius_edge_ratio, a = options.max_volume;
  if (!(q == 0.0 || (std::isfinite(q) && q >= 1.0))) {
    throw MeshError("tetrahedralize: radius_edge_ratio " + std::to_string(q) +
                        " is not usable; give 0 (no quality bound) or a number of at least 1 "
                        "(TetGen may not terminate below 1)",
                    -1, -1);
  }
  if (!(std::isfinite(a) && a >= 0.0)) {
    throw MeshError("tetrahedralize: max_volume " + std::to_string(a) +
                        " is not usable; give 0 (no bound) or a positive volume",
                    -1, -1);
  }
}

// The sentence that says what to do with a surface that does not bound a solid.
const char* const kWhatToDo =
    "; to fill it with tetrahedra, make it the closed boundary of a solid (each edge in "
    "exactly two faces, which run along it in opposite directions), or read it as a sheet "
    "with read_obj";

// An open edge often is a seam: the file repeats a vertex at the same position instead of
// sharing it. Says so when another node is where `end` is.
std::string seam_hint(const TriangleSurface& surface, const Names& names, int end) {
  for (int n = 0; n < surface.nodes.cols(); ++n) {
    if (n != end && surface.nodes.col(n) == surface.nodes.col(end)) {
      return " (" + names.node(n) + " is at the same position as " + names.node(end) +
             ": merge the vertices that repeat a position)";
    }
  }
  return "";
}

void refuse_defect(const SurfaceDefect& d, const TriangleSurface& surface, const Names& names) {
  const int line = names.line(d.triangle);
  std::string what;
  switch (d.kind) {
    case SurfaceDefect::Kind::kOpenEdge: {
      what = "the surface is not closed: the edge from " + names.node(d.a) + " to " +
             names.node(d.b) + " is in " + names.face(d.triangle) +
             " only, so the surface has a hole there";
      const std::string hint = seam_hint(surface, names, d.a);
      what += hint.empty() ? seam_hint(surface, names, d.b) : hint;
      break;
    }
    case SurfaceDefect::Kind::kMisorientedEdge:
      what = "the surface is not consistently oriented: " + names.face(d.triangle) + " and " +
             names.other_face(d.other) + " both run from " + names.node(d.a) + " to " +
             names.node(d.b) +
             ", so one of them is flipped (reverse its vertex order, so that every face's "
             "normal points out of the solid)";
      break;
    case SurfaceDefect::Kind::kNonManifoldEdge:
      what = "the surface is not a manifold: the edge between " + names.node(d.a) + " and " +
             names.node(d.b) + " is in " + std::to_string(d.count) + " faces (" +
             names.face(d.triangle) + " and " + names.other_face(d.other) + " among them)";
      break;
    case SurfaceDefect::Kind::kNonManifoldVertex:
      what = "the surface is not a manifold: the faces around " + names.node(d.a) + " (" +
             names.face(d.triangle) + " among them) form " + std::to_string(d.count) +
             " fans that meet only at that vertex (separate the parts that touch there)";
      break;
  }
  names.fail(line, what + kWhatToDo, d.triangle, d.a);
}

void check_surface(const TriangleSurface& surface, const Names& names) {
  if (surface.triangles.empty()) names.fail(0, "the surface has no triangles; nothing to fill");
  std::vector<char> used(surface.nodes.cols(), 0);
  std::optional<SurfaceDefect> defect;
  try {
    defect = find_surface_defect(surface);
  } catch (const MeshError& e) {  // an index out of range or a repeated node
    names.fail(names.line(e.element()), e.what(), e.element(), e.node());
  }
  for (const auto& tri : surface.triangles) {
    for (const int n : tri) used[n] = 1;
  }
  for (int n = 0; n < surface.nodes.cols(); ++n) {
    if (!surface.nodes.col(n).allFinite()) {
      names.fail(0, names.node(n) + " is not finite; give every node a finite position", -1, n);
    }
    if (!used[n]) {
      names.fail(0, names.node(n) + " is in no triangle; remove it (TetGen would drop it)", -1, n);
    }
  }
  if (defect) refuse_defect(*defect, surface, names);
}

// A fresh directory for TetGen's files, removed with everything in it when this goes.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "gencoord_tetgen_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::system_error(errno, std::generic_category(),
                              "cannot create a temporary directory " + pattern);
    }
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// TetGen's .smesh: points numbered from 0, each triangle a facet, no holes, no regions.
void write_smesh(const TriangleSurface& surface, const fs::path& path) {
  std::ofstream out(path);
  out.precision(17);  // round trip: TetGen reads the same doubles
  out << surface.nodes.cols() << " 3 0 0\n";
  for (int n = 0; n < surface.nodes.cols(); ++n) {
    out << n << " " << surface.nodes(0, n) << " " << surface.nodes(1, n) << " "
        << surface.nodes(2, n) << "\n";
  }
  out << surface.triangles.size() << " 0\n";
  for (const auto& tri : surface.triangles) {
    out << "3 " << tri[0] << " " << tri[1] << " " << tri[2] << "\n";
  }
  out << "0\n0\n";
  if (!out.flush()) {
    throw std::system_error(errno, std::generic_category(), "cannot write " + path.string());
  }
}

std::string number(double x) {
  std::ostringstream text;
  text.precision(12);
  text << x;
  return text.str();
}

// What TetGen printed, without blank lines, the last few lines at most.
std::string printed(const std::string& output) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  if (lines.empty()) return "nothing";
  const size_t keep = 12;
  std::string text = lines.size() > keep ? "... " : "";
  for (size_t k = lines.size() > keep ? lines.size() - keep : 0; k < lines.size(); ++k) {
    text += "'" + lines[k] + "'" + (k + 1 < lines.size() ? " " : "");
  }
  return text;
}

// TetGen aborts on a surface that intersects itself without saying so; its -d switch lists
// the triangles that cross others in a .face file. Refuses naming their lines, if any.
void refuse_self_intersection(const std::string& tetgen, const TempDir& dir,
                              const TriangleSurface& surface, const Names& names) {
  const fs::path input = dir.path() / "check.smesh";
  write_smesh(surface, input);
  const ProgramRun run =
      detail::run_program(tetgen, {"-pdQ", input.string()}, (dir.path() / "check.log").string());
  const fs::path faces = dir.path() / "check.1.face";
  if (!run.succeeded() || !fs::exists(faces)) return;
  std::map<std::array<int, 3>, int> triangle_of;
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    std::array<int, 3> key = surface.triangles[t];
    std::sort(key.begin(), key.end());
    triangle_of.emplace(key, static_cast<int>(t));
  }
  std::ifstream in(faces);
  detail::TextLines lines(in, faces.string(), '#');
  std::vector<int> crossing;
  if (lines.next()) {
    while (lines.next()) {
      if (lines.words().size() < 4) continue;
      std::array<int, 3> key;
      for (int k = 0; k < 3; ++k) key[k] = static_cast<int>(lines.integer(1 + k, "corner"));
      std::sort(key.begin(), key.end());
      const auto found = triangle_of.find(key);
      if (found != triangle_of.end()) crossing.push_back(found->second);
    }
  }
  if (crossing.empty()) return;
  std::vector<int> labels;  // the faces' lines, else the triangles
  for (const int t : crossing) labels.push_back(names.line(t) > 0 ? names.line(t) : t);
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  std::string list = names.line(crossing[0]) > 0 ? "in the faces on lines " : "triangles ";
  const size_t shown = std::min<size_t>(labels.size(), 8);
  for (size_t k = 0; k < shown; ++k) list += (k == 0 ? "" : ", ") + std::to_string(labels[k]);
  if (labels.size() > shown) list += " and " + std::to_string(labels.size() - shown) + " more";
  names.fail(names.line(crossing[0]),  // the triangles, and so their lines, are in file order
             "the surface intersects itself: TetGen cannot fill it; " +
                 std::to_string(crossing.size()) + " triangles cross others (" + list +
                 "); move their vertices so that faces meet only along their shared edges and "
                 "corners",
             crossing[0]);
}

// Runs TetGen on the surface in a temporary directory and reads its tetrahedra.
SimplexMesh<3> run_tetgen(const std::string& tetgen, const TriangleSurface& surface,
                          const TetgenOptions& options, const Names& names) {
  const TempDir dir;
  const fs::path input = dir.path() / "surface.smesh";
  if (input.string().size() > 1000) {  // TetGen keeps file names in 1024 characters
    names.fail(0, "the temporary directory's path " + dir.path().string() +
                      " is too long for TetGen; set TMPDIR to a shorter one");
  }
  write_smesh(surface, input);
  std::vector<std::string> args = {"-p"};
  if (options.radius_edge_ratio > 0.0) args.push_back("-q" + number(options.radius_edge_ratio));
  if (options.max_volume > 0.0) args.push_back("-a" + number(options.max_volume));
  args.push_back("-Q");
  args.push_back(input.string());
  const ProgramRun run = detail::run_program(tetgen, args, (dir.path() / "tetgen.log").string());
  const fs::path base = dir.path() / "surface.1";
  if (!run.succeeded() || !fs::exists(base.string() + ".ele")) {
    refuse_self_intersection(tetgen, dir, surface, names);
    std::string command = "tetgen";  // its input by the file's name, the directory is gone
    for (size_t k = 0; k + 1 < args.size(); ++k) command += " " + args[k];
    command += " surface.smesh";
    names.fail(0, "TetGen failed to fill the surface with tetrahedra: '" + command + "' " +
                      run.status() + " after printing " + printed(run.output) +
                      "; check that the surface bounds a solid");
  }

  try {
    return read_tetgen<3>(base.string());
  } catch (const MeshFileError& e) {
    names.fail(0, std::string("the tetrahedra TetGen made cannot be read: ") + e.what());
  }
}

}  // namespace

SimplexMesh<3> tetrahedralize(const TriangleSurface& surface, const std::string& name,
                              const TetgenOptions& options, const ObjSource* source) {
  check_options(options);
  const Names names(name, surface, source);
  check_surface(surface, names);
  const std::string tetgen = detail::find_program("tetgen");
  if (tetgen.empty()) {
    names.fail(0,
               "cannot fill the surface with tetrahedra: the program 'tetgen' (TetGen 1.5) is "
               "not on PATH; install it (Debian, Ubuntu: apt-get install tetgen)");
  }

  SimplexMesh<3> mesh;
  try {
    mesh = run_tetgen(tetgen, surface, options, names);
  } catch (const std::system_error& e) {  // also std::filesystem::filesystem_error
    names.fail(0, std::string("cannot fill the surface with tetrahedra: ") + e.what() +
                      "; check that TMPDIR (else /tmp) is a writable directory and that tetgen "
                      "can be run");
  }
  // A surface that intersects itself, or one part inside another, can give tetrahedra that
  // are not the solid the surface encloses: refused rather than simulated.
  double filled = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    filled += element_measure(mesh, e);
  }
  const double enclosed = std::abs(enclosed_volume(surface));
  if (!(std::abs(filled - enclosed) <= 1e-8 * enclosed)) {
    std::ostringstream what;
    what.precision(10);
    what << "TetGen's tetrahedra fill " << filled << " m^3, but the surface encloses " << enclosed
         << " m^3; check that it does not intersect itself and that no part of it lies inside "
            "another (a hollow solid is not filled as such: TetGen fills its cavities)";
    names.fail(0, what.str());
  }
  // TetGen writes its input points first, in order, to 17 digits: the same doubles
  const long long n = surface.nodes.cols();
  if (mesh.nodes.cols() < n || mesh.nodes.leftCols(n) != surface.nodes) {
    int moved = 0;
    while (moved < n && moved < mesh.nodes.cols() &&
           mesh.nodes.col(moved) == surface.nodes.col(moved)) {
      ++moved;
    }
    names.fail(0, "TetGen moved or dropped " + names.node(moved) +
                      " (it merges points that nearly coincide); move the surface's nodes "
                      "apart");
  }
  return mesh;
}

}  // namespace gencoord::deformable
