# rrc_add_spirv_header(<target> <source.comp> <c-identifier> [DEPENDS includes...]
#                      [INCLUDE_DIRS dirs...] [DEFINES NAME=VALUE...])
# Compiles a GLSL shader with glslangValidator into a C header
# (${CMAKE_CURRENT_BINARY_DIR}/<c-identifier>.h, a uint32_t array named
# <c-identifier>) that <target> (an INTERFACE library) makes available, so the SPIR-V is embedded
# in the library and never loaded from disk.  #include looks next to the
# including file, in the source's directory, then in INCLUDE_DIRS (e.g.
# include/ for <rrc/rrc_values.h>); list every included file in DEPENDS so an
# edit rebuilds the shader.  DEFINES go to glslang as -DNAME=VALUE (one source, several modules).
find_program(GLSLANG_VALIDATOR NAMES glslangValidator glslang)
if(NOT GLSLANG_VALIDATOR)
  message(FATAL_ERROR "glslangValidator not found: install Debian's glslang-tools (README.md's commands do it).")
endif()

function(rrc_add_spirv_header target source identifier)
  cmake_parse_arguments(ARG "" "" "DEPENDS;INCLUDE_DIRS;DEFINES" ${ARGN})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${identifier}.h)
  set(include_flags)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I${dir})
  endforeach()
  foreach(def ${ARG_DEFINES})
    list(APPEND include_flags -D${def})
  endforeach()
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 --quiet
            -I${CMAKE_CURRENT_SOURCE_DIR} ${include_flags} --vn ${identifier} -o ${out}
            ${CMAKE_CURRENT_SOURCE_DIR}/${source}
    MAIN_DEPENDENCY ${CMAKE_CURRENT_SOURCE_DIR}/${source}
    DEPENDS ${ARG_DEPENDS}
    COMMENT "glslang: ${source} ${ARG_DEFINES} -> ${identifier}.h"
    VERBATIM)
  # A custom command's output is only visible in its own directory: a custom
  # target carries the build order to consumers elsewhere.
  add_custom_target(${identifier}_gen DEPENDS ${out})
  add_dependencies(${target} ${identifier}_gen)
  target_include_directories(${target} INTERFACE ${CMAKE_CURRENT_BINARY_DIR})
endfunction()
