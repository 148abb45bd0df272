// SPDX-License-Identifier: BSD-3-Clause
#include "simplex_shape.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "gencoord/deformable/validate.hpp"

namespace gencoord::deformable::detail {

namespace {

const char* measure_name(int dim) { return dim == 1 ? "length" : dim == 2 ? "area" : "volume"; }

// The shape of a simplex from its edges, computed on the edges divided by their largest
// coordinate so that no square overflows or underflows; measure = scale^dim * unit measure.
template <class Edges, class UnitMeasure>
SimplexShape shape_of(const Edges& edges, int dim, UnitMeasure unit_measure) {
  SimplexShape shape;
  shape.dim = dim;
  const double scale = edges.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    shape.longest = scale;  // all corners at one point (0), or not finite
    return shape;
  }
  const Edges unit = edges / scale;
  double longest = 0.0;
  for (int a = 0; a < unit.cols(); ++a) {
    longest = std::max(longest, unit.col(a).norm());
    for (int b = a + 1; b < unit.cols(); ++b) {
      longest = std::max(longest, (unit.col(b) - unit.col(a)).norm());
    }
  }
  const double measure = unit_measure(unit);
  shape.longest = scale * longest;
  shape.measure = std::pow(scale, dim) * measure;
  shape.relative = measure / std::pow(longest, dim);
  return shape;
}

}  // namespace

template <int Dim>
SimplexShape simplex_shape(const Eigen::Matrix<double, Dim, Dim>& edges) {
  constexpr double factorial = Dim == 2 ? 2.0 : (Dim == 3 ? 6.0 : 1.0);
  return shape_of(edges, Dim, [](const Eigen::Matrix<double, Dim, Dim>& unit) {
    return std::abs(unit.determinant()) / factorial;
  });
}

SimplexShape triangle_shape(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  Eigen::Matrix<double, 3, 2> edges;
  edges << e1, e2;
  return shape_of(edges, 2, [](const Eigen::Matrix<double, 3, 2>& unit) {
    return 0.5 * unit.col(0).cross(unit.col(1)).norm();
  });
}

std::string shape_problem(const SimplexShape& shape, const char* corners, const char* remedy) {
  std::ostringstream what;
  const char* measure = measure_name(shape.dim);
  const bool representable = std::isfinite(shape.longest) && std::isfinite(shape.measure) &&
                             shape.measure >= std::numeric_limits<double>::min();
  if (std::isfinite(shape.longest) && !(shape.relative > kMinRelativeMeasure)) {
    what << "is degenerate: its " << measure << " " << shape.measure << " is not above "
         << kMinRelativeMeasure * std::pow(shape.longest, shape.dim) << " ("
         << static_cast<float>(kMinRelativeMeasure) << " times its longest edge to the power "
         << shape.dim << "); its " << corners << " are (nearly) "
         << (shape.dim == 2 ? "collinear" : "coplanar") << remedy;
  } else if (!representable) {
    what << "has " << (shape.dim == 2 ? "an " : "a ") << measure << " (" << shape.measure
         << ", its longest edge " << shape.longest
         << ") outside the range of a double; give its coordinates in metres "
         << "or rescale the mesh";
  }
  return what.str();
}

template SimplexShape simplex_shape<2>(const Eigen::Matrix<double, 2, 2>&);
template SimplexShape simplex_shape<3>(const Eigen::Matrix<double, 3, 3>&);

}  // namespace gencoord::deformable::detail
