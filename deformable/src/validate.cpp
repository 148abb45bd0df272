// SPDX-License-Identifier: BSD-3-Clause
// Checks of meshes, materials, objects and step sizes; each refusal names what it refuses.
#include "gencoord/deformable/validate.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "gencoord/errors.hpp"
#include "message.hpp"
#include "pi.hpp"
#include "simplex_shape.hpp"

namespace gencoord::deformable {

namespace {

using detail::message;

bool finite_non_negative(double x) { return std::isfinite(x) && x >= 0.0; }

// an element's nodes distinct and in range, its edges the springs joining them; `kind` and
// `index` name it ("volume term" 3)
template <int Dim, class Element>
void validate_element_nodes(const MassSpringSystem<Dim>& s, const Element& element,
                            const char* kind, int index) {
  const int count = s.num_nodes();
  const int springs = static_cast<int>(s.springs.size());
  for (int node : element.nodes) {
    if (node < 0 || node >= count)
      throw ObjectError(message("mass-spring object: ", kind, " ", index, " refers to node ", node,
                                ", out of range [0, ", count, ")"),
                        -1, -1);
  }
  int edge = 0;
  for (int a = 0; a < Element::kNodes; ++a) {
    for (int b = a + 1; b < Element::kNodes; ++b, ++edge) {
      const int k = element.springs[edge];
      const int i = element.nodes[a], j = element.nodes[b];
      const bool joins = k >= 0 && k < springs &&
                         ((s.springs[k].i == i && s.springs[k].j == j) ||
                          (s.springs[k].i == j && s.springs[k].j == i));
      if (i == j || !joins)
        throw ObjectError(
            message("mass-spring object: ", kind, " ", index, "'s edge (", i, ", ", j,
                    ") names spring ", k, ", which does not join those two distinct nodes"),
            i, k >= 0 && k < springs ? k : -1);
    }
  }
}

// each term's nodes and edges, V0 > 0, kappa >= 0
template <int Dim>
void validate_volume_terms(const MassSpringSystem<Dim>& s) {
  for (int t = 0; t < static_cast<int>(s.volume_terms.size()); ++t) {
    const VolumeTerm<Dim>& term = s.volume_terms[t];
    validate_element_nodes(s, term, "volume term", t);
    if (!(std::isfinite(term.rest_measure) && term.rest_measure > 0.0) ||
        !finite_non_negative(term.stiffness))
      throw ObjectError(message("mass-spring object: volume term ", t, " has rest measure ",
                                term.rest_measure, " and stiffness ", term.stiffness,
                                "; need a positive, finite measure and a finite stiffness >= 0"),
                        term.nodes[0], -1);
  }
}

// Dm^-1 of a linear element, the shape-function gradients of a quadratic one
template <int Dim>
bool rest_shape_finite(const ContinuumElement<Dim>& element) {
  return element.rest_inverse.allFinite();
}
template <int Dim>
bool rest_shape_finite(const QuadraticElement<Dim>& element) {
  for (const auto& point : element.gradients)
    for (const auto& g : point)
      if (!g.allFinite()) return false;
  return true;
}

// an element's nodes and edges, V0 > 0, a finite rest shape, mu, lambda, beta >= 0
template <int Dim, class Element>
void validate_continuum_element(const MassSpringSystem<Dim>& s, const Element& element,
                                const char* kind, int t) {
  validate_element_nodes(s, element, kind, t);
  if (!(std::isfinite(element.rest_measure) && element.rest_measure > 0.0) ||
      !rest_shape_finite(element) || !finite_non_negative(element.mu) ||
      !finite_non_negative(element.lambda) || !finite_non_negative(element.damping_time))
    throw ObjectError(
        message("mass-spring object: ", kind, " ", t, " has rest measure ", element.rest_measure,
                ", mu ", element.mu, ", lambda ", element.lambda, " and damping time ",
                element.damping_time,
                "; need a positive, finite measure, a finite rest shape and finite constants "
                ">= 0"),
        element.nodes[0], -1);
}

// each element's nodes and edges, V0 > 0, a finite rest shape, mu, lambda, beta >= 0
template <int Dim>
void validate_continuum_elements(const MassSpringSystem<Dim>& s) {
  if (Dim == 1 && !(s.elements.empty() && s.quadratic_elements.empty()))
    throw ObjectError(
        message("mass-spring object: ", s.elements.size() + s.quadratic_elements.size(),
                " continuum elements in 1D; they exist in 2D and 3D"),
        -1, -1);
  for (int t = 0; t < static_cast<int>(s.elements.size()); ++t)
    validate_continuum_element(s, s.elements[t], "continuum element", t);
  for (int t = 0; t < static_cast<int>(s.quadratic_elements.size()); ++t)
    validate_continuum_element(s, s.quadratic_elements[t], "quadratic element", t);
}

using detail::kPi;

}  // namespace

void validate_material(const Material& m) {
  if (!(std::isfinite(m.youngs_modulus) && m.youngs_modulus > 0.0))
    throw MaterialError(message("material: Young's modulus E = ", m.youngs_modulus,
                                " must be positive and finite"));
  if (!(std::isfinite(m.density) && m.density > 0.0))
    throw MaterialError(
        message("material: density rho = ", m.density, " must be positive and finite"));
  if (!finite_non_negative(m.damping))
    throw MaterialError(
        message("material: damping D = ", m.damping, " must be non-negative and finite"));
}

namespace {

// the checks of validate_mesh() on a linear or quadratic mesh: the shape is the corners'
template <int Dim, class Mesh>
void validate_any_mesh(const Mesh& mesh) {
  const int count = static_cast<int>(mesh.nodes.cols());
  if (count == 0 || mesh.elements.empty())
    throw MeshError(message("mesh: ", count, " nodes and ", mesh.elements.size(),
                            " elements; need at least one element"),
                    -1, -1);
  for (int n = 0; n < count; ++n) {
    if (!mesh.nodes.col(n).allFinite())
      throw MeshError(message("mesh: node ", n, " has a coordinate that is not finite (",
                              mesh.nodes.col(n).transpose(), ")"),
                      -1, n);
  }
  std::vector<char> used(count, 0);
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const auto& el = mesh.elements[e];
    for (int a = 0; a < static_cast<int>(el.size()); ++a) {
      if (el[a] < 0 || el[a] >= count)
        throw MeshError(message("mesh: element ", e, " refers to node ", el[a],
                                ", out of range (the mesh has ", count, " nodes)"),
                        e, el[a]);
      for (int b = 0; b < a; ++b) {
        if (el[a] == el[b])
          throw MeshError(message("mesh: element ", e, " repeats node ", el[a]), e, el[a]);
      }
      used[el[a]] = 1;
    }
    Eigen::Matrix<double, Dim, Dim> edges;
    for (int c = 0; c < Dim; ++c) edges.col(c) = mesh.nodes.col(el[c + 1]) - mesh.nodes.col(el[0]);
    const std::string problem = detail::shape_problem(detail::simplex_shape<Dim>(edges), "nodes");
    if (!problem.empty()) throw MeshError(message("mesh: element ", e, " ", problem), e, -1);
  }
  for (int n = 0; n < count; ++n) {
    if (!used[n])
      throw MeshError(
          message("mesh: node ", n, " belongs to no element, so it would get no mass; remove it"),
          -1, n);
  }
}

}  // namespace

