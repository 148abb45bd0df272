# SPDX-License-Identifier: BSD-3-Clause
# DART, the second reference of the robot tests (its own URDF loader and recursions), as the
# targets dart and dart-utils-urdf when it is installed (Debian: libdart-dev and
# libdart-utils-urdf-dev, which scripts/setup.sh --dart installs); GENCOORD_HAVE_DART says
# whether it is.
if(NOT TARGET dart-utils-urdf)
  find_package(DART 6.12 QUIET CONFIG COMPONENTS utils-urdf)
endif()
if(TARGET dart-utils-urdf)
  set(GENCOORD_HAVE_DART ON)
else()
  set(GENCOORD_HAVE_DART OFF)
endif()
