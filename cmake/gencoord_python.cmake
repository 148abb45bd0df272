# SPDX-License-Identifier: BSD-3-Clause
# gencoord_add_python_module(<target> MODEL <model.py> [MODULE_NAME <module>] [NAME <name>]
#                            [OPTIONS key=value ...] [DEPENDS <file> ...] [DYNAMICS ...]
#                            [OUTPUT_DIR <dir>])
# gencoord_add_python_module(<target> MODEL_TARGET <model target> [MODULE_NAME <module>]
#                            [OUTPUT_DIR <dir>])
#
# Builds the Python extension module of a model file with pybind11: import it as <module>
# (default: the header's name, e.g. double_pendulum or n_link_chain_5) to get its Params,
# metadata, every kernel over NumPy arrays, rhs/jac for scipy.integrate.solve_ivp and
# simulate() (docs/python.md). MODEL, NAME, OPTIONS, DEPENDS and DYNAMICS are
# gencoord_add_model()'s; the generated header goes to <target>_model. MODEL_TARGET instead
# names a target gencoord_add_model() made already. The module is written
# to OUTPUT_DIR, default the current binary directory.
#
# Needs pybind11 (Debian: pybind11-dev) and the headers of the Python that will import the
# module (python3-dev); which Python is pybind11's choice: PYBIND11_PYTHON_VERSION or
# Python_EXECUTABLE (with PYBIND11_FINDPYTHON=ON) select it.

include_guard(GLOBAL)
include("${CMAKE_CURRENT_LIST_DIR}/simd.cmake")

set(GENCOORD_PYTHON_BINDINGS_DIR "${CMAKE_CURRENT_LIST_DIR}/../bindings/python" CACHE INTERNAL
    "gencoord's pybind11 bindings: include/gencoord_python/*.hpp and model_module.cpp")

function(gencoord_add_python_module target)
  cmake_parse_arguments(ARG "" "MODEL;MODEL_TARGET;MODULE_NAME;NAME;DYNAMICS;OUTPUT_DIR"
                        "OPTIONS;DEPENDS" ${ARGN})
  if(NOT ARG_MODEL AND NOT ARG_MODEL_TARGET)
    message(FATAL_ERROR "gencoord_add_python_module(${target}): MODEL <file.py> or "
                        "MODEL_TARGET <target of gencoord_add_model()> is required")
  endif()
  if(NOT COMMAND pybind11_add_module)
    find_package(pybind11 CONFIG REQUIRED)
  endif()
  # the interpreter pybind11 builds for (its classic or its FindPython mode), named by the
  # module when another one lacks NumPy
  set(built_for "${PYTHON_EXECUTABLE}")
  if(NOT built_for)
    set(built_for "${Python_EXECUTABLE}")
  endif()
  if(ARG_MODEL_TARGET)
    set(model_target ${ARG_MODEL_TARGET})
  else()
    set(model_target ${target}_model)
    _gencoord_python_model(${model_target})
  endif()
  get_target_property(name ${model_target} GENCOORD_MODEL_NAME)
  get_target_property(class_name ${model_target} GENCOORD_MODEL_CLASS)
  set(module_name "${name}")
  if(ARG_MODULE_NAME)
    set(module_name "${ARG_MODULE_NAME}")
  endif()

  # NO_EXTRAS: no link-time optimization, which doubles the build for no measured gain
  pybind11_add_module(${target} MODULE NO_EXTRAS
                      "${GENCOORD_PYTHON_BINDINGS_DIR}/model_module.cpp"
                      "${GENCOORD_PYTHON_BINDINGS_DIR}/qddot_lanes.cpp")
  # qddot_simd's Pack<4> kernel alone gets the SIMD flags
  gencoord_enable_simd_source(${target} "${GENCOORD_PYTHON_BINDINGS_DIR}/qddot_lanes.cpp")
  target_include_directories(${target} PRIVATE "${GENCOORD_PYTHON_BINDINGS_DIR}/include")
  target_compile_definitions(${target} PRIVATE
                             "GENCOORD_MODEL_HEADER=\"generated/${name}.hpp\""
                             "GENCOORD_MODEL_CLASS=${class_name}"
                             "GENCOORD_MODULE_NAME=${module_name}"
                             "GENCOORD_BUILT_FOR=\"${built_for}\"")
  target_link_libraries(${target} PRIVATE ${model_target} gencoord::runtime)
  set_target_properties(${target} PROPERTIES OUTPUT_NAME "${module_name}")
  if(ARG_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIR}")
  endif()
endfunction()

# gencoord_add_model(<model target> ...) with the caller's MODEL, NAME, DYNAMICS, OPTIONS and
# DEPENDS (a macro: it reads the caller's ARG_ variables).
macro(_gencoord_python_model model_target)
  set(model_arguments MODEL "${ARG_MODEL}")
  foreach(keyword IN ITEMS NAME DYNAMICS)
    if(ARG_${keyword})
      list(APPEND model_arguments ${keyword} "${ARG_${keyword}}")
    endif()
  endforeach()
  if(ARG_OPTIONS)
    list(APPEND model_arguments OPTIONS ${ARG_OPTIONS})
  endif()
  if(ARG_DEPENDS)
    list(APPEND model_arguments DEPENDS ${ARG_DEPENDS})
  endif()
  gencoord_add_model(${model_target} ${model_arguments})
endmacro()
