// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/model/model_traits.hpp"

#include <gtest/gtest.h>

#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandCoupled;
using test_models::HandOscillator;
using test_models::HandPendulum;

// a model with one member hidden by a data member of the same name
struct PendulumWithoutEnergy : HandPendulum {
  static constexpr int energy = 0;
};
// sizes that contradict each other
struct PendulumWithBadDim : HandPendulum {
  static constexpr int dim = 4;
};
// coordinate_names of the wrong length
struct PendulumWithBadNames : HandPendulum {
  static constexpr std::array<const char*, 2> coordinate_names{{"a", "b"}};
};
// dynamics with the wrong signature (no output pointers)
struct PendulumWithBadDynamics : HandPendulum {
  static void dynamics(const QVector<double>&, const QVector<double>&, const double&,
                       const Params&) {}
};

TEST(ModelTraits, HandModelsSatisfyTheInterface) {
  static_assert(is_model_v<HandPendulum>);
  static_assert(is_model_v<HandOscillator>);
  static_assert(is_model_v<HandCoupled>);
  static_assert(assert_model_v<HandCoupled>);
  EXPECT_TRUE(is_model_v<HandPendulum>);
}

TEST(ModelTraits, DetectsMissingOrMalformedMembers) {
  static_assert(!is_model_v<int>);
  static_assert(!is_model_v<PendulumWithoutEnergy>);
  static_assert(!is_model_v<PendulumWithBadDim>);
  static_assert(!is_model_v<PendulumWithBadNames>);
  static_assert(!is_model_v<PendulumWithBadDynamics>);
  EXPECT_FALSE(is_model_v<PendulumWithoutEnergy>);
}

TEST(ModelTraits, AliasesAreTheModelsDoubleTypes) {
  static_assert(std::is_same_v<QVec<HandCoupled>, Eigen::Vector2d>);
  static_assert(std::is_same_v<QMat<HandCoupled>, Eigen::Matrix2d>);
  static_assert(std::is_same_v<XVec<HandCoupled>, Eigen::Vector3d>);
  static_assert(std::is_same_v<XJac<HandCoupled>, Eigen::Matrix<double, 3, 2>>);
  static_assert(std::is_same_v<ParamsOf<HandCoupled>, HandCoupled::Params>);
  SUCCEED();
}

}  // namespace
}  // namespace gencoord
