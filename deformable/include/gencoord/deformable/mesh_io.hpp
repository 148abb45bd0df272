// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file mesh_io.hpp
/// Reading triangle (Dim = 2) and tetrahedral (Dim = 3) meshes written by Gmsh (.msh, ASCII
/// format 2.2 or 4.1) or by TetGen / Triangle (.node + .ele), and triangle surfaces in 3D from
/// Wavefront .obj files: a sheet, or the boundary of a solid that read_mesh<3> fills with
/// tetrahedra (tetrahedralize.hpp).
///
/// What every mesh reader returns: the nodes that some element uses, in the order of the file
/// (file tags or numbers are remapped to 0..n-1; unused nodes, e.g. geometry points of a .msh,
/// are dropped), and the elements in the order of the file, each oriented positively (a
/// negatively oriented element has its last two nodes swapped, which leaves its area or volume
/// and its edges unchanged). Elements of other kinds (points, lines, the surface triangles of a
/// 3D .msh, quadrangles) are skipped. A 2D read takes x and y; a .msh for a 2D read must have
/// the same z at every node used.
///
/// Every refusal is a MeshFileError (errors.hpp) whose message starts with "file:line: " and
/// says what is wrong and what to do: a file that cannot be opened, an unknown or binary
/// format, a line with too few or too many numbers, a word where a number belongs, a count that
/// disagrees with what follows, a file that ends early, a node index or tag that does not
/// exist, a node that is not finite, an element that repeats a node or whose area or volume is
/// not above kMinRelativeMeasure (validate.hpp) times its longest edge to the power Dim, and a
/// file without any element of the requested dimension.

#include <istream>
#include <string>
#include <vector>

#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// Reads a Gmsh .msh file (ASCII, format 2.x or 4.1): 3-node triangles (element type 2) for
/// Dim = 2, 4-node tetrahedra (type 4) for Dim = 3. \throws MeshFileError
template <int Dim>
SimplexMesh<Dim> read_gmsh(const std::string& path);

/// The same from a stream; `name` stands for the file in messages.
template <int Dim>
SimplexMesh<Dim> read_gmsh(std::istream& in, const std::string& name);

/// Reads a TetGen (Dim = 3) or Triangle (Dim = 2) mesh: `base`.node and `base`.ele. Indices
/// are 0- or 1-based, as the first point of the .node file is numbered; attributes and
/// boundary markers are read past; second-order elements (10-node tetrahedra, 6-node
/// triangles) keep their corners. \throws MeshFileError
template <int Dim>
SimplexMesh<Dim> read_tetgen(const std::string& base);

/// The same from two streams; `node_name` and `ele_name` stand for the files in messages.
template <int Dim>
SimplexMesh<Dim> read_tetgen(std::istream& node, const std::string& node_name, std::istream& ele,
                             const std::string& ele_name);

/// Where the triangles and nodes of a surface read by read_obj come from, for messages about
/// them (tetrahedralize names the lines and vertex numbers of the file).
struct ObjSource {
  std::vector<int> face_lines;            ///< per triangle: the line of its `f` statement
  std::vector<long long> vertex_numbers;  ///< per node: its number in the file (from 1)
};

/// Reads a Wavefront .obj file as a triangle surface. It reads the `v x y z` lines (an
/// optional fourth number, the weight w, and the colour `v x y z r g b` some programs write
/// are read past) and the `f` lines, whose vertices are written `i`, `i/t`, `i//n` or `i/t/n`
/// (only the vertex index i is used); an index counts the `v` lines from 1, a negative index
/// counts back from the last `v` line above it (-1 is that line). A face of more than three
/// vertices v0 v1 ... vk is cut into the fan of triangles (v0, v(j), v(j+1)), which is right
/// for a convex planar polygon. `#` starts a comment; `vt vn vp g o s usemtl mtllib l p mg` and
/// the display statements (`bevel c_interp d_interp lod usemap maplib shadow_obj trace_obj`)
/// are skipped.
///
/// Returns the vertices that some face uses, in file order (numbered from 0), and the
/// triangles in file order, each with its vertices in the order of the face. When `source` is
/// given, it receives each triangle's line and each node's vertex number in the file.
///
/// \throws MeshFileError ("file:line: what is wrong; what to do") for a file that cannot be
/// opened, a word where a number belongs, a coordinate that is not finite, a `v` line with other
/// than 3, 4 or 6 numbers, a vertex that is not an index of those forms, index 0 or an index
/// that names no `v` line, a face of fewer than 3 vertices or that repeats a vertex, a triangle
/// whose area is not above kMinRelativeMeasure times its longest edge squared, free-form
/// geometry (`cstype`, `curv`, `surf`, ...), an unknown statement, a line continued with `\`,
/// and a file without faces.
TriangleSurface read_obj(const std::string& path, ObjSource* source = nullptr);

/// The same from a stream; `name` stands for the file in messages.
TriangleSurface read_obj(std::istream& in, const std::string& name, ObjSource* source = nullptr);

/// Reads `path` by its extension: .msh (read_gmsh), .node or .ele (read_tetgen of the pair),
/// or, for Dim = 3, .obj: read_obj, then tetrahedralize (tetrahedralize.hpp) with its default
/// options, which needs the `tetgen` program and a closed surface. A 2D read of an .obj is
/// refused (its surface is in 3D; read_obj reads it as a sheet). \throws MeshFileError, also
/// for any other extension.
template <int Dim>
SimplexMesh<Dim> read_mesh(const std::string& path);

}  // namespace gencoord::deformable