template <int Dim>
void validate_mesh(const SimplexMesh<Dim>& mesh) {
  validate_any_mesh<Dim>(mesh);
}

template <int Dim>
void validate_mesh(const QuadraticMesh<Dim>& mesh) {
  validate_any_mesh<Dim>(mesh);
  // (corner, corner, midpoint, element) of every edge, to find edges given two midpoints
  std::vector<std::array<int, 4>> edges;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const auto& el = mesh.elements[e];
    int m = Dim + 1;
    for (int a = 0; a <= Dim; ++a) {
      for (int b = a + 1; b <= Dim; ++b, ++m) {
        const auto middle = 0.5 * (mesh.nodes.col(el[a]) + mesh.nodes.col(el[b]));
        const double edge = (mesh.nodes.col(el[b]) - mesh.nodes.col(el[a])).norm();
        if (!((mesh.nodes.col(el[m]) - middle).norm() <= kMaxRelativeMidpointOffset * edge))
          throw MeshError(message("mesh: element ", e, "'s node ", el[m],
                                  " is not at the middle of its edge (", el[a], ", ", el[b],
                                  "); curved quadratic elements are not supported: place it "
                                  "at the middle"),
                          e, el[m]);
        edges.push_back({std::min(el[a], el[b]), std::max(el[a], el[b]), el[m], e});
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 1; k < edges.size(); ++k) {
    const auto &p = edges[k - 1], &q = edges[k];
    if (p[0] == q[0] && p[1] == q[1] && p[2] != q[2])
      throw MeshError(message("mesh: elements ", p[3], " and ", q[3], " give their shared edge (",
                              p[0], ", ", p[1], ") different midpoint nodes, ", p[2], " and ", q[2],
                              ", which leaves a crack between them; share one node"),
                      q[3], q[2]);
  }
}

namespace {

// the contact settings, obstacles and surface of an object with `count` nodes
template <int Dim>
void validate_collisions(const Collisions<Dim>& c, int count) {
  const ContactParams& p = c.params;
  if (!finite_non_negative(p.omega) || !finite_non_negative(p.damping_ratio) ||
      !finite_non_negative(p.friction) || !finite_non_negative(p.thickness))
    throw ObjectError(message("mass-spring object: contact omega ", p.omega, ", damping ratio ",
                              p.damping_ratio, ", friction ", p.friction, ", thickness ",
                              p.thickness, "; each must be finite and >= 0"),
                      -1, -1);
  for (std::size_t k = 0; k < c.spheres.size(); ++k) {
    const auto& sphere = c.spheres[k];
    if (!sphere.center.allFinite() || !(std::isfinite(sphere.radius) && sphere.radius > 0.0))
      throw ObjectError(message("mass-spring object: sphere obstacle ", k, " has centre (",
                                sphere.center.transpose(), ") and radius ", sphere.radius,
                                "; need a finite centre and a positive, finite radius"),
                        -1, -1);
  }
  for (std::size_t k = 0; k < c.boxes.size(); ++k) {
    const auto& box = c.boxes[k];
    if (!box.lower.allFinite() || !box.upper.allFinite() ||
        !(box.lower.array() < box.upper.array()).all())
      throw ObjectError(message("mass-spring object: box obstacle ", k, " spans (",
                                box.lower.transpose(), ") to (", box.upper.transpose(),
                                "); need finite corners with lower < upper on every axis"),
                        -1, -1);
  }
  if (!c.two_sided.empty() && c.two_sided.size() != c.surface.size())
    throw ObjectError(message("mass-spring object: ", c.two_sided.size(), " sidedness flags for ",
                              c.surface.size(),
                              " contact surface simplices; give one per simplex "
                              "or none"),
                      -1, -1);
  if (!c.surface_thickness.empty() && c.surface_thickness.size() != c.surface.size())
    throw ObjectError(
        message("mass-spring object: ", c.surface_thickness.size(), " thicknesses for ",
                c.surface.size(), " contact surface simplices; give one per simplex or none"),
        -1, -1);
  for (std::size_t k = 0; k < c.surface_thickness.size(); ++k) {
    if (!finite_non_negative(c.surface_thickness[k]))
      throw ObjectError(
          message("mass-spring object: contact surface simplex ", k, " has thickness ",
                  c.surface_thickness[k], "; it must be finite and >= 0"),
          -1, -1);
  }
  for (std::size_t k = 0; k < c.surface.size(); ++k) {
    for (int a = 0; a < Dim; ++a) {
      const int n = c.surface[k][a];
      bool repeated = false;
      for (int b = a + 1; b < Dim; ++b) repeated = repeated || c.surface[k][b] == n;
      if (n < 0 || n >= count || repeated)
        throw ObjectError(message("mass-spring object: contact surface simplex ", k, " has node ",
                                  n, (repeated ? " twice" : ""), "; the object has ", count,
                                  " nodes, and each simplex needs distinct ones"),
                          -1, -1);
    }
  }
}

}  // namespace

void validate_surface(const TriangleSurface& surface) {
  const int count = static_cast<int>(surface.nodes.cols());
  const int triangles = static_cast<int>(surface.triangles.size());
  if (count == 0 || triangles == 0)
    throw MeshError(message("surface: ", count, " nodes and ", triangles,
                            " triangles; need at least one triangle"),
                    -1, -1);
  for (int n = 0; n < count; ++n) {
    if (!surface.nodes.col(n).allFinite())
      throw MeshError(message("surface: node ", n, " has a coordinate that is not finite (",
                              surface.nodes.col(n).transpose(), ")"),
                      -1, n);
  }
  std::vector<char> used(count, 0);
  // (i, j, k) sorted with its triangle; then each edge (i < j) with its triangle
  std::vector<std::array<int, 4>> sorted_triangles;
  std::vector<std::array<int, 3>> edges;
  for (int t = 0; t < triangles; ++t) {
    const auto& tri = surface.triangles[t];
    for (int a = 0; a < 3; ++a) {
      if (tri[a] < 0 || tri[a] >= count)
        throw MeshError(message("surface: triangle ", t, " refers to node ", tri[a],
                                ", out of range (the surface has ", count, " nodes)"),
                        t, tri[a]);
      for (int b = 0; b < a; ++b) {
        if (tri[a] == tri[b])
          throw MeshError(message("surface: triangle ", t, " repeats node ", tri[a]), t, tri[a]);
      }
      used[tri[a]] = 1;
    }
    const Eigen::Vector3d x0 = surface.nodes.col(tri[0]);
    const Eigen::Vector3d e1 = surface.nodes.col(tri[1]) - x0, e2 = surface.nodes.col(tri[2]) - x0;
    const std::string problem = detail::shape_problem(detail::triangle_shape(e1, e2), "nodes");
    if (!problem.empty()) throw MeshError(message("surface: triangle ", t, " ", problem), t, -1);
    std::array<int, 3> nodes = tri;
    std::sort(nodes.begin(), nodes.end());
    sorted_triangles.push_back({nodes[0], nodes[1], nodes[2], t});
    for (int a = 0; a < 3; ++a) {
      for (int b = a + 1; b < 3; ++b) edges.push_back({nodes[a], nodes[b], t});
    }
  }
  std::sort(sorted_triangles.begin(), sorted_triangles.end());
  for (std::size_t k = 1; k < sorted_triangles.size(); ++k) {
    const auto& p = sorted_triangles[k - 1];
    const auto& q = sorted_triangles[k];
    if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2])
      throw MeshError(message("surface: triangles ", p[3], " and ", q[3], " have the same nodes (",
                              p[0], ", ", p[1], ", ", p[2], "); remove one"),
                      q[3], -1);
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 2; k < edges.size(); ++k) {
    if (edges[k][0] == edges[k - 2][0] && edges[k][1] == edges[k - 2][1])
      throw MeshError(
          message("surface: the edge (", edges[k][0], ", ", edges[k][1], ") borders triangles ",
                  edges[k - 2][2], ", ", edges[k - 1][2], " and ", edges[k][2],
                  "; a sheet's edge may border at most two triangles"),
          edges[k][2], edges[k][0]);
  }
  for (int n = 0; n < count; ++n) {
    if (!used[n])
      throw MeshError(message("surface: node ", n,
                              " belongs to no triangle, so it would get no mass; remove it"),
                      -1, n);
  }
}

