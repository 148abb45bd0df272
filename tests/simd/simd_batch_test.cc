// SPDX-License-Identifier: BSD-3-Clause
// Pack<N> as the generated kernels' Scalar (gencoord/simd/): its sin, cos, tanh, exp and log
// within 4 ulp of std::'s, its arithmetic and other functions lane by lane as scalar code, and
// batch_qddot_simd()
// against the scalar batch on planar and 3D models, a 10-link chain, the 7-joint arm and the
// floating quadruped (unit quaternions), with a batch size that leaves a scalar tail, and a
// failing state that throws as the scalar batch does.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/errors.hpp"
#include "gencoord/parallel/batch.hpp"
#include "gencoord/simd/batch.hpp"
#include "gencoord/simd/pack.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/heavy_top.hpp"
#include "generated/iiwa14.hpp"
#include "generated/n_link_chain_10.hpp"
#include "ulp_distance.hpp"

namespace gencoord {
namespace {

using gencoord::testing::ulp_distance;

TEST(Pack, SinAndCosAreWithinFourUlp) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-50.0, 50.0);
  std::int64_t worst = 0;
  for (int round = 0; round < 20000; ++round) {
    const Pack<4> x = Pack<4>::generate([&](int) { return angle(rng); });
    const Pack<4> s = sin(x), c = cos(x);
    for (int k = 0; k < 4; ++k) {
      // near a zero an ulp of the result is tiny: compare there to an ulp of 1e-16
      const double fs = std::sin(x[k]), fc = std::cos(x[k]);
      if (std::abs(fs) > 1e-3) worst = std::max(worst, ulp_distance(s[k], fs));
      if (std::abs(fc) > 1e-3) worst = std::max(worst, ulp_distance(c[k], fc));
      EXPECT_NEAR(s[k], fs, 1e-15);
      EXPECT_NEAR(c[k], fc, 1e-15);
    }
  }
  RecordProperty("worst_ulps", static_cast<int>(worst));
  EXPECT_LE(worst, 4);
}

// tanh (a smooth joint friction's law), exp and log: through libmvec where it has them, over
// the arguments where each changes character (tanh's linear start and saturation, exp's
// underflow and large values, log near 1)
TEST(Pack, TanhExpAndLogAreWithinFourUlp) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> wide(-30.0, 30.0), exponent(-12.0, 12.0);
  std::int64_t worst = 0;
  for (int round = 0; round < 20000; ++round) {
    const Pack<4> x = Pack<4>::generate([&](int k) {
      return k < 2 ? wide(rng) : std::copysign(std::pow(10.0, exponent(rng)), wide(rng));
    });
    const Pack<4> positive = Pack<4>::generate([&](int k) { return std::abs(x[k]); });
    const Pack<4> t = tanh(x), e = exp(x), l = log(positive);
    for (int k = 0; k < 4; ++k) {
      worst = std::max(worst, ulp_distance(t[k], std::tanh(x[k])));
      worst = std::max(worst, ulp_distance(e[k], std::exp(x[k])));
      // near log's zero an ulp of the result is tiny: compare there to an ulp of 1e-16
      const double fl = std::log(positive[k]);
      if (std::abs(fl) > 1e-3) {
        worst = std::max(worst, ulp_distance(l[k], fl));
      } else {
        EXPECT_NEAR(l[k], fl, 1e-16);
      }
    }
  }
  RecordProperty("worst_ulps", static_cast<int>(worst));
  EXPECT_LE(worst, 4);
}

TEST(Pack, ArithmeticIsLaneByLane) {
  const Pack<4> a = Pack<4>::generate([](int k) { return 1.0 / (k + 3); });
  const Pack<4> b = Pack<4>::generate([](int k) { return -2.5 * k + 0.1; });
  const Pack<4> r = (a * b - b / a + 2.0) * -a;
  for (int k = 0; k < 4; ++k) EXPECT_EQ(r[k], (a[k] * b[k] - b[k] / a[k] + 2.0) * -a[k]);
  EXPECT_EQ(sqrt(a)[1], std::sqrt(a[1]));
  EXPECT_EQ(abs(b)[3], std::abs(b[3]));
}

