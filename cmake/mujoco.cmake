# MuJoCo, the reference the robot tests and the peer benchmarks compare with, as the imported
# target gencoord::mujoco when it is installed (Debian: libmujoco-dev); GENCOORD_HAVE_MUJOCO
# says whether it is. Found by path, not find_package(mujoco): Debian's config names a qhull
# include folder that need not exist.
include_guard(GLOBAL)

find_path(GENCOORD_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
find_library(GENCOORD_MUJOCO_LIBRARY mujoco)
if(GENCOORD_MUJOCO_INCLUDE_DIR AND GENCOORD_MUJOCO_LIBRARY)
  set(GENCOORD_HAVE_MUJOCO ON)
  add_library(gencoord::mujoco UNKNOWN IMPORTED)
  set_target_properties(gencoord::mujoco PROPERTIES
                        IMPORTED_LOCATION "${GENCOORD_MUJOCO_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${GENCOORD_MUJOCO_INCLUDE_DIR}")
else()
  set(GENCOORD_HAVE_MUJOCO OFF)
endif()
