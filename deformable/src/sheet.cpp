// SPDX-License-Identifier: BSD-3-Clause
// Sheets in 3D: springs along the edges, hinges across the interior ones, both calibrated
// (sheet.hpp).
#include "gencoord/deformable/sheet.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "gencoord/deformable/bending.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/lattice_elasticity.hpp"
#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable {

namespace {

// A surface lies in a plane when every node is within this fraction of its extent of it.
constexpr double kPlanarTolerance = 1e-9;
// calibrate_hinges() accepts direction-dependent factors down to this fraction of the
// uniform one (as calibrate_springs() does)
constexpr double kSmallestHingeFactor = 0.2;

// One triangle's use of an edge (i < j): the triangle and its third node.
struct EdgeUse {
  int i, j, triangle, wing;
  bool operator<(const EdgeUse& o) const {
    return std::tie(i, j, triangle) < std::tie(o.i, o.j, o.triangle);
  }
};

std::vector<EdgeUse> edge_uses(const TriangleSurface& surface) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * surface.triangles.size());
  for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
    const auto& tri = surface.triangles[t];
    for (int a = 0; a < 3; ++a) {
      const int p = tri[a], q = tri[(a + 1) % 3];
      uses.push_back({std::min(p, q), std::max(p, q), t, tri[(a + 2) % 3]});
    }
  }
  std::sort(uses.begin(), uses.end());
  return uses;
}

// M of a hinge (sheet.hpp): theta = -M : K for a small uniform curvature K of the flat hinge,
// as a 3 x 3 tensor in the plane of wing A's triangle, unfolded
Eigen::Matrix3d curvature_map(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                              const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  const Eigen::Vector3d e = x1 - x0;
  const double l2 = e.squaredNorm(), l = std::sqrt(l2);
  const double sa = (x2 - x0).dot(e) / l2, sb = (x3 - x0).dot(e) / l2;
  const Eigen::Vector3d ra = x2 - x0 - sa * e;
  const double ha = ra.norm(), hb = (x3 - x0 - sb * e).norm();
  const Eigen::Vector3d t = e / l, n = ra / ha;
  const double across = 0.5 * (ha + hb);
  const double mixed = 0.5 * (sa - sb) * l;
  const double along = 0.5 * ((sa * sa - sa) * l2 / ha + (sb * sb - sb) * l2 / hb);
  return across * n * n.transpose() + mixed * (t * n.transpose() + n * t.transpose()) +
         along * t * t.transpose();
}

// (M_uu, M_vv, sqrt(2) M_uv): M in an orthonormal basis of the symmetric 2 x 2 tensors
Eigen::Vector3d in_plane(const Eigen::Matrix3d& m, const Eigen::Vector3d& u,
                         const Eigen::Vector3d& v) {
  return {u.dot(m * u), v.dot(m * v), std::sqrt(2.0) * u.dot(m * v)};
}

// a symmetric 3 x 3 matrix as 6 numbers whose Euclidean norm is its Frobenius norm
using Stored = Eigen::Matrix<double, 6, 1>;
Stored stored(const Eigen::Matrix3d& b) {
  const double r2 = std::sqrt(2.0);
  Stored out;
  out << b(0, 0), b(1, 1), b(2, 2), r2 * b(0, 1), r2 * b(0, 2), r2 * b(1, 2);
  return out;
}

// lambda + 2 mu of the isotropic part of sum_h kb_h M_h (x) M_h (2 / A) (sheet.hpp)
double isotropic_stiffness(const std::vector<double>& kb, const std::vector<Eigen::Matrix3d>& maps,
                           double area) {
  double sum = 0.0;
  for (std::size_t h = 0; h < kb.size(); ++h) {
    const double trace = maps[h].trace();
    sum += kb[h] * (2.0 * maps[h].squaredNorm() + trace * trace);
  }
  return sum / (4.0 * area);
}