// the compiler may call libmvec for a loop over lanes: a few ulp from the scalar function
TEST(Pack, EveryOtherFunctionOfTheKernelsIsWithinFourUlpOfTheScalarOne) {
  const Pack<4> x = Pack<4>::generate([](int k) { return 0.15 * k + 0.2; });  // in (0, 1)
  const Pack<4> y = Pack<4>::generate([](int k) { return 1.5 - 0.4 * k; });
  for (int k = 0; k < 4; ++k) {
    EXPECT_LE(ulp_distance(tan(x)[k], std::tan(x[k])), 4);
    EXPECT_LE(ulp_distance(asin(x)[k], std::asin(x[k])), 4);
    EXPECT_LE(ulp_distance(acos(x)[k], std::acos(x[k])), 4);
    EXPECT_LE(ulp_distance(atan(x)[k], std::atan(x[k])), 4);
    EXPECT_LE(ulp_distance(sinh(x)[k], std::sinh(x[k])), 4);
    EXPECT_LE(ulp_distance(cosh(x)[k], std::cosh(x[k])), 4);
    EXPECT_LE(ulp_distance(tanh(y)[k], std::tanh(y[k])), 4);
    EXPECT_LE(ulp_distance(exp(y)[k], std::exp(y[k])), 4);
    EXPECT_LE(ulp_distance(log(x)[k], std::log(x[k])), 4);
    EXPECT_LE(ulp_distance(cbrt(y)[k], std::cbrt(y[k])), 4);
    EXPECT_LE(ulp_distance(atan2(y, x)[k], std::atan2(y[k], x[k])), 4);
    EXPECT_LE(ulp_distance(pow(x, y)[k], std::pow(x[k], y[k])), 4);
  }
}

template <class M>
std::vector<State<M>> random_states(std::size_t count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<State<M>> states(count);
  for (auto& s : states) {
    for (int i = 0; i < M::nq; ++i) s.q[i] = 3.0 * unit(rng);
    for (int i = 0; i < nv_of_v<M>; ++i) s.v[i] = 2.0 * unit(rng);
    if constexpr (has_generalized_speeds_v<M>)
      for (const int start : M::quaternion_starts) s.q.template segment<4>(start).normalize();
    s.t = unit(rng);
  }
  return states;
}

template <class M>
class SimdBatch : public ::testing::Test {};
using Models = ::testing::Types<models::DoublePendulum, models::HeavyTop, models::NLinkChain10,
                                models::Iiwa14, models::FloatingQuadruped>;
TYPED_TEST_SUITE(SimdBatch, Models);

TYPED_TEST(SimdBatch, EqualsTheScalarBatchToRoundOff) {
  using M = TypeParam;
  const std::vector<State<M>> states = random_states<M>(203);  // 50 packs of 4 and a tail of 3
  const typename M::Params p;
  std::vector<VVec<M>> scalar, packed, wide;
  batch_qddot<M>(states, {p}, &scalar, 2);
  batch_qddot_simd<M>(states, p, &packed, 2);
  batch_qddot_simd<M, 8>(states, p, &wide, 1);
  ASSERT_EQ(packed.size(), states.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const double scale = std::max(1.0, scalar[i].norm());
    worst = std::max(
        {worst, (packed[i] - scalar[i]).norm() / scale, (wide[i] - scalar[i]).norm() / scale});
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", worst);
  ::testing::Test::RecordProperty("worst_relative_difference", text);
  EXPECT_LT(worst, 1e-11) << M::name;  // measured 7.8e-16 to 6.1e-13 (the top near gimbal lock)
}

TEST(SimdBatchErrors, AFailingStateThrowsAsTheScalarBatch) {
  using M = models::DoublePendulum;
  std::vector<State<M>> states = random_states<M>(8);
  states[5].q[0] = std::numeric_limits<double>::quiet_NaN();
  std::vector<VVec<M>> out;
  EXPECT_THROW(batch_qddot_simd<M>(states, M::Params{}, &out, 1), DynamicsError);
  EXPECT_THROW(batch_qddot<M>(states, {M::Params{}}, &out, 1), DynamicsError);
}

}  // namespace
}  // namespace gencoord
