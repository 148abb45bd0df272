// SPDX-License-Identifier: BSD-3-Clause
// ParaView output: the .vtu files read back (points, cells, strain, broken flags, velocity,
// mass), the .pvd's frames and times, the same run giving the same bytes, and refusals.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/vtk_writer.hpp"
#include "gencoord/io/output_file.hpp"

namespace gencoord::deformable {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The folders of this process's tests (one root per process, so that runs do not collide),
// removed when the tests have run.
const fs::path kRoot =
    fs::temp_directory_path() / ("gencoord_vtk_test_" + std::to_string(::getpid()));
class RemoveFolders : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(kRoot); }
};
const ::testing::Environment* const kRemoveFolders =
    ::testing::AddGlobalTestEnvironment(new RemoveFolders);

// A fresh folder under kRoot.
fs::path Folder(const std::string& name) {
  const fs::path folder = kRoot / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

// True if every tag is closed in order (a small check that the file is well-formed XML).
bool TagsBalanced(const std::string& xml) {
  const std::regex tag(R"(<(/?)([A-Za-z]+)[^>]*?(/?)>)");
  std::vector<std::string> open;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), tag); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    if (m[3] == "/") continue;  // <Tag .../>
    if (m[1] == "/") {
      if (open.empty() || open.back() != m[2]) return false;
      open.pop_back();
    } else {
      open.push_back(m[2]);
    }
  }
  return open.empty();
}

// The value of attribute `name` of the first <tag ...>.
std::string Attribute(const std::string& xml, const std::string& tag, const std::string& name) {
  std::smatch m;
  const std::regex pattern("<" + tag + "\\b[^>]*\\b" + name + "=\"([^\"]*)\"");
  return std::regex_search(xml, m, pattern) ? m[1].str() : "(missing)";
}

// The numbers of the DataArray called `name`.
std::vector<double> Array(const std::string& xml, const std::string& name) {
  const size_t at = xml.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const size_t begin = xml.find('>', at) + 1, end = xml.find("</DataArray>", begin);
  std::istringstream in(xml.substr(begin, end - begin));
  std::vector<double> values;
  for (double x; in >> x;) values.push_back(x);
  return values;
}

