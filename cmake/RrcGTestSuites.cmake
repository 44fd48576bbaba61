# rrc_gtest_suites(<target> [TEST_FILTER <gtest filter>] [LABELS <label>...]
#                  [UNIT_SUITES <suite>...]):
# registers one CTest test per GoogleTest test suite of <target>, named
# "<target>/<suite>" (for example `rrc_api_test/Api`), which runs that suite's
# cases in one process.
#
# Why not gtest_discover_tests (one process per case): a test process's first
# Vulkan context costs about 0.35 s more than the next ones in the same process
# (fresh pages for the driver's and the library's allocations, the driver and
# the validation layer loaded and relocated), more under the sanitizers, and
# the suite has some 700 cases (docs/measurements/PERFORMANCE.md, "The test suite's time").
# A case still gets a fresh context of its own: every test makes its context
# (tests/support/rrc_test_context.h), so a validation message fails the case
# that caused it, and the output of a failed suite names the failing cases.
#
# The tests are listed after each build (--gtest_list_tests, through the
# target's CROSSCOMPILING_EMULATOR: rrc_test_environment's lavapipe
# environment).  TEST_FILTER keeps the cases it matches (one executable can be
# registered twice, with complementary filters and different labels); a
# suite's test then runs exactly the listed cases.
#
# LABELS go to every suite's test; a suite named in UNIT_SUITES (as in its
# test's name, e.g. `Cases/Golden`) gets the label `unit` too: the fast tier,
# `ctest -L unit`.  Labels are applied when ctest reads the tests, from this
# configuration, so a change of labels needs no rebuild; a unit suite the
# program does not list becomes a failing test of the tier, so a renamed suite
# cannot leave it unnoticed.
set(RRC_GTEST_SUITES_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/RrcGTestSuitesList.cmake)

function(rrc_gtest_suites target)
  cmake_parse_arguments(ARG "" "TEST_FILTER" "LABELS;UNIT_SUITES" ${ARGN})
  # One output file per registration of the target (the filtered pairs).
  get_property(calls TARGET ${target} PROPERTY RRC_GTEST_SUITES_CALLS)
  if(NOT calls)
    set(calls 0)
  endif()
  math(EXPR calls "${calls} + 1")
  set_property(TARGET ${target} PROPERTY RRC_GTEST_SUITES_CALLS ${calls})

  # Under the sanitizers a test program's own sources build at -O0: the same
  # checks, half the compile time of -O1, and its tests' time is spent in the
  # driver, the reference and the programs' libraries, which keep -O1
  # (docs/measurements/PERFORMANCE.md, "The test suite's time").
  if(RRC_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
  endif()

  # A release-pass label: the release build makes this executable (CMakeLists.txt, rrc_release_pass).
  foreach(label IN LISTS ARG_LABELS)
    if(label IN_LIST RRC_RELEASE_PASS_LABELS)
      add_dependencies(rrc_release_pass ${target})
      break()
    endif()
  endforeach()

  set(base "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites${calls}")
  get_target_property(emulator ${target} CROSSCOMPILING_EMULATOR)
  if(NOT emulator)
    set(emulator "")
  endif()
  # The listing's inputs, written once generator expressions are known.
  file(GENERATE OUTPUT "${base}_args.cmake" CONTENT
"set(TEST_EXECUTABLE [==[$<TARGET_FILE:${target}>]==])
set(TEST_EXECUTOR [==[${emulator}]==])
set(TEST_TARGET [==[${target}]==])
set(TEST_FILTER [==[${ARG_TEST_FILTER}]==])
set(TEST_WORKING_DIRECTORY [==[${CMAKE_CURRENT_BINARY_DIR}]==])
set(TEST_OUTPUT [==[${base}_tests.cmake]==])
")
  # Relinked, and so listed again, when the listing's script or inputs change.
  set_property(TARGET ${target} APPEND PROPERTY LINK_DEPENDS "${base}_args.cmake" ${RRC_GTEST_SUITES_SCRIPT})
  add_custom_command(TARGET ${target} POST_BUILD
    BYPRODUCTS "${base}_tests.cmake"
    COMMAND ${CMAKE_COMMAND} -D "ARGS_FILE=${base}_args.cmake" -P ${RRC_GTEST_SUITES_SCRIPT}
    VERBATIM)
  # ctest reads the listed tests; before the target is built there are none,
  # and a test named after the target says so.  The listing sets
  # rrc_listed_suites; the labels follow from this call's arguments.
  file(WRITE "${base}_include.cmake"
"if(EXISTS [==[${base}_tests.cmake]==])
  set(rrc_listed_suites \"\")
  include([==[${base}_tests.cmake]==])
  set(rrc_unit_suites [==[${ARG_UNIT_SUITES}]==])
  foreach(rrc_suite IN LISTS rrc_listed_suites)
    set(rrc_labels [==[${ARG_LABELS}]==])
    list(FIND rrc_unit_suites \"\${rrc_suite}\" rrc_at)
    if(NOT rrc_at EQUAL -1)
      list(APPEND rrc_labels unit)
    endif()
    if(rrc_labels)
      set_tests_properties(\"${target}/\${rrc_suite}\" PROPERTIES LABELS \"\${rrc_labels}\")
    endif()
  endforeach()
  foreach(rrc_suite IN LISTS rrc_unit_suites)
    list(FIND rrc_listed_suites \"\${rrc_suite}\" rrc_at)
    if(rrc_at EQUAL -1)
      add_test(\"${target}/\${rrc_suite}_NOT_LISTED\" \"${target}/\${rrc_suite}_NOT_LISTED\")
      set_tests_properties(\"${target}/\${rrc_suite}_NOT_LISTED\" PROPERTIES LABELS unit)
    endif()
  endforeach()
else()
  add_test([==[${target}_NOT_BUILT]==] [==[${target}_NOT_BUILT]==])
endif()
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${base}_include.cmake")
endfunction()