// Scales kb (the discrete-shells weights for D = 1) so that the hinges' B is an isotropic
// plate of cylindrical stiffness 1 as far as their directions allow (planar: in the plane of
// u, v), else by the uniform factor (sheet.hpp).
void calibrate_hinges(std::vector<double>& kb, const std::vector<Eigen::Matrix3d>& maps,
                      double area, bool planar, const Eigen::Vector3d& u,
                      const Eigen::Vector3d& v) {
  // first the uniform factor, which gives the isotropic part its stiffness
  const double uniform = 1.0 / isotropic_stiffness(kb, maps, area);
  for (double& k : kb) k *= uniform;
  if (planar) {
    // then g_h = 1 + phi_h . y with the smallest sum_h w_h (g_h - 1)^2 such that
    // sum_h w_h g_h phi_h = I + lambda (J - I) for some lambda (I: cylindrical stiffness 1,
    // J = (1,1,0)(1,1,0)^T, lambda the mesh's choice): stationarity in lambda makes y normal
    // to J - I, so (P G P) y = P (I - S) with P the projection normal to it (sums relative to
    // W = sum_h w_h); y = 0 where the uniformly scaled hinges are already isotropic
    const std::size_t count = kb.size();
    std::vector<Stored> phi(count);
    std::vector<double> weight(count);
    double total = 0.0;
    for (std::size_t h = 0; h < count; ++h) {
      const Eigen::Vector3d m = in_plane(maps[h], u, v);
      const Stored c = stored((2.0 * kb[h] / area) * m * m.transpose());
      weight[h] = c.norm();
      phi[h] = c / weight[h];
      total += weight[h];
    }
    Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Zero();
    Stored now = Stored::Zero();
    for (std::size_t h = 0; h < count; ++h) {
      gram += (weight[h] / total) * phi[h] * phi[h].transpose();
      now += (weight[h] / total) * phi[h];
    }
    Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
    j.topLeftCorner<2, 2>().setOnes();
    const Stored free_direction = stored(j - Eigen::Matrix3d::Identity()).normalized();
    const Eigen::Matrix<double, 6, 6> project =
        Eigen::Matrix<double, 6, 6>::Identity() - free_direction * free_direction.transpose();
    const Stored target = stored(Eigen::Matrix3d::Identity()) / total;
    const Stored y = (project * gram * project)
                         .completeOrthogonalDecomposition()
                         .solve(project * (target - now));
    std::vector<double> factor(count, 1.0);
    bool directional = true;
    for (std::size_t h = 0; h < count && directional; ++h) {
      factor[h] = 1.0 + phi[h].dot(project * y);
      // directions too few for isotropy ask for factors near or below zero: keep the uniform
      directional = std::isfinite(factor[h]) && factor[h] >= kSmallestHingeFactor;
    }
    if (directional) {
      for (std::size_t h = 0; h < count; ++h) kb[h] *= factor[h];
    }
  }
  // where the directions cannot reach an isotropic B the least-squares factors leave its
  // isotropic part off 1; set it (a no-op where they can)
  const double rescale = 1.0 / isotropic_stiffness(kb, maps, area);
  for (double& k : kb) k *= rescale;
}

// In-plane springs of a planar sheet: calibrate_springs<2> in the plane of u, v
double calibrate_planar_springs(MassSpringSystem<3>& s, const Eigen::Vector3d& u,
                                const Eigen::Vector3d& v, double area, double youngs_modulus) {
  MassSpringSystem<2> flat;
  flat.springs = s.springs;
  Eigen::Matrix2Xd rest(2, s.num_nodes());
  for (int n = 0; n < s.num_nodes(); ++n) rest.col(n) << u.dot(s.x.col(n)), v.dot(s.x.col(n));
  const double largest = calibrate_springs<2>(flat, rest, area, youngs_modulus);
  for (std::size_t k = 0; k < s.springs.size(); ++k) s.springs[k].params = flat.springs[k].params;
  return largest;
}