TEST(VtkWriterTest, StretchedSpringStrainVelocityAndMass) {
  MassSpringSystem<2> s;
  s.x.resize(2, 2);
  s.x << 0.0, 1.1, 0.0, 0.0;
  s.v.resize(2, 2);
  s.v << 0.5, 1.0, -0.25, 2.0;
  s.mass = Eigen::Vector2d(2.0, 3.0);
  s.pinned = {1, 0};
  Spring spring;
  spring.i = 0;
  spring.j = 1;
  spring.params.rest_length = 1.0;
  spring.params.stiffness = 10.0;
  s.springs.push_back(spring);
  s.t = 0.125;
  const fs::path file = Folder("spring") / "spring.vtu";
  write_vtu(file.string(), s);
  const std::string xml = Slurp(file);
  EXPECT_TRUE(TagsBalanced(xml));
  EXPECT_EQ(Attribute(xml, "VTKFile", "type"), "UnstructuredGrid");
  EXPECT_EQ(Attribute(xml, "Piece", "NumberOfPoints"), "2");
  EXPECT_EQ(Attribute(xml, "Piece", "NumberOfCells"), "1");
  EXPECT_THAT(Array(xml, "TimeValue"), ElementsAre(0.125));
  EXPECT_THAT(Array(xml, "Points"), ElementsAre(0, 0, 0, 1.1, 0, 0));
  EXPECT_THAT(Array(xml, "velocity"), ElementsAre(0.5, -0.25, 0, 1, 2, 0));
  EXPECT_THAT(Array(xml, "mass"), ElementsAre(2, 3));
  EXPECT_THAT(Array(xml, "pinned"), ElementsAre(1, 0));
  EXPECT_THAT(Array(xml, "strain"), ElementsAre((1.1 - 1.0) / 1.0)) << "exactly, not rounded";
  EXPECT_THAT(Array(xml, "broken"), ElementsAre(0));
  EXPECT_THAT(Array(xml, "kind"), ElementsAre(0));
  EXPECT_THAT(Array(xml, "connectivity"), ElementsAre(0, 1));
  EXPECT_THAT(Array(xml, "offsets"), ElementsAre(2));
  EXPECT_THAT(Array(xml, "types"), ElementsAre(3));
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

TEST(VtkWriterTest, TrianglesAfterTheSpringsWithTheirAreaChange) {
  const SimplexMesh<2> mesh = rectangle_mesh(1.0, 1.0, 1, 1);
  MassSpringSystem<2> s = make_mass_spring(mesh, Material{100.0, 1.0, 0.0});
  s.x.row(0) *= 1.1;  // stretched 10% along x: every area grows 10%
  const fs::path file = Folder("square") / "square.vtu";
  write_vtu(file.string(), s, &mesh);
  const std::string xml = Slurp(file);
  EXPECT_TRUE(TagsBalanced(xml));
  EXPECT_EQ(Attribute(xml, "Piece", "NumberOfCells"), "7");
  EXPECT_THAT(Array(xml, "types"), ElementsAre(3, 3, 3, 3, 3, 5, 5));
  EXPECT_THAT(Array(xml, "kind"), ElementsAre(0, 0, 0, 0, 0, 1, 1));
  EXPECT_THAT(Array(xml, "offsets"), ElementsAre(2, 4, 6, 8, 10, 13, 16));
  const std::vector<double> connectivity = Array(xml, "connectivity");
  ASSERT_EQ(connectivity.size(), 16u);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(connectivity[10 + a], mesh.elements[0][a]);
  const std::vector<double> strain = Array(xml, "strain");
  ASSERT_EQ(strain.size(), 7u);
  EXPECT_NEAR(strain[5], 0.1, 1e-15);
  EXPECT_NEAR(strain[6], 0.1, 1e-15);
  const std::vector<double> points = Array(xml, "Points");
  ASSERT_EQ(points.size(), 12u);
  for (int n = 0; n < 4; ++n) EXPECT_EQ(points[3 * n + 2], 0.0) << "z = 0 in 2D";
}

TEST(VtkWriterTest, TetrahedraIn3DAndLinesIn1D) {
  const SimplexMesh<3> box = box_mesh(1.0, 1.0, 1.0, 1, 1, 1);
  const MassSpringSystem<3> solid = make_mass_spring(box, Material{100.0, 1.0, 0.0});
  const fs::path folder = Folder("dims");
  write_vtu((folder / "box.vtu").string(), solid, &box);
  const std::string xml = Slurp(folder / "box.vtu");
  EXPECT_TRUE(TagsBalanced(xml));
  EXPECT_EQ(Attribute(xml, "Piece", "NumberOfPoints"), "8");
  EXPECT_EQ(Attribute(xml, "Piece", "NumberOfCells"), "25") << "19 springs and 6 tetrahedra";
  const std::vector<double> types = Array(xml, "types");
  ASSERT_EQ(types.size(), 25u);
  EXPECT_EQ(types[18], 3);
  EXPECT_EQ(types[19], 10);
  EXPECT_EQ(Array(xml, "offsets").back(), 19 * 2 + 6 * 4);
  EXPECT_THAT(Array(xml, "strain"), ::testing::Each(0.0)) << "at rest";
  // every tetrahedron written positively oriented (box_mesh has both orientations)
  const std::vector<double> p = Array(xml, "Points"), c = Array(xml, "connectivity");
  ASSERT_EQ(c.size(), 19u * 2 + 6 * 4);
  for (int e = 0; e < 6; ++e) {
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) {
      const int a = static_cast<int>(c[38 + 4 * e]), b = static_cast<int>(c[38 + 4 * e + k + 1]);
      for (int d = 0; d < 3; ++d) edges(d, k) = p[3 * b + d] - p[3 * a + d];
    }
    EXPECT_GT(edges.determinant(), 0.0) << "tetrahedron " << e;
  }

  MassSpringSystem<1> rod;
  rod.x.resize(1, 2);
  rod.x << 0.0, 2.0;
  rod.v = Eigen::RowVector2d(0.0, 3.0);
  rod.mass = Eigen::Vector2d(1.0, 1.0);
  rod.pinned = {0, 0};
  Spring spring;
  spring.j = 1;
  spring.params.rest_length = 1.0;
  rod.springs.push_back(spring);
  write_vtu((folder / "rod.vtu").string(), rod);
  const std::string line = Slurp(folder / "rod.vtu");
  EXPECT_THAT(Array(line, "Points"), ElementsAre(0, 0, 0, 2, 0, 0));
  EXPECT_THAT(Array(line, "velocity"), ElementsAre(0, 0, 0, 3, 0, 0));
  EXPECT_THAT(Array(line, "strain"), ElementsAre(1.0));
}

TEST(VtkWriterTest, BrokenFlagAfterFracture) {
  // a strip pulled apart: the right end moves at 2 m/s, springs break at 5% strain
  const SimplexMesh<2> mesh = rectangle_mesh(1.0, 0.2, 4, 1);
  MassSpringSystem<2> s = make_mass_spring(mesh, Material{100.0, 1.0, 0.0});
  pin_nodes_where(s, 0, 0.0);
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.x(0, n) > 1.0 - 1e-9) {
      s.pinned[n] = 1;
      s.v(0, n) = 2.0;
    }
  }
  s.inelastic.fracture_strain = 0.05;
  const double dt = 0.5 * cfl_limit(s);
  while (s.fractures.empty() && s.t < 1.0) symplectic_euler_step(s, dt);
  ASSERT_FALSE(s.fractures.empty()) << "nothing broke";
  const fs::path file = Folder("fracture") / "fracture.vtu";
  write_vtu(file.string(), s, &mesh);
  const std::string xml = Slurp(file);
  const std::vector<double> broken = Array(xml, "broken");
  const size_t springs = s.springs.size();
  ASSERT_EQ(broken.size(), springs + mesh.elements.size());
  for (size_t k = 0; k < springs; ++k) {
    EXPECT_EQ(broken[k], s.springs[k].broken ? 1.0 : 0.0) << "spring " << k;
  }
  const Spring& first = s.springs[s.fractures.front().spring];
  int flagged = 0;
  for (size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto& el = mesh.elements[e];
    const bool has_i = std::find(el.begin(), el.end(), first.i) != el.end();
    const bool has_j = std::find(el.begin(), el.end(), first.j) != el.end();
    if (has_i && has_j) {
      EXPECT_EQ(broken[springs + e], 1.0) << "element " << e << " has the broken spring";
      ++flagged;
    }
  }
  EXPECT_GE(flagged, 1);
  EXPECT_GT(Array(xml, "strain")[s.fractures.front().spring], 0.05);
}

