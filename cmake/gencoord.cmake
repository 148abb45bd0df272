# SPDX-License-Identifier: BSD-3-Clause
# gencoord_add_model(<target> MODEL <model.py> [NAME <name>] [OPTIONS key=value ...]
#                    [DEPENDS <file> ...] [DYNAMICS auto|dense|recursive]
#                    [TRANSLATION_UNITS <k>] [MAX_FUNCTION_STATEMENTS <n>] [LOOP_MIN_NQ <n>]
#                    [OUTPUT_DIR <dir>] [MAXIMAL])
#
# Generates <name>.hpp from a gencoord model file at build time and makes <target> an
# INTERFACE library that carries it: `target_link_libraries(app PRIVATE <target>)` and then
# `#include "generated/<name>.hpp"`. The header is regenerated whenever the model file, any
# generator source or any template changes. <name> is the model file's stem (or NAME, which
# passes --name) followed by "_<value>" for each option, in the order given (list options in
# the model file's order).
# DEPENDS names other files the model file reads (a URDF its load_urdf() loads): a change
# to one regenerates the header too. DYNAMICS passes --dynamics (how a tree of particles or
# of bodies computes qddot and inverse_dynamics).
#
# TRANSLATION_UNITS <k> (./generate --translation-units, for large models) also generates
# <name>_double_0.cpp ... <name>_double_<k-1>.cpp, which compile every kernel for double once
# and in parallel; <target> is then a static library of them, and files that include the
# header compile no kernel body for double. Where the building machine has AVX2 and FMA, those
# files are compiled for them (GENCOORD_AVX2_KERNELS, simd.cmake). With two or more, the first
# holds the kernels that run alone in a call (qddot, inverse_dynamics, mass_matrix, ...), the
# others the derivative path (dynamics, residual_jacobians) and the Jacobians, and GCC compiles
# the first with pre-register-allocation scheduling (GENCOORD_SCHEDULED_KERNELS). MAX_FUNCTION_STATEMENTS passes
# --max-function-statements, LOOP_MIN_NQ --loop-min-nq (from how many coordinates a tree's
# Mt, J and residual Jacobians are loops over O(nq) products); OUTPUT_DIR replaces
# ${CMAKE_BINARY_DIR}/gencoord_generated as the folder that holds generated/<name>.hpp (the
# include directory). MAXIMAL passes --maximal: the header also holds the maximal-coordinate
# penalty model (struct Maximal) that the crosscheck driver and gencoord/maximal/ run.
#
# GENCOORD_GENERATION_CACHE (a cache variable, empty by default) names a folder where generate
# keeps what it generated and reuses it for the same inputs (generate --cache): a fresh build
# folder or a second checkout then derives no model again. The key holds the model file and its
# DEPENDS, so a model file that reads files it does not name there must not use it.
#
# This file works from three places: gencoord's own build, a project that added gencoord with
# add_subdirectory(), and an install (gencoordConfig.cmake includes it from share/gencoord/cmake/).
# In all three the generator sits one folder up with the same layout: the script `generate`
# and the Python package python/gencoord/ (its C++ backend's templates in cxx/templates/). The
# generator needs a Python with SymPy and Jinja2: GENCOORD_PYTHON, the first python3 on PATH
# unless given.

include_guard(GLOBAL)
include("${CMAKE_CURRENT_LIST_DIR}/simd.cmake")  # gencoord_enable_avx2_kernels()

