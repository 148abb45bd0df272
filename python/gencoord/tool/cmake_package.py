# SPDX-License-Identifier: BSD-3-Clause
"""`gencoord --cmake-dir`: a folder for `find_package(gencoord)` (CMAKE_PREFIX_PATH or
gencoord_DIR), wherever gencoord runs from.

A CMake install has its own package files. A checkout or a pip install has a CMake project
instead: the runtime is built once into the per-user cache (runtime_build.py) and a package
config beside it gives gencoord::runtime and gencoord_add_model(), which runs this
interpreter's generator. (gencoord::control, the LQR design, comes with a CMake install.)
"""

from __future__ import annotations

import os
import sys

from gencoord import __version__
from gencoord.generate.cli import write_atomically
from gencoord.tool.layout import Layout, cache_dir
from gencoord.tool.runtime_build import runtime_key, runtime_targets_dir

_CONFIG = """\
# find_package(gencoord) for the gencoord in {source_dir}, written by `gencoord --cmake-dir`
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.4 NO_MODULE)
set(THREADS_PREFER_PTHREAD_FLAG ON)  # as the runtime was built: batch.hpp runs std::thread
find_dependency(Threads)
include("{targets_dir}/gencoordTargets.cmake")
if(NOT GENCOORD_PYTHON)
  set(GENCOORD_PYTHON "{python}" CACHE FILEPATH "the Python that runs gencoord's generator")
endif()
include("{source_dir}/cmake/gencoord.cmake")
"""

# the same rule as the installed package's: 0.x accepts the same minor version only
_VERSION = """\
set(PACKAGE_VERSION "{version}")
set(PACKAGE_VERSION_COMPATIBLE FALSE)
if(PACKAGE_FIND_VERSION_MAJOR EQUAL {major} AND PACKAGE_FIND_VERSION_MINOR EQUAL {minor}
   AND NOT PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
endif()
if(NOT PACKAGE_FIND_VERSION OR PACKAGE_FIND_VERSION VERSION_EQUAL PACKAGE_VERSION)
  set(PACKAGE_VERSION_EXACT TRUE)
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
endif()
"""


def cmake_package_dir(layout: Layout, *, verbose: bool = False) -> str:
    if not layout.source_dir:
        assert layout.prefix is not None  # without a source_dir, an installation's prefix
        return os.path.join(layout.prefix, "lib", "cmake", "gencoord")
    targets_dir = runtime_targets_dir(layout, verbose=verbose)
    folder = os.path.join(cache_dir(), f"cmake-{runtime_key(layout.source_dir)}")
    major, minor = __version__.split(".")[:2]
    write_atomically(os.path.join(folder, "gencoordConfig.cmake"),
                     _CONFIG.format(source_dir=layout.source_dir, targets_dir=targets_dir,
                                    python=sys.executable))
    write_atomically(os.path.join(folder, "gencoordConfigVersion.cmake"),
                     _VERSION.format(version=__version__, major=major, minor=minor))
    return folder
