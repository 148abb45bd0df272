# SPDX-License-Identifier: BSD-3-Clause
# The memory suites: the test suites of the code that can have memory errors (the runtime on
# hand-written models, the deformables, the maximal model, constraints, the fuzz targets'
# corpora, the sweep program's exchange between ranks). scripts/test.sh builds them with
# AddressSanitizer and UndefinedBehaviorSanitizer and runs them there, and configures its
# Release build with GENCOORD_MEMORY_SUITES off, so that each suite is built and run once.
#
# gencoord_memory_suite(<target> <label>): <target>, whose tests carry the CTest label <label>,
# is a memory suite: the target gencoord_memory_suites builds it, and <label> joins the label
# expression written to <build>/memory_suites.labels at the end of the configuration
# (`ctest -L "$(cat <build>/memory_suites.labels)"` runs the memory suites' tests).
# GoogleTest's discovery takes one label per suite, so the suites are found by theirs.

add_custom_target(gencoord_memory_suites)

function(gencoord_memory_suite target label)
  add_dependencies(gencoord_memory_suites ${target})
  set_property(GLOBAL APPEND PROPERTY GENCOORD_MEMORY_SUITE_LABELS ${label})
endfunction()

# writes the labels' expression; called once, after every suite is added
function(gencoord_write_memory_suite_labels)
  get_property(labels GLOBAL PROPERTY GENCOORD_MEMORY_SUITE_LABELS)
  list(REMOVE_DUPLICATES labels)
  list(SORT labels)
  list(JOIN labels "|" alternatives)
  file(CONFIGURE OUTPUT "${CMAKE_BINARY_DIR}/memory_suites.labels"
       CONTENT "^(${alternatives})$\n")
endfunction()
