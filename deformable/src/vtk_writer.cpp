// SPDX-License-Identifier: BSD-3-Clause
// VTK XML output for ParaView: .vtu frames and the .pvd collection.
#include "gencoord/deformable/vtk_writer.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include "gencoord/io/output_file.hpp"

namespace gencoord::deformable {

namespace {

// Text with numbers in their shortest round-trip form (std::to_chars ignores the locale).
class Text {
 public:
  Text& operator<<(const std::string& s) {
    out_ += s;
    return *this;
  }
  Text& operator<<(const char* s) {
    out_ += s;
    return *this;
  }
  Text& operator<<(double x) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
    out_.append(buffer, end);
    return *this;
  }
  Text& operator<<(long long n) {
    out_ += std::to_string(n);
    return *this;
  }
  Text& operator<<(int n) { return *this << static_cast<long long>(n); }
  Text& operator<<(size_t n) { return *this << static_cast<long long>(n); }
  const std::string& str() const { return out_; }

 private:
  std::string out_;
};

// `text` with the characters that XML attributes cannot hold as they are escaped.
std::string xml_attribute(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Writes `content` to `path` + ".tmp" and renames it to `path` once it is complete.
void write_atomically(const std::string& path, const std::string& content) {
  const std::string temporary = path + ".tmp";
  try {
    OutputFile file(temporary);
    file.stream() << content;
    file.close();
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw OutputError(path, "renaming '" + temporary + "' to");
  }
}

// Signed area or volume (length in 1D) of the simplex with corners `el` among the columns of x.
template <int Dim, class Points, size_t N>
double signed_measure(const Points& x, const std::array<int, N>& el) {
  Eigen::Matrix<double, Dim, Dim> edges;
  for (int c = 0; c < Dim; ++c) edges.col(c) = x.col(el[c + 1]) - x.col(el[0]);
  const double factorial = Dim == 3 ? 6.0 : (Dim == 2 ? 2.0 : 1.0);
  return edges.determinant() / factorial;
}

template <int Dim>
void check_mesh(const MassSpringSystem<Dim>& s, const SimplexMesh<Dim>& mesh) {
  if (mesh.nodes.cols() != s.num_nodes()) {
    throw std::invalid_argument("write_vtu: the mesh has " + std::to_string(mesh.nodes.cols()) +
                                " nodes, the object " + std::to_string(s.num_nodes()) +
                                "; pass the mesh the object was made from");
  }
  for (size_t e = 0; e < mesh.elements.size(); ++e) {
    for (int n : mesh.elements[e]) {
      if (n < 0 || n >= s.num_nodes()) {
        throw std::invalid_argument("write_vtu: mesh element " + std::to_string(e) +
                                    " refers to node " + std::to_string(n) + ", out of range");
      }
    }
  }
}

// Opens a DataArray; `components` 0 leaves NumberOfComponents out.
void open_array(Text& t, const char* type, const char* name, int components) {
  t << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 0) t << " NumberOfComponents=\"" << components << "\"";
  t << " format=\"ascii\">\n";
}
void close_array(Text& t) { t << "        </DataArray>\n"; }

// Writes values one line per tuple.
template <class Values>
void write_rows(Text& t, const Values& rows) {
  for (const auto& row : rows) {
    t << "          ";
    for (size_t c = 0; c < row.size(); ++c) t << (c ? " " : "") << row[c];
    t << "\n";
  }
}

}  // namespace