// Curved sheet: the uniform factor 3 E A / sum k L (lattice_elasticity.hpp, 2D)
double calibrate_curved_springs(MassSpringSystem<3>& s, double area, double youngs_modulus) {
  double total = 0.0;
  for (const Spring& sp : s.springs) total += sp.params.stiffness * sp.params.rest_length;
  const double factor = 3.0 * youngs_modulus * (area / total);
  if (!(std::isfinite(factor) && factor > 0.0))
    throw MaterialError("make_sheet: Young's modulus " + std::to_string(youngs_modulus) +
                        " over springs of total k L " + std::to_string(total) +
                        " gives no finite spring stiffness; choose E, rho and the surface's "
                        "size so that E / rho stays within double range");
  for (Spring& sp : s.springs) {
    sp.params.stiffness *= factor;
    sp.params.damping *= factor;
  }
  return factor;
}

// Whether the nodes lie in a plane; if so, u and v span it
bool planar_frame(const Eigen::Matrix3Xd& nodes, Eigen::Vector3d* u, Eigen::Vector3d* v) {
  const Eigen::Vector3d center = nodes.rowwise().mean();
  const Eigen::Matrix3Xd centered = nodes.colwise() - center;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centered * centered.transpose());
  const Eigen::Vector3d normal = eigen.eigenvectors().col(0);  // smallest spread
  *u = eigen.eigenvectors().col(2);
  *v = eigen.eigenvectors().col(1);
  const double extent = centered.colwise().norm().maxCoeff();
  return (normal.transpose() * centered).cwiseAbs().maxCoeff() <= kPlanarTolerance * extent;
}

}  // namespace

double triangle_area(const TriangleSurface& surface, int t) {
  const auto& tri = surface.triangles[t];
  const Eigen::Vector3d x0 = surface.nodes.col(tri[0]);
  return 0.5 * (surface.nodes.col(tri[1]) - x0).cross(surface.nodes.col(tri[2]) - x0).norm();
}

TriangleSurface rectangle_sheet(double width, double height, int nx, int ny,
                                const Eigen::Vector3d& origin, DiagonalPattern pattern) {
  const SimplexMesh<2> flat = rectangle_mesh(width, height, nx, ny, pattern);
  TriangleSurface out;
  out.nodes.resize(3, flat.nodes.cols());
  out.nodes.topRows<2>() = flat.nodes;
  out.nodes.row(2).setZero();
  out.nodes.colwise() += origin;
  out.triangles.assign(flat.elements.begin(), flat.elements.end());  // counter-clockwise in xy
  return out;
}

TriangleSurface triangle_lattice_sheet(double width, double height, int nx, int ny,
                                       const Eigen::Vector3d& origin) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("triangle_lattice_sheet: need nx, ny >= 1");
  // the x of each row's nodes: 0, 1, ..., nx spacings; a shifted row 0, 1/2, 3/2, ..., nx
  std::vector<std::vector<double>> rows(ny + 1);
  std::vector<int> first(ny + 1);
  int count = 0;
  for (int j = 0; j <= ny; ++j) {
    std::vector<double>& row = rows[j];
    row.push_back(0.0);
    for (int i = 1; i <= nx; ++i) row.push_back(j % 2 ? i - 0.5 : i);
    if (j % 2) row.push_back(nx);
    first[j] = count;
    count += static_cast<int>(row.size());
  }
  TriangleSurface out;
  out.nodes.resize(3, count);
  for (int j = 0; j <= ny; ++j) {
    for (std::size_t i = 0; i < rows[j].size(); ++i)
      out.nodes.col(first[j] + i) =
          origin + Eigen::Vector3d(width * rows[j][i] / nx, height * j / ny, 0.0);
  }
  // stitch each pair of rows, advancing along the row whose next node comes first (the lower
  // one on a tie), so every triangle has an edge on one row and its third node on the other
  for (int j = 0; j < ny; ++j) {
    const std::vector<double>&lower = rows[j], &upper = rows[j + 1];
    std::size_t a = 0, b = 0;
    while (a + 1 < lower.size() || b + 1 < upper.size()) {
      const bool advance_lower =
          a + 1 < lower.size() && (b + 1 >= upper.size() || lower[a + 1] <= upper[b + 1]);
      const int la = first[j] + static_cast<int>(a), ub = first[j + 1] + static_cast<int>(b);
      if (advance_lower) {
        out.triangles.push_back({la, la + 1, ub});
        ++a;
      } else {
        out.triangles.push_back({la, ub + 1, ub});
        ++b;
      }
    }
  }
  return out;
}

