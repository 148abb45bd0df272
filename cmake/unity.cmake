# SPDX-License-Identifier: BSD-3-Clause
# gencoord_unity_build_here(): the targets that the calling directory and its subdirectories
# add from here on compile their sources in batches (CMake's unity build), when
# GENCOORD_UNITY_BUILD is on. A test file spends most of its compile time parsing and
# instantiating what its neighbours parse and instantiate too (GoogleTest, Eigen, the runtime's
# templates for the same models); a batch does that once (docs/testing.md has the cold build's
# time). A source with compile options of its own stays out of the batches (CMake's rule), and
# so do a model's kernel sources (gencoord_add_model). With the option off, each file compiles
# alone: a developer who edits one test file then recompiles that file only, and a file that
# leans on an include of its neighbour in the batch shows it.
macro(gencoord_unity_build_here)
  if(GENCOORD_UNITY_BUILD)
    set(CMAKE_UNITY_BUILD ON)
    set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)
  endif()
endmacro()