// A short disk drop written every 20 steps; returns the writer's frames.
std::vector<PvdFrame> RunSeries(const fs::path& folder) {
  const SimplexMesh<2> mesh = disk_mesh(0.2, 2, {0.0, 0.25});
  MassSpringSystem<2> s = make_mass_spring(mesh, Material{5000.0, 1.0, 0.5});
  s.gravity << 0.0, -9.81;
  with_ground(s, 0.0, 0.05);
  VtkSeriesWriter writer(folder.string(), "disk");
  writer.write_frame(s, &mesh);
  const double dt = 0.5 * cfl_limit(s);
  for (int frame = 1; frame < 4; ++frame) {
    for (int k = 0; k < 20; ++k) symplectic_euler_step(s, dt);
    writer.write_frame(s, &mesh);
  }
  EXPECT_EQ(writer.pvd_path(), (folder / "disk.pvd").string());
  return writer.frames();
}

TEST(VtkWriterTest, PvdListsEveryFrameWithItsTime) {
  const fs::path folder = Folder("series");
  const std::vector<PvdFrame> frames = RunSeries(folder);
  ASSERT_EQ(frames.size(), 4u);
  const std::string pvd = Slurp(folder / "disk.pvd");
  EXPECT_TRUE(TagsBalanced(pvd));
  EXPECT_EQ(Attribute(pvd, "VTKFile", "type"), "Collection");
  const std::regex dataset(R"re(<DataSet timestep="([^"]*)" group="" part="0" file="([^"]*)"/>)re");
  std::vector<std::pair<double, std::string>> listed;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset);
       it != std::sregex_iterator(); ++it) {
    listed.emplace_back(std::stod((*it)[1].str()), (*it)[2].str());
  }
  ASSERT_EQ(listed.size(), 4u);
  for (size_t f = 0; f < 4; ++f) {
    EXPECT_EQ(listed[f].first, frames[f].time) << "frame " << f;
    EXPECT_EQ(listed[f].second, "disk_00000" + std::to_string(f) + ".vtu");
    const std::string vtu = Slurp(folder / listed[f].second);
    EXPECT_TRUE(TagsBalanced(vtu)) << listed[f].second;
    EXPECT_THAT(Array(vtu, "TimeValue"), ElementsAre(frames[f].time));
  }
  EXPECT_EQ(listed[0].first, 0.0);
  EXPECT_GT(listed[3].first, listed[2].first);
  // only the frames and the collection are left, no temporary file
  int files = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    EXPECT_NE(entry.path().extension(), ".tmp");
    ++files;
  }
  EXPECT_EQ(files, 5);
  // the ball fell: its velocities are written
  const std::vector<double> v = Array(Slurp(folder / listed[3].second), "velocity");
  ASSERT_FALSE(v.empty());
  EXPECT_LT(v[1], 0.0) << "the centre node moves down";
}

TEST(VtkWriterTest, SameRunSameBytes) {
  const fs::path a = Folder("same_a"), b = Folder("same_b");
  RunSeries(a);
  RunSeries(b);
  for (const std::string name :
       {"disk.pvd", "disk_000000.vtu", "disk_000001.vtu", "disk_000002.vtu", "disk_000003.vtu"}) {
    const std::string first = Slurp(a / name);
    EXPECT_FALSE(first.empty()) << name;
    EXPECT_EQ(first, Slurp(b / name)) << name;
  }
}

TEST(VtkWriterTest, RefusesAMissingFolderAndAMeshThatDoesNotFit) {
  const SimplexMesh<2> mesh = rectangle_mesh(1.0, 1.0, 1, 1);
  const MassSpringSystem<2> s = make_mass_spring(mesh, Material{100.0, 1.0, 0.0});
  const std::string missing = (kRoot / "missing" / "no" / "frame.vtu").string();
  try {
    write_vtu(missing, s);
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const OutputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(missing));
  }
  const SimplexMesh<2> other = rectangle_mesh(1.0, 1.0, 2, 1);
  const fs::path file = Folder("misfit") / "misfit.vtu";
  try {
    write_vtu(file.string(), s, &other);
    ADD_FAILURE() << "accepted a mesh of 6 nodes for an object of 4";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("the mesh has 6 nodes, the object 4"));
  }
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace gencoord::deformable
