# Installs rrc into a fresh prefix, then builds and runs the minimal C host
# (host_sample/examples/minimal_standalone.c) twice: with find_package(rrc)
# and with pkg-config.
# -DBUILD_DIR=<rrc build> -DSOURCE_DIR=<rrc source> -DWORK=<scratch dir>
# -DLIBRARY_ONLY=ON: installs with README's library-only command instead
# (.ci/install-library, its own Release build of the library alone).
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
if(LIBRARY_ONLY)
  run(bash ${SOURCE_DIR}/.ci/install-library ${prefix} ${WORK}/library-build)
  # The library alone: no test, program or benchmark was configured.
  foreach(target_dir tests host_sample bench)
    if(EXISTS ${WORK}/library-build/${target_dir})
      message(FATAL_ERROR "the library-only build configured ${target_dir}/")
    endif()
  endforeach()
else()
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
endif()
include(GNUInstallDirs)
set(libdir ${prefix}/${CMAKE_INSTALL_LIBDIR})
foreach(f include/rrc/rrc.h include/rrc/rrc_vulkan.h ${CMAKE_INSTALL_LIBDIR}/cmake/rrc/rrcConfig.cmake
          ${CMAKE_INSTALL_LIBDIR}/cmake/rrc/rrcConfigVersion.cmake ${CMAKE_INSTALL_LIBDIR}/pkgconfig/rrc.pc)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install is missing ${f}")
  endif()
endforeach()

# 1. CMake package.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK}/cmake -DCMAKE_PREFIX_PATH=${prefix}
    -DRRC_MINIMAL_HOST=${SOURCE_DIR}/host_sample/examples/minimal_standalone.c)
run(${CMAKE_COMMAND} --build ${WORK}/cmake)
run(${WORK}/cmake/minimal_standalone)

# 2. pkg-config, with the C compiler directly.
find_program(PKG_CONFIG pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${libdir}/pkgconfig)
execute_process(COMMAND ${PKG_CONFIG} --cflags --libs rrc OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config does not find rrc in ${libdir}/pkgconfig")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run(cc -std=c99 -pedantic-errors -Wall -Wextra -Werror ${SOURCE_DIR}/host_sample/examples/minimal_standalone.c ${flags}
    -Wl,-rpath,${libdir} -o ${WORK}/minimal_standalone_pkgconfig)
run(${WORK}/minimal_standalone_pkgconfig)
