// SPDX-License-Identifier: BSD-3-Clause
// Closedness of a triangle surface: its edges in pairs of opposite directions, and a single fan
// of triangles around each node; and the volume it encloses.
#include "gencoord/deformable/closed_surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "gencoord/deformable/errors.hpp"

namespace gencoord::deformable {

namespace {

void check_triangles(const TriangleSurface& surface) {
  const long long n = surface.nodes.cols();
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tri = surface.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (tri[k] < 0 || tri[k] >= n) {
        throw MeshError("triangle " + std::to_string(t) + " refers to node " +
                            std::to_string(tri[k]) + ", out of range: the surface has " +
                            std::to_string(n) + " nodes",
                        static_cast<int>(t), tri[k]);
      }
      if (tri[k] == tri[(k + 1) % 3]) {
        throw MeshError("triangle " + std::to_string(t) + " uses node " + std::to_string(tri[k]) +
                            " twice; every corner must be a different node",
                        static_cast<int>(t), tri[k]);
      }
    }
  }
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

// The edges: how often triangles run along each from its lower to its higher node and back.
struct EdgeUses {
  int up = 0, down = 0;
};

std::optional<SurfaceDefect> find_edge_defect(const TriangleSurface& surface) {
  std::unordered_map<std::uint64_t, EdgeUses> edges;
  edges.reserve(surface.triangles.size() * 3 / 2 + 1);
  for (const auto& tri : surface.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      EdgeUses& uses = edges[edge_key(a, b)];
      ++(a < b ? uses.up : uses.down);
    }
  }
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tri = surface.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      const EdgeUses& uses = edges.at(edge_key(a, b));
      const int count = uses.up + uses.down;
      if (count == 2 && uses.up == 1) continue;
      SurfaceDefect defect;
      defect.kind = count == 1   ? SurfaceDefect::Kind::kOpenEdge
                    : count == 2 ? SurfaceDefect::Kind::kMisorientedEdge
                                 : SurfaceDefect::Kind::kNonManifoldEdge;
      defect.a = a;
      defect.b = b;
      defect.triangle = static_cast<int>(t);
      defect.count = count;
      for (size_t u = t + 1; u < surface.triangles.size() && defect.other < 0; ++u) {
        const auto& next = surface.triangles[u];
        for (int j = 0; j < 3; ++j) {
          if (edge_key(next[j], next[(j + 1) % 3]) == edge_key(a, b))
            defect.other = static_cast<int>(u);
        }
      }
      return defect;
    }
  }
  return std::nullopt;
}

// With every edge in two triangles of opposite directions, the triangles (v, x, y) around a
// node v give link edges x -> y in which each x starts exactly one edge: the link is a set of
// cycles, one per fan. The surface is a manifold at v when there is a single cycle.
std::optional<SurfaceDefect> find_vertex_defect(const TriangleSurface& surface) {
  struct LinkEdge {
    int vertex, from, to;
    bool operator<(const LinkEdge& o) const {
      return vertex != o.vertex ? vertex < o.vertex : from < o.from;
    }
  };
  std::vector<LinkEdge> link;
  link.reserve(surface.triangles.size() * 3);
  for (const auto& tri : surface.triangles) {
    for (int k = 0; k < 3; ++k) link.push_back({tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]});
  }
  std::sort(link.begin(), link.end());
  std::vector<int> fans(surface.nodes.cols(), 0);
  for (size_t begin = 0; begin < link.size();) {
    size_t end = begin;
    while (end < link.size() && link[end].vertex == link[begin].vertex) ++end;
    std::vector<char> seen(end - begin, 0);
    int count = 0;
    for (size_t start = begin; start < end; ++start) {
      if (seen[start - begin]) continue;
      ++count;
      for (size_t at = start; at < end && !seen[at - begin];) {
        seen[at - begin] = 1;
        const LinkEdge next{link[at].vertex, link[at].to, 0};
        at = std::lower_bound(link.begin() + begin, link.begin() + end, next) - link.begin();
      }
    }
    fans[link[begin].vertex] = count;
    begin = end;
  }
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    for (const int v : surface.triangles[t]) {
      if (fans[v] > 1) {
        SurfaceDefect defect;
        defect.kind = SurfaceDefect::Kind::kNonManifoldVertex;
        defect.a = v;
        defect.triangle = static_cast<int>(t);
        defect.count = fans[v];
        return defect;
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<SurfaceDefect> find_surface_defect(const TriangleSurface& surface) {
  check_triangles(surface);
  if (auto defect = find_edge_defect(surface)) return defect;
  return find_vertex_defect(surface);
}

bool is_closed_surface(const TriangleSurface& surface) {
  return !find_surface_defect(surface).has_value();
}

double enclosed_volume(const TriangleSurface& surface) {
  check_triangles(surface);
  if (surface.nodes.cols() == 0) return 0.0;
  // about the centroid, so that a surface far from the origin loses no digits
  const Eigen::Vector3d center = surface.nodes.rowwise().mean();
  double six_volume = 0.0;
  for (const auto& tri : surface.triangles) {
    const Eigen::Vector3d a = surface.nodes.col(tri[0]) - center;
    const Eigen::Vector3d b = surface.nodes.col(tri[1]) - center;
    const Eigen::Vector3d c = surface.nodes.col(tri[2]) - center;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

}  // namespace gencoord::deformable
