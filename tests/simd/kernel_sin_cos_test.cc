// SPDX-License-Identifier: BSD-3-Clause
// The generated headers' batched sines and cosines, as the kernel objects compiled for AVX2
// (where the machine has it) evaluate them: within 4 ulp of std::sin and std::cos.
#include <gtest/gtest.h>

#include "kernel_sin_cos.hpp"

namespace gencoord::testing {
namespace {

TEST(KernelSinCos, WithinFourUlpAtTheSimdInstructionSet) {
  const KernelSinCosError worst = worst_kernel_sin_cos(3000);
  RecordProperty("worst_ulps", static_cast<int>(worst.ulps));
  EXPECT_LE(worst.ulps, 4);
  EXPECT_LE(worst.absolute, 1e-15);
#ifdef GENCOORD_KERNEL_LIBMVEC
  // libmvec rounds differently from libm somewhere: the vector path is the one taken
  EXPECT_GT(worst.inexact, 0);
#endif
}

}  // namespace
}  // namespace gencoord::testing
