# Run after a test program is built (cmake -D ARGS_FILE=... -P, from
# rrc_gtest_suites in RrcGTestSuites.cmake): lists its GoogleTest cases and
# writes one add_test per test suite to TEST_OUTPUT, and the suites' names
# (labels come later, from the configuration: rrc_gtest_suites).
include(${ARGS_FILE})

set(list_command ${TEST_EXECUTOR} ${TEST_EXECUTABLE} --gtest_list_tests)
if(TEST_FILTER)
  list(APPEND list_command "--gtest_filter=${TEST_FILTER}")
endif()
execute_process(COMMAND ${list_command}
  WORKING_DIRECTORY ${TEST_WORKING_DIRECTORY}
  TIMEOUT 60
  RESULT_VARIABLE result
  OUTPUT_VARIABLE listing
  ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "listing the tests of ${TEST_EXECUTABLE} failed (${result}):\n${listing}\n${errors}")
endif()

# --gtest_list_tests prints "Suite." on its own line (a typed or parameterized
# suite adds "  # TypeParam = ..."), then each case indented by two spaces
# ("  Case" or "  Case/param  # GetParam() = ..."), after gtest_main's
# "Running main() from ..." line.
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(suites "")
set(suite "")
set(suite_count 0)
foreach(line IN LISTS lines)
  string(REGEX REPLACE " *#.*$" "" line "${line}")
  if(line MATCHES "^  ([^ ]+)$")
    if(suite STREQUAL "")
      message(FATAL_ERROR "a case before any suite in the listing of ${TEST_EXECUTABLE}: ${line}")
    endif()
    list(APPEND cases_${suite_count} "${suite}.${CMAKE_MATCH_1}")
  elseif(line MATCHES "^([^ ]+)\\.$")
    set(suite "${CMAKE_MATCH_1}")
    math(EXPR suite_count "${suite_count} + 1")
    list(APPEND suites "${suite}")
  elseif(NOT line STREQUAL "" AND NOT line MATCHES "^Running main\\(\\) from ")  # gtest_main's banner
    message(FATAL_ERROR "unexpected line in the listing of ${TEST_EXECUTABLE}: '${line}'")
  endif()
endforeach()
if(NOT suites)
  message(FATAL_ERROR "${TEST_EXECUTABLE} lists no tests (filter: '${TEST_FILTER}')")
endif()

set(executor_args "")
foreach(arg IN LISTS TEST_EXECUTOR)
  string(APPEND executor_args " [==[${arg}]==]")
endforeach()
set(content "# Written by cmake/RrcGTestSuitesList.cmake after building ${TEST_TARGET}.\n")
set(index 0)
foreach(suite IN LISTS suites)
  math(EXPR index "${index} + 1")
  if(TEST_FILTER)
    # Exactly the listed cases: gtest's filter cannot intersect two patterns.
    list(JOIN cases_${index} ":" filter)
  else()
    set(filter "${suite}.*")
  endif()
  set(name "${TEST_TARGET}/${suite}")
  string(APPEND content "add_test([==[${name}]==]${executor_args} [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${filter}]==])\n")
  string(APPEND content "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${TEST_WORKING_DIRECTORY}]==])\n")
endforeach()
# The suites, for the labels rrc_gtest_suites' include file gives them.
string(APPEND content "set(rrc_listed_suites [==[${suites}]==])\n")
file(WRITE ${TEST_OUTPUT} "${content}")
