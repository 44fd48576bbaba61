# Fails when an example outgrows its budget, counted as `wc -l` counts (newlines):
# minimal_standalone.c 120 lines, every file of interop/ (C++ and GLSL) 380, the
# C++ formatted with .clang-format (raster pass, validation, frame and shading
# cache, checks).
# cmake -DDIR=<host_sample/examples> -P line_budget.cmake
function(count_lines out)
  set(total 0)
  foreach(file ${ARGN})
    file(READ ${file} text)
    string(REGEX MATCHALL "\n" newlines "${text}")
    list(LENGTH newlines n)
    math(EXPR total "${total} + ${n}")
  endforeach()
  set(${out} ${total} PARENT_SCOPE)
endfunction()

set(failed FALSE)
file(GLOB interop ${DIR}/interop/*)
foreach(budget "120;${DIR}/minimal_standalone.c" "380;${interop}")
  list(POP_FRONT budget limit)
  count_lines(lines ${budget})
  message(STATUS "${lines} of ${limit} lines: ${budget}")
  if(lines GREATER limit)
    set(failed TRUE)
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "an example is over its line budget")
endif()
