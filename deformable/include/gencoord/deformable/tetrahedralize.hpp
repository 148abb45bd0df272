// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file tetrahedralize.hpp
/// Tetrahedral meshes of solids given by their boundary, a closed triangle surface, made by
/// the TetGen program (version 1.5, Debian package `tetgen`).
///
/// TetGen is licensed under the AGPL. This library runs it as a separate program, found on
/// PATH, and never links its library (libtet), so that none of its code is in this library or
/// in the programs that use it.

#include <string>

#include "gencoord/deformable/mesh.hpp"
#include "gencoord/deformable/mesh_io.hpp"

namespace gencoord::deformable {

/// What TetGen is asked for.
struct TetgenOptions {
  /// Bound on every tetrahedron's circumradius over its shortest edge (TetGen's -q): TetGen
  /// adds points, inside and on the surface, until each tetrahedron keeps it. 0: no quality
  /// bound (TetGen adds only the points the boundary needs). Otherwise at least 1: below that
  /// TetGen may not terminate.
  double radius_edge_ratio = 1.414;
  /// Largest volume of a tetrahedron (m^3, TetGen's -a); 0: no bound.
  double max_volume = 0.0;
};

/// Fills the solid bounded by `surface` with tetrahedra: writes the surface as a TetGen
/// .smesh file into a fresh temporary directory (under $TMPDIR, else /tmp), runs
/// `tetgen -p [-q<ratio>] [-a<volume>] -Q` on it (without a shell), reads its .node and .ele
/// files with read_tetgen<3>, and removes the directory, also when something fails.
///
/// The mesh's first surface.nodes.cols() nodes are the surface's nodes, in order and at the
/// same positions; the nodes after them are those TetGen added (inside, and on the surface
/// where it split triangles, which leaves the surface's shape and the volume unchanged). Every
/// tetrahedron is positively oriented. `name` stands for the surface in messages (the .obj
/// file it was read from); `source`, when given (read_obj fills it), lets messages name the
/// file's lines and vertex numbers, else they name triangle and node indices.
///
/// \throws MeshError for options out of range (a ratio between 0 and 1, a volume below 0 or
/// not finite). \throws MeshFileError ("name:line: what is wrong; what to do") for a surface
/// without triangles, with a node that is not finite or in no triangle, with an index out of
/// range or a repeated node, or that is not closed (find_surface_defect, closed_surface.hpp:
/// the message names the edge or vertex and a face's line, and says to close the surface or to
/// read it as a sheet with read_obj); when `tetgen` is not on PATH (install it: apt-get install
/// tetgen); when TetGen fails (the message has what it printed, and, when the surface
/// intersects itself, the lines of the faces that cross others).
SimplexMesh<3> tetrahedralize(const TriangleSurface& surface, const std::string& name,
                              const TetgenOptions& options = {}, const ObjSource* source = nullptr);

}  // namespace gencoord::deformable
