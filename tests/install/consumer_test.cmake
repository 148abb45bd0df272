# SPDX-License-Identifier: BSD-3-Clause
# Builds and runs the gantry-crane consumer (examples/consumer) against gencoord, by one route:
#   cmake -DROUTE=find_package|pip|add_subdirectory -DSOURCE_DIR=<repository> -DBUILD_DIR=<its build>
#         -DWORK_DIR=<scratch folder> -DPYTHON=<GENCOORD_PYTHON> -DGENERATOR=<CMake generator>
#         -DCXX_COMPILER=<compiler> -P consumer_test.cmake
# find_package: installs BUILD_DIR into a staging prefix, moves it (the package must be
# relocatable and name no source or build path), copies examples/consumer out of the
# repository and configures it with CMAKE_PREFIX_PATH=<moved prefix> only; then the installed
# gencoord command simulates the example's model, building its driver against the prefix.
# pip: `pip install .` into a fresh virtual environment (with the system's site packages, for
# SymPy), the source removed; `gencoord --cmake-dir` gives the folder for find_package, and the
# installed command simulates the example's model.
# add_subdirectory: configures tests/install/subdirectory, which adds the repository with
# add_subdirectory() and builds the same program, with GoogleTest and Google Benchmark made
# unfindable (they must not be needed).
# Both: build with 2 jobs, -Wall -Wextra -Werror; the program must exit 0 and print its checks.
# -DLINK_FLAGS=... (optional) links the consumer with them, e.g. the sanitizers that an
# installed library built with GENCOORD_SANITIZE needs; -DCXX_LAUNCHER=... (optional) compiles
# through it, e.g. the build's ccache. -DDEFORMABLE=ON (find_package route): BUILD_DIR has
# gencoord::deformable, which must install too, and the consumer in deformable/ (outside the
# repository as well) finds it with find_package(gencoord COMPONENTS deformable), builds and
# runs.
cmake_minimum_required(VERSION 3.20)

foreach(var IN ITEMS ROUTE SOURCE_DIR BUILD_DIR WORK_DIR PYTHON GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "consumer_test.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${command}")
  endif()
endfunction()

# only what this script passes decides where packages come from
unset(ENV{CMAKE_PREFIX_PATH})
unset(ENV{gencoord_DIR})
unset(ENV{gencoord_ROOT})

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(consumer_build "${WORK_DIR}/build")
set(common_arguments -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Werror"
    "-DGENCOORD_PYTHON=${PYTHON}" "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}")
if(CXX_LAUNCHER)  # the build's own, e.g. ccache
  list(APPEND common_arguments "-DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER}")
endif()

if(ROUTE STREQUAL "find_package")
  # cmake --install needs the libraries built
  set(libraries gencoord_runtime gencoord_control)
  if(DEFORMABLE)
    list(APPEND libraries gencoord_deformable)
  endif()
  run("${CMAKE_COMMAND}" --build "${BUILD_DIR}" --target ${libraries} --parallel 2)
  set(staging "${WORK_DIR}/staging")
  set(prefix "${WORK_DIR}/prefix")
  run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${staging}")
  file(RENAME "${staging}" "${prefix}")

  # no installed text file may name the source tree, the build tree or the staging prefix
  file(GLOB_RECURSE installed LIST_DIRECTORIES false "${prefix}/*")
  set(text_files 0)
  foreach(file IN LISTS installed)
    if(file MATCHES "\\.(cmake|py|j2|hpp)$" OR file MATCHES "/generate$")
      math(EXPR text_files "${text_files} + 1")
      file(READ "${file}" content)
      foreach(path IN ITEMS "${SOURCE_DIR}" "${BUILD_DIR}" "${staging}")
        string(FIND "${content}" "${path}" at)
        if(NOT at EQUAL -1)
          message(FATAL_ERROR "installed ${file} names ${path}: the package is not relocatable")
        endif()
      endforeach()
    endif()
  endforeach()
  set(expected_files
      include/gencoord/gencoord.hpp lib/cmake/gencoord/gencoordConfig.cmake
      lib/cmake/gencoord/gencoordConfigVersion.cmake lib/cmake/gencoord/gencoordTargets.cmake
      lib/cmake/gencoord/gencoordControlTargets.cmake
      share/gencoord/generate share/gencoord/python/gencoord/generate/cli.py
      share/gencoord/python/gencoord/cxx/templates/model.hpp.j2
      share/gencoord/cmake/gencoord.cmake bin/gencoord share/gencoord/python/gencoord/tool/main.py
      share/gencoord/drivers/simulate.cpp share/gencoord/drivers/gencoord_drivers.cmake
      share/gencoord/python/gencoord/viewer/page.html
      share/gencoord/python/gencoord/viewer/viewer.js)
  if(DEFORMABLE)
    list(APPEND expected_files include/gencoord/deformable/mass_spring_system.hpp
         lib/cmake/gencoord/gencoordDeformableTargets.cmake)
  endif()
  foreach(expected IN LISTS expected_files)
    if(NOT EXISTS "${prefix}/${expected}")
      message(FATAL_ERROR "not installed: ${expected}")
    endif()
  endforeach()
  message(STATUS "installed ${text_files} text files, none naming a source or build path")

  # the consumer outside the repository, so nothing resolves through the source tree
  file(COPY "${SOURCE_DIR}/examples/consumer/" DESTINATION "${WORK_DIR}/consumer")
  run("${CMAKE_COMMAND}" -S "${WORK_DIR}/consumer" -B "${consumer_build}" ${common_arguments}
      "-DCMAKE_PREFIX_PATH=${prefix}")
  file(STRINGS "${consumer_build}/CMakeCache.txt" found REGEX "^gencoord_DIR:")
  if(NOT found STREQUAL "gencoord_DIR:PATH=${prefix}/lib/cmake/gencoord")
    message(FATAL_ERROR "the consumer found gencoord elsewhere: ${found}")
  endif()