MassSpringSystem<3> make_sheet(const TriangleSurface& surface, const Material& material,
                               double bending_stiffness) {
  validate_surface(surface);
  validate_material(material);
  if (!(std::isfinite(bending_stiffness) && bending_stiffness >= 0.0))
    throw MaterialError("make_sheet: bending stiffness D = " + std::to_string(bending_stiffness) +
                        " N m must be finite and >= 0 (0: no hinges)");
  const int count = static_cast<int>(surface.nodes.cols());
  const int triangles = static_cast<int>(surface.triangles.size());
  const double rho = material.density;
  const double c = material.wave_speed();

  MassSpringSystem<3> s;
  s.x = surface.nodes;
  s.v = Eigen::Matrix3Xd::Zero(3, count);
  s.mass = Eigen::VectorXd::Zero(count);
  s.pinned.assign(count, 0);
  std::vector<double> areas(triangles);
  double area = 0.0;
  for (int t = 0; t < triangles; ++t) {
    areas[t] = triangle_area(surface, t);
    area += areas[t];
    for (int node : surface.triangles[t]) s.mass(node) += rho * areas[t] / 3.0;
  }

  // one spring per edge, its mass around it a third of each triangle's; one hinge per edge
  // of two triangles (validate_surface() refuses more)
  const std::vector<EdgeUse> uses = edge_uses(surface);
  std::vector<Eigen::Matrix3d> maps;
  std::vector<double> kb;   // the discrete-shells weights for D = 1 (sheet.hpp)
  double hinge_area = 0.0;  // the hinges' thirds of their triangles: the area they measure
  for (std::size_t a = 0; a < uses.size();) {
    std::size_t b = a;
    double m = 0.0;
    for (; b < uses.size() && uses[b].i == uses[a].i && uses[b].j == uses[a].j; ++b)
      m += rho * areas[uses[b].triangle] / 3.0;
    Spring sp;
    sp.i = uses[a].i;
    sp.j = uses[a].j;
    sp.params.rest_length = (surface.nodes.col(sp.j) - surface.nodes.col(sp.i)).norm();
    sp.params.stiffness = c * c * m / sp.params.rest_length;
    sp.params.damping = material.damping * m / (rho * sp.params.rest_length);
    s.springs.push_back(sp);
    if (b - a == 2 && bending_stiffness > 0.0) {
      Hinge h;
      h.nodes = {sp.i, sp.j, uses[a].wing, uses[a + 1].wing};
      h.spring = static_cast<int>(s.springs.size()) - 1;
      const auto x = [&](int k) -> Eigen::Vector3d { return surface.nodes.col(h.nodes[k]); };
      h.rest_angle = hinge_angle(x(0), x(1), x(2), x(3)).angle;
      s.hinges.push_back(h);
      maps.push_back(curvature_map(x(0), x(1), x(2), x(3)));
      const double l2 = (x(1) - x(0)).squaredNorm();
      const double pair = areas[uses[a].triangle] + areas[uses[a + 1].triangle];
      kb.push_back(1.5 * l2 / pair);
      hinge_area += pair / 3.0;
    }
    a = b;
  }

  Eigen::Vector3d u, v;
  const bool planar = planar_frame(surface.nodes, &u, &v);
  const double largest = planar ? calibrate_planar_springs(s, u, v, area, material.youngs_modulus)
                                : calibrate_curved_springs(s, area, material.youngs_modulus);
  const double spring_speed = c * std::sqrt(largest);  // the fastest spring's sqrt(k L / m)
  if (!s.hinges.empty()) {
    calibrate_hinges(kb, maps, hinge_area, planar, u, v);
    for (std::size_t h = 0; h < s.hinges.size(); ++h) {
      s.hinges[h].stiffness = bending_stiffness * kb[h];
      if (!std::isfinite(s.hinges[h].stiffness))
        throw MaterialError(
            "make_sheet: bending stiffness D = " + std::to_string(bending_stiffness) +
            " N m gives a hinge stiffness that is not finite; choose a smaller D");
    }
  }
  // the CFL limit L_min / wave_speed covers springs and hinges (bending.hpp)
  s.wave_speed = std::hypot(spring_speed, 0.5 * bending_frequency_bound(s) * min_rest_length(s));
  return s;
}

