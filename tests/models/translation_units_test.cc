// SPDX-License-Identifier: BSD-3-Clause
// Kernels compiled in translation units of their own (./generate --translation-units)
// compute what the header-only kernels compute.
//
// The build generates double_pendulum and n_link_chain_5 a second time with
// --translation-units 3 and --max-function-statements 3 (gencoord_add_model's
// TRANSLATION_UNITS): every kernel's many parts are spread over three class templates,
// compiled for double only in <name>_double_{0,1,2}.cpp, which this program links. Those
// models keep their names, so this is a program of its own, and header-only versions cut
// the same way (the split-kernel test's) are included here inside namespace `whole`.
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <string_view>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_5.hpp"
#include "same_kernels.hpp"

namespace whole {
#include "split/generated/double_pendulum.hpp"  // NOLINT(build/include)
#include "split/generated/n_link_chain_5.hpp"   // NOLINT(build/include)
}  // namespace whole

namespace gencoord::testing {
namespace {

TEST(TranslationUnits, DoublePendulumLinkedPartsComputeTheHeaderOnlyKernels) {
  check_every_kernel<whole::gencoord::models::DoublePendulum, models::DoublePendulum>();
}

TEST(TranslationUnits, FiveLinkChainLinkedPartsComputeTheHeaderOnlyKernels) {
  check_every_kernel<whole::gencoord::models::NLinkChain5, models::NLinkChain5>();
}

TEST(TranslationUnits, FloatIsStillCompiledWhereItIsUsed) {
  // only double is compiled in the group files; float instantiates from the header
  using Chain = models::NLinkChain5;
  using Whole = whole::gencoord::models::NLinkChain5;
  Chain::QVector<float> q, v;
  for (int i = 0; i < Chain::nq; ++i) q[i] = 0.3f * i - 0.5f, v[i] = 0.1f * i;
  const Chain::QVector<float> a = Chain::qddot(q, v, 0.0f, Chain::Params{});
  const Whole::QVector<double> b =
      Whole::qddot(Whole::QVector<double>(q.cast<double>()),
                   Whole::QVector<double>(v.cast<double>()), 0.0, Whole::Params{});
  for (int i = 0; i < Chain::nq; ++i) {
    EXPECT_NEAR(a[i], b[i], 1e-3 * std::max(1.0, std::abs(b[i]))) << "qddot " << i;
  }
}

}  // namespace
}  // namespace gencoord::testing