elseif(ROUTE STREQUAL "pip")
  # a copy of what `pip install .` reads, so that its build leaves the checkout untouched
  set(source "${WORK_DIR}/source")
  foreach(item IN ITEMS pyproject.toml setup.py README.md LICENSE CMakeLists.txt generate
                        cmake runtime drivers bindings python)
    file(COPY "${SOURCE_DIR}/${item}" DESTINATION "${source}" PATTERN __pycache__ EXCLUDE
         PATTERN "*.egg-info" EXCLUDE)
  endforeach()
  set(venv "${WORK_DIR}/venv")
  run("${PYTHON}" -m venv --system-site-packages "${venv}")
  # offline: the setuptools already installed builds it (no build isolation, no index)
  run("${venv}/bin/python" -m pip install --quiet --no-build-isolation --no-deps --no-index
      "${source}")
  file(REMOVE_RECURSE "${source}")  # the installed package must not need its source
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "GENCOORD_CACHE_DIR=${WORK_DIR}/cache"
                          "${venv}/bin/gencoord" --cmake-dir
                  RESULT_VARIABLE rc OUTPUT_VARIABLE cmake_dir OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${cmake_dir}/gencoordConfig.cmake")
    message(FATAL_ERROR "gencoord --cmake-dir of the pip install failed (${rc}): ${cmake_dir}")
  endif()
  file(COPY "${SOURCE_DIR}/examples/consumer/" DESTINATION "${WORK_DIR}/consumer")
  # the generator that gencoord_add_model runs is the pip install's: its config names the
  # virtual environment's python, so this route passes none
  list(FILTER common_arguments EXCLUDE REGEX "^-DGENCOORD_PYTHON=")
  run("${CMAKE_COMMAND}" -S "${WORK_DIR}/consumer" -B "${consumer_build}" ${common_arguments}
      "-Dgencoord_DIR=${cmake_dir}")
elseif(ROUTE STREQUAL "add_subdirectory")
  run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/tests/install/subdirectory" -B "${consumer_build}"
      ${common_arguments} "-DGENCOORD_SOURCE_DIR=${SOURCE_DIR}"
      -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON)
else()
  message(FATAL_ERROR "ROUTE must be find_package, pip or add_subdirectory, not '${ROUTE}'")
endif()

run("${CMAKE_COMMAND}" --build "${consumer_build}" --parallel 2)
execute_process(COMMAND "${consumer_build}/gantry_crane" RESULT_VARIABLE rc
                OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT rc EQUAL 0 OR NOT output MATCHES "all checks passed")
  message(FATAL_ERROR "gantry_crane failed (exit status ${rc})")
endif()

if(ROUTE STREQUAL "pip")
  # the pip-installed command simulates the example's model with the runtime it built
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "GENCOORD_CACHE_DIR=${WORK_DIR}/cache"
                          "${venv}/bin/gencoord" simulate gantry_crane.py --duration 0.5
                          -o "${WORK_DIR}/out"
                  WORKING_DIRECTORY "${WORK_DIR}/consumer"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("${output}")
  if(NOT rc EQUAL 0 OR NOT output MATCHES "trajectory .*gantry_crane.csv \\(501 rows\\)")
    message(FATAL_ERROR "the pip-installed gencoord simulate failed (exit status ${rc})")
  endif()
endif()

if(ROUTE STREQUAL "find_package")
  # the installed gencoord command compiles its simulate driver against the installation
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "GENCOORD_CACHE_DIR=${WORK_DIR}/cache"
                          "${PYTHON}" "${prefix}/bin/gencoord" simulate gantry_crane.py
                          --duration 0.5 -o "${WORK_DIR}/out"
                  WORKING_DIRECTORY "${WORK_DIR}/consumer"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("${output}")
  if(NOT rc EQUAL 0 OR NOT output MATCHES "trajectory .*gantry_crane.csv \\(501 rows\\)"
     OR NOT EXISTS "${WORK_DIR}/out/gantry_crane.svg"
     OR NOT EXISTS "${WORK_DIR}/out/gantry_crane.html")
    message(FATAL_ERROR "the installed gencoord simulate failed (exit status ${rc})")
  endif()
  file(GLOB driver_caches "${WORK_DIR}/cache/gantry_crane-*/build/CMakeCache.txt")
  file(STRINGS "${driver_caches}" found REGEX "^gencoord_DIR:")
  if(NOT found STREQUAL "gencoord_DIR:PATH=${prefix}/lib/cmake/gencoord")
    message(FATAL_ERROR "the installed gencoord command built against another gencoord: ${found}")
  endif()

  if(DEFORMABLE)
    set(deformable_build "${WORK_DIR}/deformable_build")
    file(COPY "${SOURCE_DIR}/tests/install/deformable/" DESTINATION "${WORK_DIR}/deformable")
    run("${CMAKE_COMMAND}" -S "${WORK_DIR}/deformable" -B "${deformable_build}"
        ${common_arguments} "-DCMAKE_PREFIX_PATH=${prefix}")
    run("${CMAKE_COMMAND}" --build "${deformable_build}" --parallel 2)
    execute_process(COMMAND "${deformable_build}/rod_consumer" RESULT_VARIABLE rc
                    OUTPUT_VARIABLE output ERROR_VARIABLE output)
    message("${output}")
    if(NOT rc EQUAL 0 OR NOT output MATCHES "all checks passed")
      message(FATAL_ERROR "the consumer of gencoord::deformable failed (exit status ${rc})")
    endif()
  endif()
endif()
