# gencoord_add_model(<target> MODEL <model.py> [OPTIONS key=value ...])
#
# Generates <name>.hpp from a gencoord model file at build time and makes <target> an
# INTERFACE library that carries it: `target_link_libraries(app PRIVATE <target>)` and then
# `#include "generated/<name>.hpp"`. The header is regenerated whenever the model file, any
# generator source or any template changes. <name> is the model file's stem followed by
# "_<value>" for each option, in the order given (list options in the model file's order).

set(GENCOORD_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." CACHE INTERNAL "gencoord source root")

if(NOT GENCOORD_PYTHON)
  # the first python3 on PATH, the one a user runs ./generate with
  find_program(GENCOORD_PYTHON NAMES python3 python REQUIRED)
endif()
execute_process(COMMAND "${GENCOORD_PYTHON}" -c "import sympy, jinja2"
                RESULT_VARIABLE _gencoord_python_ok OUTPUT_QUIET ERROR_QUIET)
if(NOT _gencoord_python_ok EQUAL 0)
  message(FATAL_ERROR "gencoord: ${GENCOORD_PYTHON} cannot import sympy and jinja2. "
                      "Run scripts/setup.sh, or pass -DGENCOORD_PYTHON=<a python with both>.")
endif()

file(GLOB _gencoord_generator_sources CONFIGURE_DEPENDS
     "${GENCOORD_ROOT}/generator/*.py" "${GENCOORD_ROOT}/templates/*.j2")
set(GENCOORD_GENERATOR_SOURCES ${_gencoord_generator_sources} "${GENCOORD_ROOT}/generate"
    CACHE INTERNAL "files whose change regenerates every model")

function(gencoord_add_model target)
  cmake_parse_arguments(ARG "" "MODEL" "OPTIONS" ${ARGN})
  if(NOT ARG_MODEL)
    message(FATAL_ERROR "gencoord_add_model(${target}): MODEL <file.py> is required")
  endif()
  get_filename_component(model "${ARG_MODEL}" ABSOLUTE)
  get_filename_component(name "${model}" NAME_WE)
  set(set_arguments)
  foreach(option IN LISTS ARG_OPTIONS)
    string(REGEX REPLACE "^[^=]*=" "" value "${option}")
    string(APPEND name "_${value}")
    list(APPEND set_arguments --set "${option}")
  endforeach()

  set(include_dir "${CMAKE_BINARY_DIR}/gencoord_generated")
  set(header "${include_dir}/generated/${name}.hpp")
  add_custom_command(
    OUTPUT "${header}"
    COMMAND ${CMAKE_COMMAND} -E env PYTHONHASHSEED=0
            "${GENCOORD_PYTHON}" "${GENCOORD_ROOT}/generate" "${model}"
            -o "${include_dir}/generated" --quiet ${set_arguments}
    # generate leaves an unchanged header alone; touch it so the build sees it up to date
    COMMAND ${CMAKE_COMMAND} -E touch "${header}"
    DEPENDS "${model}" ${GENCOORD_GENERATOR_SOURCES}
    COMMENT "gencoord: generating ${name}.hpp from ${ARG_MODEL}"
    VERBATIM)
  add_custom_target(${target}_header DEPENDS "${header}")
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_header)
  target_include_directories(${target} INTERFACE "${include_dir}")
  target_link_libraries(${target} INTERFACE Eigen3::Eigen)
endfunction()
