# SPDX-License-Identifier: BSD-3-Clause
# gencoord_unity_build_here(): the targets that the calling directory and its subdirectories
# add from here on compile their sources in batches (CMake's unity build), when
# GENCOORD_UNITY_BUILD is on. A test file spends most of its compile time parsing and
# instantiating what its neighbours parse and instantiate too (GoogleTest, Eigen, the runtime's
# templates for the same models); a batch does that once. Four of the deformable tests compile
# in 58 s of CPU as one batch against 99 s one by one. A source with compile options of its own
# stays out of the batches (CMake's rule). With the option off, each file compiles alone: a
# developer who edits one test file then recompiles that file only.
macro(gencoord_unity_build_here)
  if(GENCOORD_UNITY_BUILD)
    set(CMAKE_UNITY_BUILD ON)
    set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)
  endif()
endmacro()
