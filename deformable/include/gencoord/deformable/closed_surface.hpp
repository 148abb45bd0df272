// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file closed_surface.hpp
/// Whether a triangle surface bounds a solid (a closed, consistently oriented 2-manifold, as
/// tetrahedralize needs), and the volume it encloses.

#include <optional>

#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// The first place where a triangle surface fails to be a closed, consistently oriented
/// 2-manifold.
struct SurfaceDefect {
  enum class Kind {
    kOpenEdge,           ///< the edge is in one triangle only: the rim of a hole
    kMisorientedEdge,    ///< two triangles run along the edge a -> b in the same direction,
                         ///< so their orientations disagree (one of them is flipped)
    kNonManifoldEdge,    ///< the edge is in more than two triangles
    kNonManifoldVertex,  ///< the triangles around node a form several fans that meet only
                         ///< at a (the surface pinches there)
  };
  Kind kind = Kind::kOpenEdge;
  int a = -1;         ///< the edge's first node as `triangle` runs along it; the vertex
  int b = -1;         ///< the edge's second node; -1 for kNonManifoldVertex
  int triangle = -1;  ///< the first triangle (in order) that uses the edge or the vertex
  int other = -1;     ///< the next triangle along the edge (-1: kOpenEdge, kNonManifoldVertex)
  int count = 0;      ///< triangles along the edge; fans around the vertex
};

/// Checks that `surface` is a closed, consistently oriented 2-manifold: every edge is in
/// exactly two triangles, which run along it once in each direction, and the triangles around
/// every node form a single fan. Returns the first defect (the edges are visited triangle by
/// triangle, a -> b, b -> c, c -> a; then the nodes, in the order the triangles first use
/// them), or nothing when the surface is closed. Nodes that no triangle uses are not looked
/// at. A closed surface may have several components, and may be oriented inward
/// (enclosed_volume < 0). \throws MeshError for a triangle with a node index out of range
/// or a repeated node.
std::optional<SurfaceDefect> find_surface_defect(const TriangleSurface& surface);

/// True when find_surface_defect finds nothing. \throws MeshError as find_surface_defect.
bool is_closed_surface(const TriangleSurface& surface);

/// Volume (m^3) enclosed by a closed surface, by the divergence theorem: the sum over the
/// triangles (a, b, c) of a . (b x c) / 6, taken about the nodes' centroid. Positive when the
/// triangles' normals point outward, negative when they point inward. \throws MeshError as
/// find_surface_defect.
double enclosed_volume(const TriangleSurface& surface);

}  // namespace gencoord::deformable