template <int Dim>
void validate_object(const MassSpringSystem<Dim>& s) {
  const int count = s.num_nodes();
  if (s.v.cols() != count || s.mass.size() != count || static_cast<int>(s.pinned.size()) != count)
    throw ObjectError(message("mass-spring object: sizes disagree: x has ", count, " nodes, v ",
                              s.v.cols(), ", mass ", s.mass.size(), ", pinned ", s.pinned.size()),
                      -1, -1);
  for (int n = 0; n < count; ++n) {
    const double m = s.mass(n);
    if (!(std::isfinite(m) && (m > 0.0 || (s.pinned[n] && m == 0.0))))
      throw ObjectError(message("mass-spring object: node ", n, " has mass ", m,
                                "; a free node needs a positive, finite mass"),
                        n, -1);
    if (!s.x.col(n).allFinite() || !s.v.col(n).allFinite())
      throw ObjectError(
          message("mass-spring object: node ", n,
                  " has a position or velocity that is not finite (x = ", s.x.col(n).transpose(),
                  ", v = ", s.v.col(n).transpose(), ") at t = ", s.t),
          n, -1);
  }
  for (int k = 0; k < static_cast<int>(s.springs.size()); ++k) {
    const Spring& sp = s.springs[k];
    if (sp.broken) continue;
    if (sp.i < 0 || sp.i >= count || sp.j < 0 || sp.j >= count || sp.i == sp.j)
      throw ObjectError(message("mass-spring object: spring ", k, " joins nodes ", sp.i, " and ",
                                sp.j, "; need two distinct nodes in [0, ", count, ")"),
                        -1, k);
    const SpringParams& p = sp.params;
    if (!(std::isfinite(p.rest_length) && p.rest_length > 0.0))
      throw ObjectError(
          message("mass-spring object: spring ", k, " (nodes ", sp.i, ", ", sp.j,
                  ") has rest length ", p.rest_length, "; need a positive, finite length"),
          -1, k);
    if (!finite_non_negative(p.stiffness) || !finite_non_negative(p.damping))
      throw ObjectError(message("mass-spring object: spring ", k, " (nodes ", sp.i, ", ", sp.j,
                                ") has stiffness ", p.stiffness, " and damping ", p.damping,
                                "; both must be non-negative and finite"),
                        -1, k);
  }
  validate_volume_terms(s);
  validate_continuum_elements(s);
  if (Dim != 3 && !s.hinges.empty())
    throw ObjectError(message("mass-spring object: ", s.hinges.size(), " hinges in ", Dim,
                              "D; bending hinges exist only in 3D"),
                      -1, -1);
  const int spring_count = static_cast<int>(s.springs.size());
  for (int k = 0; k < static_cast<int>(s.hinges.size()); ++k) {
    const Hinge& h = s.hinges[k];
    bool distinct = true;
    for (int a = 0; a < 4; ++a) {
      if (h.nodes[a] < 0 || h.nodes[a] >= count)
        throw ObjectError(message("mass-spring object: hinge ", k, " refers to node ", h.nodes[a],
                                  "; need nodes in [0, ", count, ")"),
                          h.nodes[a], -1);
      for (int b = 0; b < a; ++b) distinct = distinct && h.nodes[a] != h.nodes[b];
    }
    if (!distinct)
      throw ObjectError(
          message("mass-spring object: hinge ", k, " has nodes ", h.nodes[0], ", ", h.nodes[1],
                  ", ", h.nodes[2], ", ", h.nodes[3], "; need four distinct nodes"),
          h.nodes[0], -1);
    if (h.spring < -1 || h.spring >= spring_count)
      throw ObjectError(message("mass-spring object: hinge ", k, " refers to spring ", h.spring,
                                "; need -1 (none) or a spring in [0, ", spring_count, ")"),
                        -1, h.spring);
    if (!finite_non_negative(h.stiffness) || !(std::abs(h.rest_angle) <= kPi))
      throw ObjectError(message("mass-spring object: hinge ", k, " has stiffness ", h.stiffness,
                                " and rest angle ", h.rest_angle,
                                "; need a finite stiffness >= 0 and a rest angle in [-pi, pi]"),
                        -1, -1);
  }
  if (!s.gravity.allFinite())
    throw ObjectError(
        message("mass-spring object: gravity (", s.gravity.transpose(), ") is not finite"), -1, -1);
  if (!(std::isfinite(s.wave_speed) && s.wave_speed > 0.0))
    throw ObjectError(
        message("mass-spring object: wave speed ", s.wave_speed, " must be positive and finite"),
        -1, -1);
  if (s.ground && (!std::isfinite(s.ground->height) || !finite_non_negative(s.ground->omega) ||
                   !finite_non_negative(s.ground->damping_ratio)))
    throw ObjectError(message("mass-spring object: ground height ", s.ground->height, ", omega ",
                              s.ground->omega, ", damping ratio ", s.ground->damping_ratio,
                              "; need a finite height and finite omega and damping >= 0"),
                      -1, -1);
  if (s.collisions) validate_collisions(*s.collisions, s.num_nodes());
  const InelasticParams& in = s.inelastic;
  if (std::isnan(in.fracture_strain) || std::isnan(in.yield_strain) ||
      !(in.plastic_fraction >= 0.0 && in.plastic_fraction <= 1.0))
    throw ObjectError(
        message("mass-spring object: fracture strain ", in.fracture_strain, ", yield strain ",
                in.yield_strain, ", plastic fraction ", in.plastic_fraction,
                "; the strains must not be NaN, the fraction in [0, 1]"),
        -1, -1);
}