template <int Dim>
void write_vtu(const std::string& path, const MassSpringSystem<Dim>& s,
               const SimplexMesh<Dim>* mesh) {
  if (mesh) check_mesh(s, *mesh);
  const int nodes = s.num_nodes();
  const size_t springs = s.springs.size();
  const size_t elements = mesh ? mesh->elements.size() : 0;
  constexpr int kElementType = Dim == 3 ? 10 : (Dim == 2 ? 5 : 3);

  // 3D rows of the points and velocities
  auto padded = [nodes](const typename MassSpringSystem<Dim>::Points& p) {
    std::vector<std::array<double, 3>> rows(nodes, {0.0, 0.0, 0.0});
    for (int n = 0; n < nodes; ++n) {
      for (int c = 0; c < Dim; ++c) rows[n][c] = p(c, n);
    }
    return rows;
  };

  // an element is broken when the spring along one of its edges is
  std::map<std::pair<int, int>, bool> edge_broken;
  if (mesh) {
    for (const Spring& sp : s.springs) {
      bool& b = edge_broken[{std::min(sp.i, sp.j), std::max(sp.i, sp.j)}];
      b = b || sp.broken;
    }
  }

  std::vector<std::array<double, 1>> strain, kind, broken;
  for (const Spring& sp : s.springs) {
    typename MassSpringSystem<Dim>::Vec n;
    double length = 0.0;
    spring_direction<Dim>(s.x.col(sp.j) - s.x.col(sp.i), &n, &length);
    strain.push_back({(length - sp.params.rest_length) / sp.params.rest_length});
    kind.push_back({0.0});
    broken.push_back({sp.broken ? 1.0 : 0.0});
  }
  for (size_t e = 0; e < elements; ++e) {
    const auto& el = mesh->elements[e];
    const double rest = std::abs(signed_measure<Dim>(mesh->nodes, el));
    strain.push_back({(std::abs(signed_measure<Dim>(s.x, el)) - rest) / rest});
    kind.push_back({1.0});
    bool any = false;
    for (int a = 0; a <= Dim; ++a) {
      for (int b = a + 1; b <= Dim; ++b) {
        const auto it = edge_broken.find({std::min(el[a], el[b]), std::max(el[a], el[b])});
        any = any || (it != edge_broken.end() && it->second);
      }
    }
    broken.push_back({any ? 1.0 : 0.0});
  }

  Text t;
  t << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <UnstructuredGrid>\n"
    << "    <FieldData>\n"
    << "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
       "format=\"ascii\">\n"
    << "        " << s.t << "\n"
    << "      </DataArray>\n"
    << "    </FieldData>\n"
    << "    <Piece NumberOfPoints=\"" << nodes << "\" NumberOfCells=\"" << springs + elements
    << "\">\n"
    << "      <PointData Vectors=\"velocity\" Scalars=\"mass\">\n";
  open_array(t, "Float64", "velocity", 3);
  write_rows(t, padded(s.v));
  close_array(t);
  open_array(t, "Float64", "mass", 0);
  std::vector<std::array<double, 1>> column(nodes);
  for (int n = 0; n < nodes; ++n) column[n][0] = s.mass(n);
  write_rows(t, column);
  close_array(t);
  open_array(t, "UInt8", "pinned", 0);
  for (int n = 0; n < nodes; ++n) column[n][0] = s.pinned[n] ? 1.0 : 0.0;
  write_rows(t, column);
  close_array(t);
  t << "      </PointData>\n"
    << "      <CellData Scalars=\"strain\">\n";
  open_array(t, "UInt8", "kind", 0);
  write_rows(t, kind);
  close_array(t);
  open_array(t, "Float64", "strain", 0);
  write_rows(t, strain);
  close_array(t);
  open_array(t, "UInt8", "broken", 0);
  write_rows(t, broken);
  close_array(t);
  t << "      </CellData>\n"
    << "      <Points>\n";
  open_array(t, "Float64", "Points", 3);
  write_rows(t, padded(s.x));
  close_array(t);
  t << "      </Points>\n"
    << "      <Cells>\n";
  open_array(t, "Int64", "connectivity", 0);
  for (const Spring& sp : s.springs) t << "          " << sp.i << " " << sp.j << "\n";
  for (size_t e = 0; e < elements; ++e) {
    // positively oriented in the rest shape, as VTK orders a cell's corners
    std::array<int, Dim + 1> el = mesh->elements[e];
    if (Dim > 1 && signed_measure<Dim>(mesh->nodes, el) < 0.0) std::swap(el[Dim - 1], el[Dim]);
    t << "         ";
    for (int n : el) t << " " << n;
    t << "\n";
  }
  close_array(t);
  open_array(t, "Int64", "offsets", 0);
  long long offset = 0;
  for (size_t k = 0; k < springs + elements; ++k) {
    offset += k < springs ? 2 : Dim + 1;
    t << "          " << offset << "\n";
  }
  close_array(t);
  open_array(t, "UInt8", "types", 0);
  for (size_t k = 0; k < springs + elements; ++k) {
    t << "          " << (k < springs ? 3 : kElementType) << "\n";
  }
  close_array(t);
  t << "      </Cells>\n"
    << "    </Piece>\n"
    << "  </UnstructuredGrid>\n"
    << "</VTKFile>\n";
  write_atomically(path, t.str());
}

void write_pvd(const std::string& path, const std::vector<PvdFrame>& frames) {
  Text t;
  t << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n";
  for (const PvdFrame& f : frames) {
    t << "    <DataSet timestep=\"" << f.time << "\" group=\"\" part=\"0\" file=\""
      << xml_attribute(f.file) << "\"/>\n";
  }
  t << "  </Collection>\n"
    << "</VTKFile>\n";
  write_atomically(path, t.str());
}

VtkSeriesWriter::VtkSeriesWriter(std::string folder, std::string name)
    : folder_(std::move(folder)), name_(std::move(name)) {
  std::error_code error;
  std::filesystem::create_directories(folder_, error);
  if (error) throw OutputError(folder_, "creating the folder");
}

template <int Dim>
std::string VtkSeriesWriter::write_frame(const MassSpringSystem<Dim>& s,
                                         const SimplexMesh<Dim>* mesh) {
  char number[16];
  std::snprintf(number, sizeof number, "_%06zu.vtu", frames_.size());
  const std::string file = name_ + number;
  const std::string path = folder_ + "/" + file;
  write_vtu(path, s, mesh);
  frames_.push_back({s.t, file});
  write_pvd(pvd_path(), frames_);
  return path;
}

#define GENCOORD_INSTANTIATE(D)                                                    \
  template void write_vtu<D>(const std::string&, const MassSpringSystem<D>&,       \
                             const SimplexMesh<D>*);                               \
  template std::string VtkSeriesWriter::write_frame<D>(const MassSpringSystem<D>&, \
                                                       const SimplexMesh<D>*);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
