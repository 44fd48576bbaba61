# The test environment every test program runs in, and rrc_add_gtest().
# Tests are registered one per GoogleTest suite (RrcGTestSuites.cmake).
# Included from the top-level CMakeLists.txt before host_sample/ and tests/,
# so each program registers its tests from its own folder.
#
# Every Vulkan test creates its context with VK_LAYER_KHRONOS_validation and
# synchronization validation enabled (tests/support/rrc_test_context.h) and
# fails on any message.  Tests run on lavapipe explicitly: Debian's driver
# package also installs Intel and Radeon ICDs.
find_package(GTest REQUIRED)
include(${CMAKE_CURRENT_LIST_DIR}/RrcGTestSuites.cmake)

file(GLOB RRC_LAVAPIPE_ICD /usr/share/vulkan/icd.d/lvp_icd.*.json)
if(NOT RRC_LAVAPIPE_ICD)
  message(FATAL_ERROR "lavapipe's ICD (mesa-vulkan-drivers) not found in /usr/share/vulkan/icd.d")
endif()
list(GET RRC_LAVAPIPE_ICD 0 RRC_LAVAPIPE_ICD)
set(RRC_TEST_ENV
  "VK_ICD_FILENAMES=${RRC_LAVAPIPE_ICD}"
  "VK_DRIVER_FILES=${RRC_LAVAPIPE_ICD}"
  "XDG_RUNTIME_DIR=${CMAKE_BINARY_DIR}/xdg"
  "RRC_TEST_DATA=${PROJECT_SOURCE_DIR}/tests/data"
  "RRC_VALIDATION=1")  # every context a test makes, the tools' included, runs under validation
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/xdg)

if(RRC_SANITIZE)
  # Keep drivers and layers mapped so leaks inside them are named, then
  # suppress those by library (sanitizer/lsan.supp); rrc's own leaks fail.
  add_library(rrc_keep_libraries_loaded SHARED ${PROJECT_SOURCE_DIR}/tests/sanitizer/keep_libraries_loaded.c)
  set_target_properties(rrc_keep_libraries_loaded PROPERTIES COMPILE_OPTIONS "" LINK_OPTIONS ""
    LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libasan.so OUTPUT_VARIABLE RRC_LIBASAN OUTPUT_STRIP_TRAILING_WHITESPACE)
  list(APPEND RRC_TEST_ENV
    "LD_PRELOAD=${RRC_LIBASAN}:${PROJECT_BINARY_DIR}/tests/librrc_keep_libraries_loaded.so"
    "ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1"
    "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/tests/sanitizer/lsan.supp:print_suppressions=0"
    "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1")
endif()

# Test programs run through `cmake -E env` with RRC_TEST_ENV: the target's
# emulator is honoured by the test listing (rrc_gtest_suites) and by every
# add_test, and one list of variables holds the whole environment.
function(rrc_test_environment target)
  set_target_properties(${target} PROPERTIES CROSSCOMPILING_EMULATOR "${CMAKE_COMMAND};-E;env;${RRC_TEST_ENV}")
endfunction()

# rrc_add_gtest(<name> sources... [LIBS libs...] [LABELS labels...]
#               [UNIT_SUITES suites...]): a GoogleTest executable whose test
# suites each become a CTest test with the lavapipe environment; LABELS and
# UNIT_SUITES as rrc_gtest_suites (RrcGTestSuites.cmake) takes them.
function(rrc_add_gtest name)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS;UNIT_SUITES" ${ARGN})
  add_executable(${name} ${ARG_UNPARSED_ARGUMENTS})
  target_include_directories(${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/tests)
  target_link_libraries(${name} PRIVATE rrc rrc_descs GTest::gtest_main ${ARG_LIBS})  # rrc_descs: support/rrc_test_context.h
  rrc_test_environment(${name})
  rrc_gtest_suites(${name} LABELS ${ARG_LABELS} UNIT_SUITES ${ARG_UNIT_SUITES})
endfunction()

