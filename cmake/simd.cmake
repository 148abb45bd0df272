# SPDX-License-Identifier: BSD-3-Clause
# gencoord_enable_simd(TARGET): what gencoord/simd/ needs of a target that uses it. Where the
# compiler and the building machine both have AVX2 and FMA, -mavx2 -mfma (named flags, not
# -march=native, so that ccache never hands an object to another processor), so that a Pack<4>
# is one register; and libmvec, glibc's vector sin and cos, where it is found.
include_guard(GLOBAL)
include(CheckCXXSourceRuns)
include(CMakePushCheckState)

cmake_push_check_state(RESET)
set(CMAKE_REQUIRED_FLAGS "-mavx2 -mfma")
check_cxx_source_runs("
  #include <immintrin.h>
  int main() {
    if (!__builtin_cpu_supports(\"avx2\") || !__builtin_cpu_supports(\"fma\")) return 1;
    volatile double x = 1.0;
    __m256d a = _mm256_set1_pd(x);
    a = _mm256_fmadd_pd(a, a, a);
    return _mm256_cvtsd_f64(a) == 2.0 ? 0 : 1;
  }" GENCOORD_HAVE_AVX2)
cmake_pop_check_state()
find_library(GENCOORD_LIBMVEC NAMES mvec)

function(gencoord_enable_simd target)
  if(GENCOORD_HAVE_AVX2)
    target_compile_options(${target} PRIVATE -mavx2 -mfma)
  endif()
  _gencoord_link_libmvec(${target})
  if(NOT GENCOORD_LIBMVEC)
    target_compile_definitions(${target} PRIVATE GENCOORD_NO_LIBMVEC)
  endif()
endfunction()

# gencoord_enable_simd_source(TARGET SOURCE): the same for one source of TARGET alone, so that
# the target's other sources keep the baseline instruction set (and their scalar results).
# It is also built at -O3, which the packed kernels gain from (bench/python_simd_batch.py, the
# floating quadruped's qddot_simd: 743 ns per state at -O2, 452 ns at -O3).
function(gencoord_enable_simd_source target source)
  set(options -O3)
  if(GENCOORD_HAVE_AVX2)
    list(APPEND options -mavx2 -mfma)
  endif()
  set_source_files_properties("${source}" TARGET_DIRECTORY ${target} PROPERTIES
                              COMPILE_OPTIONS "${options}")
  if(NOT GENCOORD_LIBMVEC)
    set_source_files_properties("${source}" TARGET_DIRECTORY ${target} PROPERTIES
                                COMPILE_DEFINITIONS GENCOORD_NO_LIBMVEC)
  endif()
  _gencoord_link_libmvec(${target})
endfunction()

function(_gencoord_link_libmvec target)
  if(GENCOORD_LIBMVEC)
    target_link_libraries(${target} PRIVATE "${GENCOORD_LIBMVEC}")
  endif()
endfunction()
