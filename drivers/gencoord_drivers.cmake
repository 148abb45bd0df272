# SPDX-License-Identifier: BSD-3-Clause
# gencoord_add_driver(<target> DRIVER <simulate|crosscheck|sweep> MODEL <model target>
#                     CLASS <C++ type> HEADER <generated/name.hpp>)
#
# Compiles one of the command-line drivers in this folder for one generated model: the driver
# includes "driver_model.hpp", which this function writes to include HEADER and to name CLASS
# gencoord::drivers::Model. MODEL is the target that carries the header (gencoord_add_model()
# or any library whose include path holds HEADER). `gencoord simulate MODEL.py` and
# `gencoord crosscheck MODEL.py` build their drivers through this function. The sweep driver
# also needs MPI and HDF5: the caller finds them first (find_package(MPI) with its CXX
# component and MPI_CXX_SKIP_MPICXX, find_package(HDF5) with its C component, which needs the
# C language enabled); `gencoord sweep` does.

set(GENCOORD_DRIVERS_DIR "${CMAKE_CURRENT_LIST_DIR}" CACHE INTERNAL "gencoord driver sources")

function(gencoord_add_driver target)
  cmake_parse_arguments(ARG "" "DRIVER;MODEL;CLASS;HEADER" "" ${ARGN})
  foreach(required IN ITEMS DRIVER MODEL CLASS HEADER)
    if(NOT ARG_${required})
      message(FATAL_ERROR "gencoord_add_driver(${target}): ${required} is required")
    endif()
  endforeach()
  set(source "${GENCOORD_DRIVERS_DIR}/${ARG_DRIVER}.cpp")
  if(NOT EXISTS "${source}")
    message(FATAL_ERROR "gencoord_add_driver(${target}): no driver '${ARG_DRIVER}' "
                        "(${source}); the drivers are simulate, crosscheck and sweep")
  endif()
  set(alias_dir "${CMAKE_CURRENT_BINARY_DIR}/${target}_driver_model")
  file(CONFIGURE OUTPUT "${alias_dir}/driver_model.hpp" CONTENT [[
// The model this driver is compiled for (written by gencoord_add_driver()).
#pragma once
#include "@ARG_HEADER@"
namespace gencoord::drivers {
using Model = @ARG_CLASS@;
}  // namespace gencoord::drivers
]] @ONLY)
  add_executable(${target} "${source}")
  target_include_directories(${target} PRIVATE "${alias_dir}" "${GENCOORD_DRIVERS_DIR}")
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  target_link_libraries(${target} PRIVATE gencoord::runtime ${ARG_MODEL})
  if(ARG_DRIVER STREQUAL "sweep")
    target_link_libraries(${target} PRIVATE MPI::MPI_CXX hdf5::hdf5)
  endif()
endfunction()
