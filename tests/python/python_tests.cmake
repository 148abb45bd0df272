# SPDX-License-Identifier: BSD-3-Clause
# gencoord_add_python_generator_tests(<python>): a CTest test per module of tests/python,
# run by <python> with unittest, named generator_sympy<version>.<module> and labelled
# `generator`.
#
# COST is each module's seconds with SymPy 1.11 on 2 busy cores (ctest -j 2 of the whole
# suite): CTest starts the costliest first, so the longest modules do not end the run alone
# on one core. A module missing here (a few seconds or less) costs 2. After a run CTest keeps
# its own measured costs in the build folder and uses those.
set(_GENCOORD_PYTHON_TEST_COST
  test_recursive 120 test_bad_models 56 test_golden 45 test_cli 15 test_name_clashes 14
  test_interrupts 14 test_translation_units 13 test_rigid_bodies 9 test_bad_atlas 6
  test_urdf 5 test_refused_inputs 4 test_split 4 test_structured 4 test_user_models 4
  test_independent_derivation 3 test_zero_fill 3
)

function(gencoord_add_python_generator_tests python)
  execute_process(COMMAND "${python}" -c "import sympy; print(sympy.__version__)"
                  OUTPUT_VARIABLE sympy_version OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "gencoord: ${python} cannot import sympy, so it cannot run the "
                        "generator's tests; name another in GENCOORD_TEST_PYTHONS")
  endif()
  if(TEST "generator_sympy${sympy_version}.test_golden")
    return()  # an interpreter with the same SymPy already runs them
  endif()
  file(GLOB modules RELATIVE "${CMAKE_CURRENT_FUNCTION_LIST_DIR}"
       "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/test_*.py")
  list(SORT modules)
  foreach(file IN LISTS modules)
    string(REGEX REPLACE "\\.py$" "" module "${file}")
    set(name "generator_sympy${sympy_version}.${module}")
    add_test(NAME "${name}"
             COMMAND ${CMAKE_COMMAND} -E env PYTHONHASHSEED=0
                     "${python}" -m unittest "tests.python.${module}" -v
             WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
    set(cost 2)
    list(FIND _GENCOORD_PYTHON_TEST_COST "${module}" at)
    if(at GREATER -1)
      math(EXPR at "${at} + 1")
      list(GET _GENCOORD_PYTHON_TEST_COST ${at} cost)
    endif()
    set_tests_properties("${name}" PROPERTIES LABELS generator COST ${cost} TIMEOUT 1500)
  endforeach()
endfunction()
