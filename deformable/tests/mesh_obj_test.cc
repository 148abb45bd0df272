// SPDX-License-Identifier: BSD-3-Clause
// Wavefront .obj surfaces: reading them (vertex forms, negative indices, fans, the vertices
// kept), every refusal naming its file and line, closedness, and closed surfaces filled with
// tetrahedra by the tetgen program: the volume they enclose, positive tetrahedra, the surface's
// nodes kept, the open or self-intersecting surface refused; and a read solid simulated.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <unistd.h>

#include "expect_refused.hpp"
#include "gencoord/deformable/closed_surface.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/tetrahedralize.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "mesh_files.hpp"

namespace gencoord::deformable {
namespace {

TriangleSurface ReadObj(const std::string& text, ObjSource* source = nullptr) {
  std::istringstream in(text);
  return read_obj(in, "surface.obj", source);
}

using testing::ExpectRefused;

double SignedVolume(const SimplexMesh<3>& mesh, int e) {
  Eigen::Matrix3d edges;
  for (int c = 0; c < 3; ++c) {
    edges.col(c) = mesh.nodes.col(mesh.elements[e][c + 1]) - mesh.nodes.col(mesh.elements[e][0]);
  }
  return edges.determinant() / 6.0;
}

double TriangleArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// What a tetrahedral mesh of a closed surface must satisfy: the surface's nodes first, every
// tetrahedron positive, the volume the surface encloses (divergence theorem, computed here
// about the origin; negative for a surface oriented inward), and the faces of one tetrahedron only
// (the boundary) of the surface's area. Returns the smallest tetrahedron's volume.
double ExpectFillsSurface(const SimplexMesh<3>& mesh, const TriangleSurface& surface) {
  const long long n = surface.nodes.cols();
  EXPECT_GE(mesh.nodes.cols(), n);
  EXPECT_EQ(mesh.nodes.leftCols(n), surface.nodes) << "the surface's nodes come first, exactly";
  double enclosed = 0.0, area = 0.0;
  for (const auto& t : surface.triangles) {
    const Eigen::Vector3d a = surface.nodes.col(t[0]), b = surface.nodes.col(t[1]),
                          c = surface.nodes.col(t[2]);
    enclosed += a.dot(b.cross(c)) / 6.0;
    area += TriangleArea(a, b, c);
  }
  double total = 0.0, smallest = INFINITY;
  std::map<std::array<int, 3>, int> faces;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const double v = SignedVolume(mesh, e);
    EXPECT_GT(v, 0.0) << "tetrahedron " << e << " is not positively oriented";
    total += v;
    smallest = std::min(smallest, v);
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      for (int k = 0, j = 0; k < 4; ++k) {
        if (k != skip) f[j++] = mesh.elements[e][k];
      }
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  }
  double boundary = 0.0;
  for (const auto& [f, count] : faces) {
    EXPECT_LE(count, 2);
    if (count == 1) {
      boundary += TriangleArea(mesh.nodes.col(f[0]), mesh.nodes.col(f[1]), mesh.nodes.col(f[2]));
    }
  }
  EXPECT_NEAR(total, std::abs(enclosed), 1e-9 * std::abs(enclosed))
      << "the volume differs from the enclosed one";
  EXPECT_NEAR(boundary, area, 1e-9 * area) << "the boundary is not the surface";
  return smallest;
}

// A regular tetrahedron's surface, normals outward, each line one statement.
const char* const kTetrahedron =
    "v 1 1 1\n"
    "v 1 -1 -1\n"
    "v -1 1 -1\n"
    "v -1 -1 1\n"
    "f 1 2 3\n"
    "f 1 3 4\n"
    "f 1 4 2\n"
    "f 2 4 3\n";

TEST(MeshObjTest, CubeCountsFansAndRemapping) {
  ObjSource source;
  const TriangleSurface cube = read_obj(kMeshes + "/cube.obj", &source);
  ASSERT_EQ(cube.nodes.cols(), 8) << "vertex 1 is in no face";
  EXPECT_EQ(cube.nodes.col(0), Eigen::Vector3d(0, 0, 0)) << "vertex 2 becomes node 0";
  EXPECT_EQ(cube.nodes.col(7), Eigen::Vector3d(0, 1, 1));
  ASSERT_EQ(cube.triangles.size(), 12u) << "six quadrangles, two triangles each";
  // f 2//1 5//1 4//1 3//1: the fan (2, 5, 4), (2, 4, 3), less one for the dropped vertex
  EXPECT_EQ(cube.triangles[0], (std::array<int, 3>{0, 3, 2}));
  EXPECT_EQ(cube.triangles[1], (std::array<int, 3>{0, 2, 1}));
  EXPECT_EQ(cube.triangles[11], (std::array<int, 3>{1, 6, 5}));
  EXPECT_EQ(source.vertex_numbers, (std::vector<long long>{2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(source.face_lines, (std::vector<int>{27, 27, 28, 28, 29, 29, 30, 30, 31, 31, 32, 32}));
  EXPECT_TRUE(is_closed_surface(cube));
  EXPECT_DOUBLE_EQ(enclosed_volume(cube), 1.0);
}

TEST(MeshObjTest, NegativeAndForwardIndicesAndOtherLines) {
  const TriangleSurface plain = ReadObj(kTetrahedron);
  ASSERT_EQ(plain.nodes.cols(), 4);
  ASSERT_EQ(plain.triangles.size(), 4u);
  EXPECT_NEAR(enclosed_volume(plain), 8.0 / 3.0, 1e-15) << "a regular tetrahedron of edge 2 sqrt 2";
  // the same surface: -1 is the last v line above the face, whichever lines come between;
  // a positive index may name a v line further down; w, colours and skipped statements
  const TriangleSurface relative = ReadObj(
      "v 1 1 1 1.0\n"
      "v 1 -1 -1 0.5 0.5 0.5\n"
      "v -1 1 -1\n"
      "vt 0.5 0.5\n"
      "f -3/-1 -2/-1 -1/-1\n"
      "g part  # a comment\n"
      "s 1\n"
      "f 1 3 4\n"
      "v -1 -1 1\n"
      "l 1 2\n"
      "p 1\n"
      "\n"
      "usemtl steel\n"
      "f -4 -1 -3\n"
      "f -3//1 -1//1 -2//1\n");
  EXPECT_EQ(relative.nodes, plain.nodes);
  EXPECT_EQ(relative.triangles, plain.triangles);
}

TEST(MeshObjTest, RefusesBadNumbersAndVertexLines) {
  ExpectRefused([] { ReadObj("v 0 0 0\nv 1 zero 0\n"); }, 2,
                "surface.obj:2: v: y: expected a number, got 'zero'");
  ExpectRefused([] { ReadObj("# vertices\nv 0 0\n"); }, 2,
                "surface.obj:2: v: expected 3 numbers (x y z), or 4 (x y z w) or 6 (x y z r g "
                "b), got 2");
  ExpectRefused([] { ReadObj("v 0 0 nan\n"); }, 1, "surface.obj:1: v: z: nan is not a finite");
  ExpectRefused([] { ReadObj("v 0 0 0 1 2\n"); }, 1, "got 5");
  ExpectRefused([] { ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3.5\n"); }, 4,
                "surface.obj:4: f: vertex 3 is '3.5', not a vertex reference; write i, i/t, "
                "i//n or i/t/n");
  ExpectRefused([] { ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/1/1/1 3\n"); }, 4,
                "vertex 2 is '2/1/1/1', not a vertex reference");
  ExpectRefused([] { ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/x 3\n"); }, 4,
                "vertex 2 is '2/x', not a vertex reference");
}

TEST(MeshObjTest, RefusesIndicesThatNameNoVertex) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  ExpectRefused([&] { ReadObj(triangle + "f 0 1 2\n"); }, 4,
                "surface.obj:4: f: vertex index 0 names no v line; indices count the v lines "
                "from 1");
  ExpectRefused([&] { ReadObj(triangle + "f 1 2 3\nf 1 3 4\n"); }, 5,
                "surface.obj:5: f: vertex index 4 names no v line: the file has 3 vertices");
  ExpectRefused([&] { ReadObj(triangle + "f -1 -2 -4\n"); }, 4,
                "surface.obj:4: f: vertex index -4 counts back past the first v line: only 3 v "
                "lines are above this line");
  // the smallest long long, whose negation overflows (found by scripts/fuzz.sh)
  ExpectRefused([&] { ReadObj(triangle + "f -9223372036854775808 1 2\n"); }, 4,
                "vertex index -9223372036854775808 counts back past the first v line");
}

TEST(MeshObjTest, RefusesFacesThatAreNotTriangles) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  ExpectRefused([&] { ReadObj(square + "f 1 2\n"); }, 5,
                "surface.obj:5: f: a face needs at least 3 vertices, got 2");
  ExpectRefused([&] { ReadObj(square + "f 1 2 3\nf 1 3 4 3\n"); }, 6,
                "surface.obj:6: f: the face uses vertex 3 twice (as its vertex 2 and 4)");
  // vertex 5 on the diagonal from 1 to 3: the quadrangle's first triangle is flat
  ExpectRefused([&] { ReadObj(square + "v 0.5 0.5 0\nf 1 3 4\nf 1 5 3 2\n"); }, 7,
                "surface.obj:7: f: the triangle of vertices 1 5 3 (cut from this face of 4 "
                "vertices) is degenerate: its area 0 is not above");
  ExpectRefused([&] { ReadObj(square + "f 1 2 2/1\n"); }, 5, "uses vertex 2 twice");
}

TEST(MeshObjTest, JudgesTrianglesAtAnyScale) {
  EXPECT_EQ(ReadObj("v 0 0 0\nv 1e100 0 0\nv 0 1e100 0\nf 1 2 3\n").triangles.size(), 1u);
  for (const char* side : {"1e200", "1e-200"}) {
    const std::string s = side;
    ExpectRefused([&] { ReadObj("v 0 0 0\nv " + s + " 0 0\nv 0 " + s + " 0\nf 1 2 3\n"); }, 4,
                  "surface.obj:4: f: the triangle of vertices 1 2 3 has an area (");
  }
}

TEST(MeshObjTest, RefusesOtherStatementsAndFilesWithoutFaces) {
  ExpectRefused([] { ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n# no faces\n"); }, 4,
                "surface.obj:4: the file has no faces (f lines) after 3 vertices; export the "
                "surface with its faces");
  ExpectRefused([] { ReadObj(""); }, 0, "surface.obj:0: the file has no faces");
  ExpectRefused([] { ReadObj("v 0 0 0\ncstype bspline\n"); }, 2,
                "surface.obj:2: 'cstype': free-form curves and surfaces are not read; export the "
                "surface as polygons");
  ExpectRefused([] { ReadObj("v 0 0 0\nvertex 1 2 3\n"); }, 2,
                "surface.obj:2: unknown statement 'vertex'");
  ExpectRefused([] { ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n3\n"); }, 4,
                "surface.obj:4: the line is continued with '\\'");
  ExpectRefused([] { read_obj(kMeshes + "/missing.obj"); }, 0,
                "missing.obj: cannot be opened for reading");
}

// The first defect, as find_surface_defect reports it in the cube's files.
TEST(MeshObjTest, FindsTheFirstDefectOfASurface) {
  ObjSource source;
  const TriangleSurface open = read_obj(kMeshes + "/open_box.obj", &source);
  std::optional<SurfaceDefect> d = find_surface_defect(open);
  ASSERT_TRUE(d.has_value());
  // the front face (2 3 7 6) is the first with an edge on the rim: 7 -> 6 of (2, 7, 6)
  EXPECT_EQ(d->kind, SurfaceDefect::Kind::kOpenEdge);
  EXPECT_EQ(source.vertex_numbers[d->a], 7);
  EXPECT_EQ(source.vertex_numbers[d->b], 6);
  EXPECT_EQ(source.face_lines[d->triangle], 28);
  EXPECT_EQ(d->count, 1);

  const TriangleSurface flipped = read_obj(kMeshes + "/flipped_face.obj", &source);
  d = find_surface_defect(flipped);
  ASSERT_TRUE(d.has_value());
  // the bottom's triangle (2, 4, 3) and the flipped face's (3, 8, 4) both run 4 -> 3
  EXPECT_EQ(d->kind, SurfaceDefect::Kind::kMisorientedEdge);
  EXPECT_EQ(source.vertex_numbers[d->a], 4);
  EXPECT_EQ(source.vertex_numbers[d->b], 3);
  EXPECT_EQ(source.face_lines[d->triangle], 27);
  EXPECT_EQ(source.face_lines[d->other], 32);
  // about the centre each face adds area x distance / 3 = 1/6; the flipped one subtracts it
  EXPECT_NEAR(enclosed_volume(flipped), 4.0 / 6.0, 1e-15);

  // a fin on the tetrahedron's edge 1-2: that edge is in three triangles
  TriangleSurface fin = ReadObj(std::string(kTetrahedron) + "v 3 0 0\nf 2 1 5\n");
  d = find_surface_defect(fin);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->kind, SurfaceDefect::Kind::kNonManifoldEdge);
  EXPECT_EQ(d->count, 3);
  EXPECT_EQ(d->triangle, 0);
  EXPECT_EQ(d->other, 2);

  // two tetrahedra that share vertex 1 only: closed along every edge, pinched at the vertex
  TriangleSurface pinched = ReadObj(std::string(kTetrahedron) +
                                    "v 3 3 1\nv 1 3 3\nv 3 1 3\nf 1 5 6\nf 1 6 7\nf 1 7 5\n"
                                    "f 5 7 6\n");
  d = find_surface_defect(pinched);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->kind, SurfaceDefect::Kind::kNonManifoldVertex);
  EXPECT_EQ(d->a, 0);
  EXPECT_EQ(d->count, 2);
  EXPECT_FALSE(is_closed_surface(pinched));
  EXPECT_TRUE(is_closed_surface(ReadObj(kTetrahedron)));

  EXPECT_THROW(find_surface_defect(TriangleSurface{Eigen::Matrix3Xd::Zero(3, 2), {{0, 1, 2}}}),
               MeshError);
}

TEST(MeshObjTest, IcosphereEnclosesTheVolumeOfItsPolyhedron) {
  const TriangleSurface sphere = read_obj(kMeshes + "/icosphere.obj");
  ASSERT_EQ(sphere.nodes.cols(), 42);
  ASSERT_EQ(sphere.triangles.size(), 80u);
  EXPECT_TRUE(is_closed_surface(sphere));
  // the icosahedron of circumradius 1 alone: 5 / 12 (3 + sqrt 5) a^3, a = 4 / sqrt(10 + 2 sqrt 5)
  TriangleSurface ico = ReadObj(
      "v -1 1.6180339887498949 0\nv 1 1.6180339887498949 0\nv -1 -1.6180339887498949 0\n"
      "v 1 -1.6180339887498949 0\nv 0 -1 1.6180339887498949\nv 0 1 1.6180339887498949\n"
      "v 0 -1 -1.6180339887498949\nv 0 1 -1.6180339887498949\nv 1.6180339887498949 0 -1\n"
      "v 1.6180339887498949 0 1\nv -1.6180339887498949 0 -1\nv -1.6180339887498949 0 1\n"
      "f 1 12 6\nf 1 6 2\nf 1 2 8\nf 1 8 11\nf 1 11 12\nf 2 6 10\nf 6 12 5\nf 12 11 3\n"
      "f 11 8 7\nf 8 2 9\nf 4 10 5\nf 4 5 3\nf 4 3 7\nf 4 7 9\nf 4 9 10\nf 5 10 6\n"
      "f 3 5 12\nf 7 3 11\nf 9 7 8\nf 10 9 2\n");
  ASSERT_TRUE(is_closed_surface(ico));
  ico.nodes /= std::sqrt(1.0 + 1.6180339887498949 * 1.6180339887498949);
  const double a = 4.0 / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
  EXPECT_NEAR(enclosed_volume(ico), 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * a * a * a, 1e-14);
  // subdivided, it lies between the icosahedron and the ball
  EXPECT_GT(enclosed_volume(sphere), enclosed_volume(ico));
  EXPECT_LT(enclosed_volume(sphere), 4.0 / 3.0 * M_PI);
  std::printf("[ obj ] icosahedron %.6f, icosphere %.6f, ball %.6f m^3\n", enclosed_volume(ico),
              enclosed_volume(sphere), 4.0 / 3.0 * M_PI);
}

TEST(MeshObjTest, TetrahedralizesTheCube) {
  const TriangleSurface cube = read_obj(kMeshes + "/cube.obj");
  const SimplexMesh<3> coarse = tetrahedralize(cube, "cube.obj");
  ExpectFillsSurface(coarse, cube);
  EXPECT_EQ(coarse.nodes.cols(), 8) << "the cube's tetrahedra keep the ratio 1.414 unrefined";
  // a volume bound refines it: every tetrahedron below it, the whole still the cube
  const SimplexMesh<3> fine = tetrahedralize(cube, "cube.obj", TetgenOptions{1.414, 0.01});
  ExpectFillsSurface(fine, cube);
  double largest = 0.0;
  for (int e = 0; e < static_cast<int>(fine.elements.size()); ++e) {
    largest = std::max(largest, SignedVolume(fine, e));
  }
  EXPECT_LE(largest, 0.01);
  EXPECT_GE(fine.elements.size(), 100u);
  std::printf(
      "[ obj ] cube: %zu tetrahedra; with max_volume 0.01: %zu on %d nodes, largest "
      "%.5f m^3\n",
      coarse.elements.size(), fine.elements.size(), static_cast<int>(fine.nodes.cols()), largest);
}

TEST(MeshObjTest, TetrahedralizesTheIcosphere) {
  const TriangleSurface sphere = read_obj(kMeshes + "/icosphere.obj");
  const SimplexMesh<3> mesh = tetrahedralize(sphere, "icosphere.obj");
  const double smallest = ExpectFillsSurface(mesh, sphere);
  EXPECT_NEAR(mesh.nodes.rowwise().mean().eval()(0), 0.2, 0.1) << "around its centre";
  std::printf(
      "[ obj ] icosphere: %d nodes (42 on the surface), %zu tetrahedra, the smallest "
      "%.3g m^3\n",
      static_cast<int>(mesh.nodes.cols()), mesh.elements.size(), smallest);
}

TEST(MeshObjTest, RefusesToTetrahedralizeAnOpenOrFlippedSurface) {
  ExpectRefused([] { read_mesh<3>(kMeshes + "/open_box.obj"); }, 28,
                "open_box.obj:28: the surface is not closed: the edge from vertex 7 to vertex 6 "
                "is in this face only, so the surface has a hole there; to fill it with "
                "tetrahedra, make it the closed boundary of a solid");
  ExpectRefused([] { read_mesh<3>(kMeshes + "/open_box.obj"); }, 28,
                "or read it as a sheet with read_obj");
  ExpectRefused([] { read_mesh<3>(kMeshes + "/flipped_face.obj"); }, 27,
                "flipped_face.obj:27: the surface is not consistently oriented: this face and "
                "the face on line 32 both run from vertex 4 to vertex 3");
  // without a source, messages name triangles and nodes
  ExpectRefused([] { tetrahedralize(read_obj(kMeshes + "/open_box.obj"), "box"); }, 0,
                "box: the surface is not closed: the edge from node 5 to node 4 is in "
                "triangle 3 only");
  // a seam: the front face's vertices 6 and 7 repeated as 10 and 11 in the top face
  ExpectRefused(
      [] {
        std::istringstream in(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "v 0 0 1\nv 1 0 1\n"
            "f 1 4 3 2\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\nf 9 10 7 8\n");
        ObjSource source;
        const TriangleSurface seam = read_obj(in, "seam.obj", &source);
        tetrahedralize(seam, "seam.obj", {}, &source);
      },
      12, "(vertex 10 is at the same position as vertex 6: merge the vertices that repeat");
}

// Two unit cubes, the second moved by (0.5, 0.5, 0.5): each closed, but their faces cross.
const char* const kOverlappingCubes =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "v .5 .5 .5\nv 1.5 .5 .5\nv 1.5 1.5 .5\nv .5 1.5 .5\n"
    "v .5 .5 1.5\nv 1.5 .5 1.5\nv 1.5 1.5 1.5\nv .5 1.5 1.5\n"
    "f 1 4 3 2\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\nf 5 6 7 8\n"
    "f 9 12 11 10\nf 9 10 14 13\nf 12 16 15 11\nf 9 13 16 12\nf 10 11 15 14\nf 13 14 15 16\n";

TEST(MeshObjTest, TetgenFailureNamesTheFacesThatCross) {
  std::istringstream in(kOverlappingCubes);
  ObjSource source;
  const TriangleSurface crossed = read_obj(in, "crossed.obj", &source);
  ASSERT_TRUE(is_closed_surface(crossed));
  EXPECT_NEAR(enclosed_volume(crossed), 2.0, 1e-14) << "two outward cubes";
  // the first face that crosses the other cube is the first cube's side y = 1, on line 19
  ExpectRefused([&] { tetrahedralize(crossed, "crossed.obj", {}, &source); }, 19,
                "crossed.obj:19: the surface intersects itself: TetGen cannot fill it; 12 "
                "triangles cross others (in the faces on lines 19, 21, 22, 23, 24, 26); move");
}

// A cube with a cubic cavity (the inner cube's faces point into the cavity): TetGen fills the
// cavity too, so the tetrahedra's volume is not the enclosed one, and the result is refused.
// Turned inside out as a whole, a cube is filled as it is.
TEST(MeshObjTest, RefusesAHollowSolidAndFillsACubeTurnedInsideOut) {
  std::istringstream in(
      "v 0 0 0\nv 3 0 0\nv 3 3 0\nv 0 3 0\nv 0 0 3\nv 3 0 3\nv 3 3 3\nv 0 3 3\n"
      "v 1 1 1\nv 2 1 1\nv 2 2 1\nv 1 2 1\nv 1 1 2\nv 2 1 2\nv 2 2 2\nv 1 2 2\n"
      "f 1 4 3 2\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\nf 5 6 7 8\n"
      "f 9 10 11 12\nf 9 13 14 10\nf 12 11 15 16\nf 9 12 16 13\nf 10 14 15 11\n"
      "f 13 16 15 14\n");
  const TriangleSurface hollow = read_obj(in, "hollow.obj");
  ASSERT_TRUE(is_closed_surface(hollow));
  EXPECT_NEAR(enclosed_volume(hollow), 27.0 - 1.0, 1e-13);
  ExpectRefused([&] { tetrahedralize(hollow, "hollow.obj"); }, 0,
                "hollow.obj: TetGen's tetrahedra fill 27 m^3, but the surface encloses 26 m^3; "
                "check that it does not intersect itself and that no part of it lies inside "
                "another");

  TriangleSurface inside_out = read_obj(kMeshes + "/cube.obj");
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  ASSERT_TRUE(is_closed_surface(inside_out));
  EXPECT_DOUBLE_EQ(enclosed_volume(inside_out), -1.0);
  ExpectFillsSurface(tetrahedralize(inside_out, "inside_out.obj"), inside_out);
}

// Sets an environment variable for the scope, restoring it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    const char* old = std::getenv(name);
    if (old != nullptr) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(MeshObjTest, RefusesWithoutTetgenOnThePath) {
  const TriangleSurface cube = read_obj(kMeshes + "/cube.obj");
  const ScopedEnv path("PATH", "/nonexistent");
  ExpectRefused([&] { tetrahedralize(cube, "cube.obj"); }, 0,
                "cube.obj: cannot fill the surface with tetrahedra: the program 'tetgen' (TetGen "
                "1.5) is not on PATH; install it (Debian, Ubuntu: apt-get install tetgen)");
}

// Writes an executable shell script `tetgen` into `folder`.
void WriteFakeTetgen(const std::filesystem::path& folder, const std::string& body) {
  const std::filesystem::path script = folder / "tetgen";
  std::ofstream(script) << "#!/bin/sh\n" << body;
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
}

TEST(MeshObjTest, ReportsWhatAFailingTetgenPrinted) {
  namespace fs = std::filesystem;
  const fs::path folder =
      fs::temp_directory_path() / ("gencoord_fake_tetgen_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const TriangleSurface cube = read_obj(kMeshes + "/cube.obj");
  {
    const ScopedEnv path("PATH", folder.string() + ":" + std::getenv("PATH"));
    WriteFakeTetgen(folder, "echo \"Error: a fake tetgen refuses $1\"\nexit 3\n");
    ExpectRefused([&] { tetrahedralize(cube, "cube.obj"); }, 0,
                  "cube.obj: TetGen failed to fill the surface with tetrahedra: 'tetgen -p "
                  "-q1.414 -Q surface.smesh' exited with status 3 after printing 'Error: a fake "
                  "tetgen refuses -p'; check that the surface bounds a solid");
    // what it printed before a signal ended it is kept
    WriteFakeTetgen(folder, "echo \"Opening surface.smesh.\"\nkill -ABRT $$\n");
    ExpectRefused(
        [&] {
          tetrahedralize(cube, "cube.obj", TetgenOptions{0.0, 0.5});
        },
        0,
        "'tetgen -p -a0.5 -Q surface.smesh' was ended by signal 6 (Aborted) after "
        "printing 'Opening surface.smesh.'");
  }
  {
    const ScopedEnv tmpdir("TMPDIR", (folder / "missing").string());
    ExpectRefused([&] { tetrahedralize(cube, "cube.obj"); }, 0,
                  "cube.obj: cannot fill the surface with tetrahedra: ");
  }
  fs::remove_all(folder);
}

TEST(MeshObjTest, TemporaryFilesInAPathWithSpacesAreRemoved) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::temp_directory_path() /
                          ("gencoord obj test " + std::to_string(::getpid()));  // one per process
  fs::create_directories(folder);
  {
    const ScopedEnv tmpdir("TMPDIR", folder.string());
    const TriangleSurface cube = read_obj(kMeshes + "/cube.obj");
    EXPECT_EQ(tetrahedralize(cube, "cube.obj").elements.size(), 6u);
    EXPECT_TRUE(fs::is_empty(folder)) << "the temporary directory is left behind";
    std::istringstream in(kOverlappingCubes);
    EXPECT_THROW(tetrahedralize(read_obj(in, "crossed.obj"), "crossed.obj"), MeshFileError);
    EXPECT_TRUE(fs::is_empty(folder)) << "a failed run leaves its temporary directory behind";
  }
  fs::remove_all(folder);
}

TEST(MeshObjTest, RefusesUnusableOptionsAndA2dRead) {
  const TriangleSurface cube = read_obj(kMeshes + "/cube.obj");
  EXPECT_THROW(tetrahedralize(cube, "cube.obj", TetgenOptions{0.5, 0.0}), MeshError);
  EXPECT_THROW(tetrahedralize(cube, "cube.obj", TetgenOptions{1.414, -1.0}), MeshError);
  EXPECT_THROW(tetrahedralize(cube, "cube.obj", TetgenOptions{NAN, 0.0}), MeshError);
  ExpectRefused([] { read_mesh<2>(kMeshes + "/cube.obj"); }, 0,
                "cube.obj: an .obj file holds a surface in 3D, which a 2D read cannot take; "
                "read it with read_mesh<3> to fill it with tetrahedra, or with read_obj as a "
                "sheet");
}

// A sphere read from its .obj falls freely: the springs' forces cancel, so the centre of mass
// drops g t^2 / 2 while the sphere keeps its size.
TEST(MeshObjTest, ReadSphereFallsFreely) {
  const SimplexMesh<3> mesh = read_mesh<3>(kMeshes + "/icosphere.obj");
  MassSpringSystem<3> s = make_mass_spring(mesh, Material{1e5, 1000.0, 10.0});
  s.gravity << 0.0, 0.0, -9.81;
  const double mass = s.mass.sum();
  auto center = [&] { return ((s.x * s.mass) / mass).eval(); };
  const Eigen::Vector3d start = center();
  const double width = s.x.row(0).maxCoeff() - s.x.row(0).minCoeff();
  const double dt = 0.5 * cfl_limit(s);
  for (int k = 0; k < 50; ++k) symplectic_euler_step(s, dt);
  ASSERT_TRUE(s.x.allFinite() && s.v.allFinite());
  // symplectic Euler's drop after n steps: g dt^2 n (n + 1) / 2
  const double n = static_cast<double>(s.steps);
  const double drop = 9.81 * dt * dt * n * (n + 1.0) / 2.0;
  EXPECT_NEAR(start(2) - center()(2), drop, 1e-9 * drop);
  EXPECT_NEAR((center() - start).head<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.x.row(0).maxCoeff() - s.x.row(0).minCoeff(), width, 1e-9)
      << "free fall does not deform it";
  std::printf("[ obj ] icosphere of %zu tetrahedra, %d steps of %.3g s: dropped %.6g m\n",
              mesh.elements.size(), static_cast<int>(n), dt, drop);
}

}  // namespace
}  // namespace gencoord::deformable
