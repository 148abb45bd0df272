// SPDX-License-Identifier: BSD-3-Clause
// Kernels cut into parts (python/gencoord/optimize/split.py) compute what the whole kernels
// compute.
//
// The build generates double_pendulum (flat derivation) and n_link_chain_5 (structured
// derivation, forward-mode Jacobians) a second time with --max-function-statements 3, so
// every kernel of every kind is split into many parts that pass values through `carried`
// (scalar, vector and std::array results, out-parameters, symmetric blocks, Jacobians).
// Those headers are included inside namespace `split`, after the standard and Eigen headers
// they include, so both versions of each model live in one program.
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

namespace split {
#include "split/generated/double_pendulum.hpp"  // NOLINT(build/include): on purpose
#include "split/generated/n_link_chain_5.hpp"   // NOLINT(build/include)
}  // namespace split

namespace gencoord::testing {
namespace {

TEST(SplitKernels, DoublePendulumPartsComputeTheWholeKernels) {
  check_every_kernel<models::DoublePendulum, split::gencoord::models::DoublePendulum>();
}

TEST(SplitKernels, FiveLinkChainPartsComputeTheWholeKernels) {
  check_every_kernel<models::NLinkChain5, split::gencoord::models::NLinkChain5>();
}

}  // namespace
}  // namespace gencoord::testing
