# SPDX-License-Identifier: BSD-3-Clause
# gencoord_enable_simd(TARGET): what gencoord/simd/ needs of a target that uses it. Where the
# compiler and the building machine both have AVX2 and FMA, -mavx2 -mfma (named flags, not
# -march=native, so that ccache never hands an object to another processor), so that a Pack<4>
# is one register; and libmvec, glibc's vector sin and cos, where it is found.
# gencoord_enable_avx2_kernels(TARGET): the same instruction sets for a model's kernel objects,
# and AVX-512 F and VL besides where the building machine has them.
include_guard(GLOBAL)
include(CheckCXXSourceRuns)
include(CMakePushCheckState)

# _gencoord_isa_runs(VAR FLAGS FEATURES OPERATION): VAR is true where code compiled with FLAGS
# runs on the building machine: it reports each of FEATURES, and OPERATION on the __m256d
# a = (1, 1, 1, 1) leaves 2 in the lowest lane.
function(_gencoord_isa_runs var flags features operation)
  set(unsupported "")
  foreach(feature IN LISTS features)
    string(APPEND unsupported " || !__builtin_cpu_supports(\"${feature}\")")
  endforeach()
  cmake_push_check_state(RESET)
  set(CMAKE_REQUIRED_FLAGS "${flags}")
  check_cxx_source_runs("
    #include <immintrin.h>
    int main() {
      if (false${unsupported}) return 1;
      volatile double x = 1.0;
      __m256d a = _mm256_set1_pd(x);
      a = ${operation};
      return _mm256_cvtsd_f64(a) == 2.0 ? 0 : 1;
    }" ${var})
  cmake_pop_check_state()
endfunction()
_gencoord_isa_runs(GENCOORD_HAVE_AVX2 "-mavx2 -mfma" "avx2;fma" "_mm256_fmadd_pd(a, a, a)")
# AVX-512 F and VL: the same instructions on 32 vector registers instead of 16
_gencoord_isa_runs(GENCOORD_HAVE_AVX512 "-mavx2 -mfma -mavx512f -mavx512vl" "avx512f;avx512vl"
                   "_mm256_maskz_add_pd(0x1, a, a)")
find_library(GENCOORD_LIBMVEC NAMES mvec)

option(GENCOORD_AVX2_KERNELS
       "Compile models' kernel translation units (gencoord_add_model's TRANSLATION_UNITS) with -mavx2 -mfma where the compiler and the building machine have both"
       ON)
option(GENCOORD_AVX512_KERNELS
       "With GENCOORD_AVX2_KERNELS, add -mavx512f -mavx512vl (32 vector registers; vectors kept at 256 bits) where the compiler and the building machine have both"
       ON)

# The instruction-set options of the kernel objects and of the runtime's small dense kernels.
# AVX-512's 32 registers spare a long kernel most of its spills to the stack; its vectors stay
# at 256 bits (-mprefer-vector-width), as in the AVX2 code, so that a processor that slows its
# clock for 512-bit vectors does not here (docs/performance.md measures both).
set(GENCOORD_KERNEL_ISA_OPTIONS "")
if(GENCOORD_HAVE_AVX2 AND GENCOORD_AVX2_KERNELS)
  list(APPEND GENCOORD_KERNEL_ISA_OPTIONS -mavx2 -mfma)
  if(GENCOORD_HAVE_AVX512 AND GENCOORD_AVX512_KERNELS)
    list(APPEND GENCOORD_KERNEL_ISA_OPTIONS -mavx512f -mavx512vl -mprefer-vector-width=256)
  endif()
endif()

# gencoord_enable_avx2_kernels(TARGET): the static library of a model's kernel translation
# units, compiled for AVX2 and FMA where GENCOORD_HAVE_AVX2 and GENCOORD_AVX2_KERNELS hold, and
# for AVX-512 F and VL besides where GENCOORD_HAVE_AVX512 and GENCOORD_AVX512_KERNELS do.
# Long straight-line kernels gain most: three-operand encodings make their code shorter, which
# matters once it outgrows the instruction cache, and FMA contracts a * b + c into one rounding
# (docs/performance.md measures both). Eigen's alignment stays at 16 bytes in these objects, so
# that fixed-size Eigen types keep the layout, and heap blocks the allocation, of the
# baseline-ISA objects they are linked with.
function(gencoord_enable_avx2_kernels target)
  if(GENCOORD_KERNEL_ISA_OPTIONS)
    target_compile_options(${target} PRIVATE ${GENCOORD_KERNEL_ISA_OPTIONS})
    target_compile_definitions(${target} PRIVATE EIGEN_MAX_STATIC_ALIGN_BYTES=16
                               EIGEN_MAX_ALIGN_BYTES=16)
  endif()
endfunction()

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