double SheetBending::cylindrical_stiffness_along(const Eigen::Vector2d& d) const {
  const Eigen::Vector3d k(d(0) * d(0), d(1) * d(1), std::sqrt(2.0) * d(0) * d(1));
  return k.dot(tensor * k);
}

double SheetBending::beam_stiffness_along(const Eigen::Vector2d& d) const {
  const Eigen::Vector3d k(d(0) * d(0), d(1) * d(1), std::sqrt(2.0) * d(0) * d(1));
  return 1.0 / k.dot(tensor.ldlt().solve(k));
}

SheetBending sheet_bending(const MassSpringSystem<3>& s, const TriangleSurface& rest,
                           const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  if (std::abs(u.norm() - 1.0) > 1e-12 || std::abs(v.norm() - 1.0) > 1e-12 ||
      std::abs(u.dot(v)) > 1e-12)
    throw std::invalid_argument("sheet_bending: u and v must be orthonormal");
  if (rest.nodes.cols() != s.num_nodes())
    throw std::invalid_argument("sheet_bending: the rest surface has " +
                                std::to_string(rest.nodes.cols()) + " nodes, the sheet " +
                                std::to_string(s.num_nodes()));
  SheetBending out;
  double area = 0.0;  // the hinges' thirds of their two triangles
  for (const Hinge& h : s.hinges) {
    if (!hinge_active(s, h)) continue;
    const auto x = [&](int k) -> Eigen::Vector3d { return rest.nodes.col(h.nodes[k]); };
    const Eigen::Vector3d m = in_plane(curvature_map(x(0), x(1), x(2), x(3)), u, v);
    out.tensor += (2.0 * h.stiffness) * m * m.transpose();
    const Eigen::Vector3d e = x(1) - x(0);
    area += (e.cross(x(2) - x(0)).norm() + e.cross(x(3) - x(0)).norm()) / 6.0;
  }
  if (area > 0.0) out.tensor /= area;
  // isotropic part a I + c J (a = 2 mu, c = lambda), fitted in the Frobenius norm
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  j.topLeftCorner<2, 2>().setOnes();
  const double trace = out.tensor.trace(), sum = out.tensor.topLeftCorner<2, 2>().sum();
  const double a = (4.0 * trace - 2.0 * sum) / 8.0, lambda = (3.0 * sum - 2.0 * trace) / 8.0;
  out.stiffness = a + lambda;
  if (!(out.stiffness > 0.0)) return out;  // no active hinge
  out.poisson_ratio = lambda / out.stiffness;
  const Eigen::Matrix3d iso = a * Eigen::Matrix3d::Identity() + lambda * j;
  out.anisotropy = (out.tensor - iso).norm() / iso.norm();
  return out;
}

}  // namespace gencoord::deformable