# Cache variables, not plain ones: the function runs in its callers' directories, which need
# not see the variables of the directory that included this file.
get_filename_component(_gencoord_root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set(GENCOORD_ROOT "${_gencoord_root}" CACHE INTERNAL
    "gencoord's generator folder: the script generate and the package python/gencoord/")

if(NOT GENCOORD_PYTHON)
  # the first python3 on PATH, the one a user runs ./generate with
  find_program(GENCOORD_PYTHON NAMES python3 python REQUIRED)
endif()
execute_process(COMMAND "${GENCOORD_PYTHON}" -c "import sympy, jinja2"
                RESULT_VARIABLE _gencoord_python_ok OUTPUT_QUIET ERROR_QUIET)
if(NOT _gencoord_python_ok EQUAL 0)
  message(FATAL_ERROR "gencoord: ${GENCOORD_PYTHON} cannot import sympy and jinja2. "
                      "Install both (gencoord's scripts/setup.sh does), or pass "
                      "-DGENCOORD_PYTHON=<a python with both>.")
endif()

file(GLOB_RECURSE _gencoord_generator_sources CONFIGURE_DEPENDS
     "${GENCOORD_ROOT}/python/gencoord/*.py" "${GENCOORD_ROOT}/python/gencoord/*.j2"
     "${GENCOORD_ROOT}/python/gencoord/*.txt")
set(GENCOORD_GENERATOR_SOURCES ${_gencoord_generator_sources} "${GENCOORD_ROOT}/generate"
    CACHE INTERNAL "files whose change regenerates every model")
set(GENCOORD_GENERATION_CACHE "" CACHE PATH
    "a folder where generate keeps its outputs and reuses them for the same inputs (--cache)")

# gencoord_generation_cache_arguments(<variable> [<file the model reads> ...]): the arguments
# of generate that use GENCOORD_GENERATION_CACHE, none when it is empty
function(gencoord_generation_cache_arguments variable)
  set(arguments)
  if(GENCOORD_GENERATION_CACHE)
    list(APPEND arguments --cache "${GENCOORD_GENERATION_CACHE}")
    foreach(dependency IN LISTS ARGN)
      get_filename_component(dependency "${dependency}" ABSOLUTE)
      list(APPEND arguments --depends "${dependency}")
    endforeach()
  endif()
  set(${variable} ${arguments} PARENT_SCOPE)
endfunction()

option(GENCOORD_SCHEDULED_KERNELS
       "Compile group 0 of a model's kernel translation units (TRANSLATION_UNITS 2 or more) with GCC's -fschedule-insns -fsched-pressure"
       ON)

# With two translation units or more, group 0 holds every kernel but those of the derivative
# path and the Jacobians (gencoord/optimize/split.py says why), and GCC compiles it with
# register-pressure-aware scheduling before register allocation, which x86 leaves off: it
# interleaves the independent chains of a recursion's latency-bound code (docs/performance.md).
function(_gencoord_schedule_kernels target source)
  if(GENCOORD_SCHEDULED_KERNELS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    set_source_files_properties("${source}" TARGET_DIRECTORY ${target} PROPERTIES
                                COMPILE_OPTIONS "-fschedule-insns;-fsched-pressure")
  endif()
endfunction()

function(gencoord_add_model target)
  cmake_parse_arguments(ARG "MAXIMAL"
                        "MODEL;NAME;DYNAMICS;TRANSLATION_UNITS;MAX_FUNCTION_STATEMENTS;LOOP_MIN_NQ;OUTPUT_DIR"
                        "OPTIONS;DEPENDS" ${ARGN})
  if(NOT ARG_MODEL)
    message(FATAL_ERROR "gencoord_add_model(${target}): MODEL <file.py> is required")
  endif()
  get_filename_component(model "${ARG_MODEL}" ABSOLUTE)
  get_filename_component(name "${model}" NAME_WE)
  set(set_arguments)
  if(ARG_NAME)
    set(name "${ARG_NAME}")
    list(APPEND set_arguments --name "${ARG_NAME}")
  endif()
  if(ARG_DYNAMICS)
    list(APPEND set_arguments --dynamics ${ARG_DYNAMICS})
  endif()
  foreach(option IN LISTS ARG_OPTIONS)
    string(REGEX REPLACE "^[^=]*=" "" value "${option}")
    string(APPEND name "_${value}")
    list(APPEND set_arguments --set "${option}")
  endforeach()
  if(DEFINED ARG_MAX_FUNCTION_STATEMENTS)
    list(APPEND set_arguments --max-function-statements ${ARG_MAX_FUNCTION_STATEMENTS})
  endif()
  if(DEFINED ARG_LOOP_MIN_NQ)
    list(APPEND set_arguments --loop-min-nq ${ARG_LOOP_MIN_NQ})
  endif()
  if(ARG_MAXIMAL)
    list(APPEND set_arguments --maximal)
  endif()
  gencoord_generation_cache_arguments(cache_arguments ${ARG_DEPENDS})

  set(include_dir "${CMAKE_BINARY_DIR}/gencoord_generated")
  if(ARG_OUTPUT_DIR)
    set(include_dir "${ARG_OUTPUT_DIR}")
  endif()
  set(header "${include_dir}/generated/${name}.hpp")
  set(sources)
  if(ARG_TRANSLATION_UNITS)
    list(APPEND set_arguments --translation-units ${ARG_TRANSLATION_UNITS})
    math(EXPR last "${ARG_TRANSLATION_UNITS} - 1")
    foreach(k RANGE ${last})
      list(APPEND sources "${include_dir}/generated/${name}_double_${k}.cpp")
    endforeach()
  endif()
  add_custom_command(
    OUTPUT "${header}" ${sources}
    COMMAND ${CMAKE_COMMAND} -E env PYTHONHASHSEED=0
            "${GENCOORD_PYTHON}" "${GENCOORD_ROOT}/generate" "${model}"
            -o "${include_dir}/generated" --quiet ${set_arguments} ${cache_arguments}
    # generate leaves unchanged files alone; touch them so the build sees them up to date,
    # but never create one: a header generate did not write must stay missing
    COMMAND ${CMAKE_COMMAND} -E touch_nocreate "${header}" ${sources}
    DEPENDS "${model}" ${ARG_DEPENDS} ${GENCOORD_GENERATOR_SOURCES}
    COMMENT "gencoord: generating ${name}.hpp from ${ARG_MODEL}"
    VERBATIM)
  add_custom_target(${target}_header DEPENDS "${header}" ${sources})
  # The generated code includes Eigen. Imported targets are visible only in the directory that
  # found them and below, so find Eigen here, in the caller's directory, if it cannot see it.
  if(NOT TARGET Eigen3::Eigen)
    find_package(Eigen3 3.4 REQUIRED NO_MODULE)
  endif()
  if(sources)
    add_library(${target} STATIC ${sources})
    # each file defines GENCOORD_PART_GROUP for the one header it includes; position-independent
    # so that a Python module (a shared library) can link the model too
    set_target_properties(${target} PROPERTIES UNITY_BUILD OFF POSITION_INDEPENDENT_CODE ON)
    gencoord_enable_avx2_kernels(${target})
    list(LENGTH sources count)
    if(count GREATER 1)
      _gencoord_schedule_kernels(${target} "${include_dir}/generated/${name}_double_0.cpp")
    endif()
    target_include_directories(${target} PUBLIC "${include_dir}")
    target_link_libraries(${target} PUBLIC Eigen3::Eigen)
    target_compile_features(${target} PUBLIC cxx_std_17)
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE "${include_dir}")
    target_link_libraries(${target} INTERFACE Eigen3::Eigen)
    target_compile_features(${target} INTERFACE cxx_std_17)
  endif()
  add_dependencies(${target} ${target}_header)
  # what gencoord_add_python_module() and other callers need to include and name the model
  string(REPLACE "_" ";" parts "${name}")
  set(class_name "")
  foreach(part IN LISTS parts)
    string(SUBSTRING "${part}" 0 1 first)
    string(SUBSTRING "${part}" 1 -1 rest)
    string(TOUPPER "${first}" first)
    string(APPEND class_name "${first}${rest}")
  endforeach()
  set_target_properties(${target} PROPERTIES GENCOORD_MODEL_NAME "${name}"
                        GENCOORD_MODEL_CLASS "gencoord::models::${class_name}")
endfunction()

# gencoord_add_python_module(): the model's Python module (gencoord_python.cmake).
include("${CMAKE_CURRENT_LIST_DIR}/gencoord_python.cmake")
