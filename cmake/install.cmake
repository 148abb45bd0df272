# SPDX-License-Identifier: BSD-3-Clause
# Install rules (cmake --install <build> --prefix <P>). Every path below is relative to the
# prefix, so the installed tree can be moved:
#   <P>/include/gencoord/*.hpp         runtime headers
#   <P>/lib/libgencoord_runtime.a      runtime library
#   <P>/lib/libgencoord_control.a      the LQR design (gencoord::control)
#   <P>/include/gencoord/deformable/   the deformable library's headers  } with
#   <P>/lib/libgencoord_deformable.a   the deformable library            } GENCOORD_BUILD_DEFORMABLE
#   <P>/lib/cmake/gencoord/            gencoordConfig.cmake, gencoordConfigVersion.cmake,
#                                      gencoordTargets*.cmake (gencoord::runtime),
#                                      gencoordControlTargets*.cmake (gencoord::control),
#                                      gencoordDeformableTargets*.cmake (gencoord::deformable)
#   <P>/bin/gencoord                   the gencoord command
#   <P>/share/doc/gencoord/LICENSE     the licence (BSD-3-Clause)
#   <P>/share/gencoord/                the generator and the command's parts, laid out as in
#                                      the repository: generate, python/gencoord/ (the
#                                      package, its templates and data files),
#                                      cmake/gencoord*.cmake and simd.cmake,
#                                      drivers/*.cpp, *.hpp, *.cmake, bindings/python/
# (lib and share are GNUInstallDirs' CMAKE_INSTALL_LIBDIR and CMAKE_INSTALL_DATADIR.)
# The install component `runtime` is the runtime alone (headers, library, exported target):
# the gencoord command builds it once per user into its cache and installs just it. The
# components `control` and `deformable` are those libraries (the deformable one with its
# headers), each with an export set of its own.
include(CMakePackageConfigHelpers)

set(GENCOORD_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/gencoord")
set(GENCOORD_INSTALL_DATADIR "${CMAKE_INSTALL_DATADIR}/gencoord")

# --- runtime: headers, libraries, exported targets gencoord::runtime and gencoord::control ---
install(TARGETS gencoord_runtime EXPORT gencoordTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT runtime)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/runtime/include/gencoord"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" COMPONENT runtime)
install(EXPORT gencoordTargets NAMESPACE gencoord::
        DESTINATION "${GENCOORD_INSTALL_CMAKEDIR}" COMPONENT runtime)
# a set of its own, so that the runtime installs without it
install(TARGETS gencoord_control EXPORT gencoordControlTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT control)
install(EXPORT gencoordControlTargets NAMESPACE gencoord::
        DESTINATION "${GENCOORD_INSTALL_CMAKEDIR}" COMPONENT control)

# --- deformable (deformable/): headers, library, exported target gencoord::deformable ---
if(TARGET gencoord_deformable)
  install(TARGETS gencoord_deformable EXPORT gencoordDeformableTargets
          ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT deformable
          LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT deformable)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/deformable/include/gencoord"
          DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" COMPONENT deformable)
  install(EXPORT gencoordDeformableTargets NAMESPACE gencoord::
          DESTINATION "${GENCOORD_INSTALL_CMAKEDIR}" COMPONENT deformable)
endif()

# --- share/gencoord: what gencoord_add_model() runs, at the same relative paths as in the
# repository (generate finds python/gencoord/ beside itself; gencoord.cmake finds generate one
# folder up). One line per piece.
# _gencoord_install_share(<folder> <pattern>...): the files of <folder> matching a pattern.
function(_gencoord_install_share folder)
  set(patterns)
  foreach(pattern IN LISTS ARGN)
    list(APPEND patterns PATTERN "${pattern}")
  endforeach()
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/${folder}/"
          DESTINATION "${GENCOORD_INSTALL_DATADIR}/${folder}"
          FILES_MATCHING ${patterns} PATTERN __pycache__ EXCLUDE)
endfunction()

install(PROGRAMS "${PROJECT_SOURCE_DIR}/generate" DESTINATION "${GENCOORD_INSTALL_DATADIR}")
# the package: the generator, the command, the viewer (its page template and script) and
# the C++ backend's templates and macro list
_gencoord_install_share(python/gencoord "*.py" "*.j2" "*.txt" "*.html" "*.js")
_gencoord_install_share(python/generator "*.py")  # the former name, for old model files
install(FILES "${PROJECT_SOURCE_DIR}/cmake/gencoord.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/gencoord_python.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/simd.cmake"
        DESTINATION "${GENCOORD_INSTALL_DATADIR}/cmake")
# what gencoord_add_python_module() compiles
_gencoord_install_share(bindings "*.cpp" "*.hpp")
# the gencoord command: <P>/bin/gencoord runs gencoord.tool from <P>/share/gencoord/python,
# which compiles the drivers against this installation
_gencoord_install_share(drivers "*.cpp" "*.hpp" "*.cmake")
install(PROGRAMS "${PROJECT_SOURCE_DIR}/gencoord" DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION "${CMAKE_INSTALL_DOCDIR}")

# --- the CMake package: find_package(gencoord) ---
configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/gencoordConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/gencoordConfig.cmake"
  INSTALL_DESTINATION "${GENCOORD_INSTALL_CMAKEDIR}"
  PATH_VARS GENCOORD_INSTALL_DATADIR)
# gencoord is 0.x: a minor release may change the generated interface or the runtime's API,
# so find_package(gencoord 0.1) accepts 0.1.z only (SameMajorVersion would accept any 0.y).
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/gencoordConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/gencoordConfig.cmake"
              "${PROJECT_BINARY_DIR}/gencoordConfigVersion.cmake"
        DESTINATION "${GENCOORD_INSTALL_CMAKEDIR}")
