# rrc-sample's figures, timings left out: runs the sample at 128x80 for 24
# frames (a 64-sample reference every 8th) and compares every figure of its
# summary.md but timings (the channels' settings, hit ratio, recall, false
# hits, the error tables) with summary_128x80.txt beside this script, to
# the digit.  The presets come from the library (rrc_channel_preset): a
# change to them, or to anything the sample or rrc computes, shows here.
#   cmake -DSAMPLE=<rrc-sample> -DWORK=<dir> [-DUPDATE=ON] -P summary_figures.cmake
# UPDATE=ON rewrites the checked-in file (after a change meant to move the figures).
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${SAMPLE} --frames 24 --size 128x80 --reference-every 8 --reference-samples 64 --no-images --quiet
                        --out ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rrc-sample failed (${rc}):\n${out}\n${err}")
endif()
file(STRINGS ${WORK}/summary.md lines)
set(figures "")
foreach(line IN LISTS lines)
  # The channels, the hit and visibility figures, the error table and the per-checkpoint rows.
  if(line MATCHES "^- (pcf|env|soft):" OR line MATCHES "^- (hit ratio|against true visibility|visible pixels)"
     OR line MATCHES "^\\| (pcf|env|soft)" OR line MATCHES "^\\| [0-9]+ \\| (pcf|env|soft) \\|")
    string(APPEND figures "${line}\n")
  endif()
endforeach()
set(golden ${CMAKE_CURRENT_LIST_DIR}/summary_128x80.txt)
if(UPDATE)
  file(WRITE ${golden} "${figures}")
  message(STATUS "rewrote ${golden}")
  return()
endif()
file(READ ${golden} expected)
if(NOT figures STREQUAL expected)
  file(WRITE ${WORK}/figures.txt "${figures}")
  execute_process(COMMAND diff ${golden} ${WORK}/figures.txt OUTPUT_VARIABLE d)
  message(FATAL_ERROR "rrc-sample's figures changed (${golden} against ${WORK}/figures.txt):\n${d}")
endif()
string(REGEX MATCHALL "\n" n "${figures}")
list(LENGTH n count)
message(STATUS "rrc-sample's ${count} lines of figures are unchanged")
