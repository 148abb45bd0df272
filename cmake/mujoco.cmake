# SPDX-License-Identifier: BSD-3-Clause
# MuJoCo, the reference the robot tests and the peer benchmarks compare with, as the imported
# target gencoord::mujoco (global, so every directory sees it) when it is installed (Debian:
# libmujoco-dev); GENCOORD_HAVE_MUJOCO says whether it is. Found by path, not
# find_package(mujoco): Debian's config names a qhull include folder that need not exist.
if(NOT TARGET gencoord::mujoco)
  find_path(GENCOORD_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
  find_library(GENCOORD_MUJOCO_LIBRARY mujoco)
  if(GENCOORD_MUJOCO_INCLUDE_DIR AND GENCOORD_MUJOCO_LIBRARY)
    add_library(gencoord::mujoco UNKNOWN IMPORTED GLOBAL)
    set_target_properties(gencoord::mujoco PROPERTIES
                          IMPORTED_LOCATION "${GENCOORD_MUJOCO_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${GENCOORD_MUJOCO_INCLUDE_DIR}")
  endif()
endif()
if(TARGET gencoord::mujoco)
  set(GENCOORD_HAVE_MUJOCO ON)
else()
  set(GENCOORD_HAVE_MUJOCO OFF)
endif()