void validate_time_step(double dt) {
  if (!(std::isfinite(dt) && dt > 0.0))
    throw gencoord::StepSizeError(
        message("mass-spring time step: dt = ", dt, " must be positive and finite"));
}

template <int Dim>
void validate_step_result(const typename MassSpringSystem<Dim>::Points& x,
                          const typename MassSpringSystem<Dim>::Points& v, double t, double dt) {
  for (int n = 0; n < static_cast<int>(x.cols()); ++n) {
    if (!x.col(n).allFinite() || !v.col(n).allFinite())
      throw ObjectError(
          message("mass-spring object: the step of dt = ", dt, " from t = ", t, " diverged: node ",
                  n, " ends at x = ", x.col(n).transpose(), ", v = ", v.col(n).transpose(),
                  "; take a smaller step (the object is left as it was)"),
          n, -1);
  }
}

template void validate_mesh<2>(const SimplexMesh<2>&);
template void validate_mesh<3>(const SimplexMesh<3>&);
template void validate_mesh<2>(const QuadraticMesh<2>&);
template void validate_mesh<3>(const QuadraticMesh<3>&);
template void validate_object<1>(const MassSpringSystem<1>&);
template void validate_object<2>(const MassSpringSystem<2>&);
template void validate_object<3>(const MassSpringSystem<3>&);
#define GENCOORD_INSTANTIATE(D)                                             \
  template void validate_step_result<D>(const MassSpringSystem<D>::Points&, \
                                        const MassSpringSystem<D>::Points&, double, double);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
