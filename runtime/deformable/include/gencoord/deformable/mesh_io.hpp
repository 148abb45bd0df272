#pragma once
/// \file mesh_io.hpp
/// Reading triangle (Dim = 2) and tetrahedral (Dim = 3) meshes written by Gmsh (.msh, ASCII
/// format 2.2 or 4.1) or by TetGen / Triangle (.node + .ele).
///
/// What every reader returns: the nodes that some element uses, in the order of the file
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

/// Reads `path` by its extension: .msh (read_gmsh), or .node or .ele (read_tetgen of the
/// pair). \throws MeshFileError, also for any other extension.
template <int Dim>
SimplexMesh<Dim> read_mesh(const std::string& path);

}  // namespace gencoord::deformable
