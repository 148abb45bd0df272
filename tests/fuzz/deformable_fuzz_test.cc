// SPDX-License-Identifier: BSD-3-Clause
// Random meshes, materials, rods and step sizes to the deformable library: construction
// either refuses with a typed error (MeshError, MaterialError) or gives an object whose masses
// and springs are usable; a step either refuses with a typed error (StepSizeError,
// CflViolation, ObjectError, LinearSolveError) or leaves a finite object at t + dt whose energy
// has not blown up when the step was within the CFL limit.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_values.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/errors.hpp"

namespace gencoord::deformable {
namespace {

using fuzz::Values;

struct Outcomes {
  int built = 0, refused_build = 0, stepped = 0, refused_step = 0;
};

Material random_material(Values& values) {
  Material m;
  m.youngs_modulus = values.maybe_bad_positive(1.0, 0.1);
  m.density = values.maybe_bad_positive(1.0, 0.1);
  m.damping = values.chance(0.5) ? 0.0 : values.maybe_bad_positive(0.01, 0.1);
  return m;
}

// a small procedural mesh of random size, its nodes jittered, sometimes spoiled
template <int Dim>
SimplexMesh<Dim> jittered_mesh(Values& values) {
  SimplexMesh<Dim> mesh;
  if constexpr (Dim == 2) {
    mesh =
        rectangle_mesh(values.maybe_bad_positive(1.0, 0.05), values.maybe_bad_positive(1.0, 0.05),
                       values.integer(1, 3), values.integer(1, 3));
  } else {
    mesh = box_mesh(values.maybe_bad_positive(1.0, 0.05), 1.0, values.maybe_bad_positive(1.0, 0.05),
                    values.integer(1, 2), 1, values.integer(1, 2));
  }
  const double jitter = values.chance(0.2) ? values.uniform(0.0, 2.0) : 0.1;
  for (int n = 0; n < mesh.nodes.cols(); ++n)
    for (int a = 0; a < Dim; ++a) mesh.nodes(a, n) += jitter * values.uniform(-0.1, 0.1);
  if (values.chance(0.05))
    mesh.nodes(0, values.integer(0, mesh.nodes.cols() - 1)) = values.maybe_bad(1.0, 1.0);
  if (values.chance(0.05))
    mesh.elements[values.integer(0, mesh.elements.size() - 1)][0] = values.integer(-5, 200);
  return mesh;
}

template <int Dim>
SimplexMesh<Dim> random_mesh(Values& values) {
  if (values.chance(0.5)) return jittered_mesh<Dim>(values);
  SimplexMesh<Dim> mesh;
  const int count = values.integer(0, 7);
  mesh.nodes.resize(Dim, count);
  for (int n = 0; n < count; ++n)
    for (int a = 0; a < Dim; ++a) mesh.nodes(a, n) = values.maybe_bad(1.0, 0.02);
  if (count > 0 && values.chance(0.05)) mesh.nodes.col(count - 1) = mesh.nodes.col(0);
  const int elements = values.integer(0, 5);
  for (int e = 0; e < elements; ++e) {
    std::array<int, Dim + 1> el;
    for (int a = 0; a <= Dim; ++a)
      el[a] = values.chance(0.03) ? values.integer(-2, count + 100) : values.integer(0, count - 1);
    mesh.elements.push_back(el);
  }
  return mesh;
}

// One step of a random kind and size on a valid object; checks the outcome.
template <int Dim>
void fuzz_step(Values& values, MassSpringSystem<Dim> s, Outcomes* out) {
  for (int n = 0; n < s.num_nodes(); ++n) {
    for (int a = 0; a < Dim; ++a) s.v(a, n) = values.uniform(-0.1, 0.1);
    if (values.chance(0.02)) s.x(0, n) = values.maybe_bad(1.0, 1.0);
  }
  if (values.chance(0.2)) s.pinned[values.integer(0, s.num_nodes() - 1)] = 1;
  if (values.chance(0.2)) s.gravity(Dim - 1) = -9.81;
  const double limit = cfl_limit(s);
  const double e0 = total_energy(s), t0 = s.t;
  const double dt = values.chance(0.5) ? values.uniform(0.01, 1.0) * limit : values.step_size();
  const int kind = values.integer(0, 3);
  const std::string what = "kind " + std::to_string(kind) + ", dt = " + std::to_string(dt) +
                           ", CFL limit " + std::to_string(limit) +
                           ", c = " + std::to_string(s.wave_speed) + ", masses from " +
                           std::to_string(s.mass.minCoeff()) + ", E0 = " + std::to_string(e0);
  try {
    if (kind == 0) {
      symplectic_euler_step(s, dt);
    } else if (kind == 1) {
      ExplicitOptions force;
      force.allow_cfl_violation = true;
      symplectic_euler_step(s, dt, force);
    } else {
      ImplicitOptions options;
      if (kind == 3) options.solver = LinearSolver::kSparseCholesky;
      backward_euler_step(s, dt, options);
    }
    ++out->stepped;
    EXPECT_TRUE(s.x.allFinite() && s.v.allFinite()) << what;
    EXPECT_EQ(s.t, t0 + dt) << what;
    // well inside the CFL limit one step cannot multiply the energy (no gravity: E >= 0)
    if (kind == 0 && s.gravity.isZero() && dt <= 0.5 * limit) {
      EXPECT_LE(total_energy(s), 4.0 * e0 + 1e-12) << what;
    }
  } catch (const StepSizeError&) {
    ++out->refused_step;
    EXPECT_FALSE(dt > 0.0 && std::isfinite(dt)) << what;
  } catch (const CflViolation&) {
    ++out->refused_step;
    EXPECT_EQ(kind, 0) << what;
  } catch (const ObjectError&) {
    ++out->refused_step;
  } catch (const LinearSolveError&) {
    ++out->refused_step;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": untyped error: " << e.what();
  }
}

template <int Dim>
void fuzz_meshes(std::uint64_t seed, int cases) {
  Values values(seed);
  Outcomes out;
  for (int c = 0; c < cases; ++c) {
    const SimplexMesh<Dim> mesh = random_mesh<Dim>(values);
    const Material material = random_material(values);
    try {
      const MassSpringSystem<Dim> s = make_mass_spring(mesh, material);
      ++out.built;
      for (int n = 0; n < s.num_nodes(); ++n)
        EXPECT_TRUE(std::isfinite(s.mass(n)) && s.mass(n) > 0.0) << "case " << c << " node " << n;
      for (const Spring& sp : s.springs)
        EXPECT_TRUE(sp.params.rest_length > 0.0 && std::isfinite(sp.params.stiffness))
            << "case " << c;
      fuzz_step(values, s, &out);
    } catch (const MeshError& e) {
      ++out.refused_build;
      // the element at fault is one of the mesh's (node() may be the out-of-range index itself)
      EXPECT_LT(e.element(), static_cast<int>(mesh.elements.size())) << "case " << c;
    } catch (const MaterialError&) {
      ++out.refused_build;
    }
  }
  std::printf("[ fuzz ] %dD meshes: %d built, %d refused; steps: %d taken, %d refused\n", Dim,
              out.built, out.refused_build, out.stepped, out.refused_step);
  EXPECT_GT(out.built, cases / 20);
  EXPECT_GT(out.refused_build, cases / 4);
  EXPECT_GT(out.stepped, 0);
  EXPECT_GT(out.refused_step, 0);
}

TEST(DeformableFuzz, TriangleMeshes) { fuzz_meshes<2>(11, 1500); }
TEST(DeformableFuzz, TetrahedronMeshes) { fuzz_meshes<3>(12, 1500); }

TEST(DeformableFuzz, Rods) {
  Values values(13);
  Outcomes out;
  for (int c = 0; c < 1000; ++c) {
    std::vector<double> p;
    double x = values.uniform(-1.0, 1.0);
    const int count = values.integer(0, 6);
    for (int i = 0; i < count; ++i) {
      p.push_back(values.chance(0.03) ? values.maybe_bad(1.0, 1.0) : x);
      x += values.chance(0.03) ? values.maybe_bad(0.1, 1.0) : values.uniform(0.01, 0.5);
    }
    try {
      const MassSpringSystem<1> rod = make_rod(p, random_material(values));
      ++out.built;
      for (int n = 0; n < rod.num_nodes(); ++n) EXPECT_GT(rod.mass(n), 0.0) << "case " << c;
      fuzz_step(values, rod, &out);
    } catch (const MeshError&) {
      ++out.refused_build;
    } catch (const MaterialError&) {
      ++out.refused_build;
    }
  }
  std::printf("[ fuzz ] rods: %d built, %d refused; steps: %d taken, %d refused\n", out.built,
              out.refused_build, out.stepped, out.refused_step);
  EXPECT_GT(out.built, 100);
  EXPECT_GT(out.refused_build, 50);
}

}  // namespace
}  // namespace gencoord::deformable
