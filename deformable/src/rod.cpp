// SPDX-License-Identifier: BSD-3-Clause
// The 1D elastic rod (deformable/docs/deformables.md) and some node layouts for it.
#include "gencoord/deformable/rod.hpp"

#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "gencoord/deformable/disk_sampling.hpp"
#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable {

MassSpringSystem<1> make_rod(const std::vector<double>& p, const Material& material) {
  const int count = static_cast<int>(p.size());
  if (count < 2) throw MeshError("make_rod: need at least two nodes", -1, -1);
  validate_material(material);
  // finite nodes, each spacing above a relative tolerance: every mass and length positive
  std::ostringstream os;
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(p[i])) {
      os << "make_rod: node " << i << " is not finite (" << p[i] << ")";
      throw MeshError(os.str(), -1, i);
    }
  }
  const double min_spacing = kMinRelativeLength * (p.back() - p.front());
  os.precision(17);
  for (int i = 0; i + 1 < count; ++i) {
    if (!(p[i + 1] - p[i] > min_spacing)) {
      os << "make_rod: element " << i << " (nodes " << i << ", " << i + 1 << ") goes from " << p[i]
         << " to " << p[i + 1] << "; nodes must increase by more than " << std::setprecision(3)
         << kMinRelativeLength << " times the rod's length";
      throw MeshError(os.str(), i, i + 1);
    }
  }
  const double rho = material.density;
  MassSpringSystem<1> s;
  s.x.resize(1, count);
  s.v = Eigen::Matrix<double, 1, Eigen::Dynamic>::Zero(1, count);
  s.mass.resize(count);
  s.pinned.assign(count, 0);
  for (int i = 0; i < count; ++i) {
    s.x(0, i) = p[i];
    // m_i = rho (p_{i+1} - p_{i-1}) / 2, with half intervals at the ends
    const double right = i + 1 < count ? p[i + 1] : p[i];
    const double left = i > 0 ? p[i - 1] : p[i];
    s.mass(i) = rho * (right - left) / 2.0;
  }
  for (int i = 0; i + 1 < count; ++i) {
    Spring sp;
    sp.i = i;
    sp.j = i + 1;
    sp.params.rest_length = p[i + 1] - p[i];
    sp.params.stiffness = material.youngs_modulus;  // k = E: force per unit strain
    sp.params.damping = material.damping;
    s.springs.push_back(sp);
  }
  s.wave_speed = material.wave_speed();
  return s;
}

std::vector<double> uniform_rod_nodes(int n, double length) {
  std::vector<double> p(n + 1);
  for (int i = 0; i <= n; ++i) p[i] = length * i / n;
  return p;
}

namespace {
// cumulative sums of the spacings, rescaled to end exactly at `length`
std::vector<double> nodes_from_spacings(const std::vector<double>& h, double length) {
  double total = 0.0;
  for (double hi : h) total += hi;
  std::vector<double> p(h.size() + 1, 0.0);
  double acc = 0.0;
  for (size_t i = 0; i < h.size(); ++i) {
    acc += h[i];
    p[i + 1] = length * acc / total;
  }
  p.back() = length;
  return p;
}
}  // namespace

std::vector<double> jittered_rod_nodes(int n, double jitter, std::uint64_t seed, double length) {
  std::mt19937_64 rng(seed);
  std::vector<double> h(n);
  for (double& hi : h) hi = 1.0 + jitter * (2.0 * uniform01(rng) - 1.0);
  return nodes_from_spacings(h, length);
}

std::vector<double> graded_rod_nodes(int n, double ratio, double length) {
  std::vector<double> h(n);
  for (int i = 0; i < n; ++i) h[i] = std::pow(ratio, i);
  return nodes_from_spacings(h, length);
}

}  // namespace gencoord::deformable
