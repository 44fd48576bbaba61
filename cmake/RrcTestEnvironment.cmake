# The environment every test program runs in (RRC_TEST_ENV) and
# rrc_test_environment(<target>), which applies it.  Included from the
# top-level CMakeLists.txt before host_sample/ so the examples there can
# register tests too; tests/CMakeLists.txt explains the suite's rules.
# Tests run on lavapipe explicitly: Debian's driver package also installs
# Intel and Radeon ICDs.
file(GLOB RRC_LAVAPIPE_ICD /usr/share/vulkan/icd.d/lvp_icd.*.json)
if(NOT RRC_LAVAPIPE_ICD)
  message(FATAL_ERROR "lavapipe's ICD (mesa-vulkan-drivers) not found in /usr/share/vulkan/icd.d")
endif()
list(GET RRC_LAVAPIPE_ICD 0 RRC_LAVAPIPE_ICD)
set(RRC_TEST_ENV
  "VK_ICD_FILENAMES=${RRC_LAVAPIPE_ICD}"
  "VK_DRIVER_FILES=${RRC_LAVAPIPE_ICD}"
  "XDG_RUNTIME_DIR=${PROJECT_BINARY_DIR}/xdg"
  "RRC_TEST_DATA=${PROJECT_SOURCE_DIR}/tests/data"
  "RRC_VALIDATION=1")  # every context a test makes, the tools' included, runs under validation
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/xdg)

if(RRC_SANITIZE)
  # Keep drivers and layers mapped so leaks inside them are named, then
  # suppress those by library (tests/sanitizer/lsan.supp); rrc's own leaks fail.
  set(_rrc_sanitizer_dir ${PROJECT_SOURCE_DIR}/tests/sanitizer)
  set(_rrc_keep_dir ${PROJECT_BINARY_DIR}/tests)
  add_library(rrc_keep_libraries_loaded SHARED ${_rrc_sanitizer_dir}/keep_libraries_loaded.c)
  set_target_properties(rrc_keep_libraries_loaded PROPERTIES COMPILE_OPTIONS "" LINK_OPTIONS ""
    LIBRARY_OUTPUT_DIRECTORY ${_rrc_keep_dir})
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libasan.so OUTPUT_VARIABLE RRC_LIBASAN OUTPUT_STRIP_TRAILING_WHITESPACE)
  list(APPEND RRC_TEST_ENV
    "LD_PRELOAD=${RRC_LIBASAN}:${_rrc_keep_dir}/librrc_keep_libraries_loaded.so"
    "ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1"
    "LSAN_OPTIONS=suppressions=${_rrc_sanitizer_dir}/lsan.supp:print_suppressions=0"
    "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1")
endif()

# Test programs run through `cmake -E env` with RRC_TEST_ENV: the target's
# emulator is honoured by gtest discovery and by every add_test, whereas a
# list-valued ENVIRONMENT property is split apart by gtest_discover_tests.
function(rrc_test_environment target)
  set_target_properties(${target} PROPERTIES CROSSCOMPILING_EMULATOR "${CMAKE_COMMAND};-E;env;${RRC_TEST_ENV}")
endfunction()
