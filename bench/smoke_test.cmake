# The bench's smoke test (ctest bench_smoke): rrc-bench at a tiny size on
# configurations that between them use every read and write of the roof,
# under the Khronos validation layer with synchronization validation.  It
# fails on any validation message, on roof outputs that are not exact
# copies of their inputs (read back and compared), on a missing row or a
# time that is not reported as a number, and on roof bytes that disagree with
# the per-pixel figures below, written out here independently of the C++
# bookkeeping.  No timed assertion: the machine is shared and noisy, so a time
# is checked for its presence, never for its value (tests/lint/timed_assertions.py).
#   cmake -DBENCH=<rrc-bench> -DOUT=<dir> -P smoke_test.cmake
cmake_minimum_required(VERSION 3.25)

set(width 128)
set(height 64)
# name -> bytes read and written per pixel (docs/measurements/PERFORMANCE.md, "The roof").
set(expect_base "32;9")               # depth 4, PREV_CLIP 16, prev depth 4, samples 4, fp16 history 2, age 2 | mask 1, depth copy 4, value 2, age 2
set(expect_ch_2x4 "76;25")            # 2 x (samples 16, history 8, age 2) | 2 x (values 8, age 2)
set(expect_fp32 "34;11")              # fp32 history 4 | value 4
set(expect_confidence "40;13")        # + confidence 4, previous weight 4 | + weight 4
set(expect_nocache "33;9")            # + nocache 1
set(expect_object_id "40;13")         # + ids 4, previous ids 4 | + ids copy 4
set(expect_src_motion "24;9")         # RG32F motion 8
set(expect_src_motion_depth "32;9")   # rgb in RGBA32F 16
set(expect_src_camera "16;9")         # no per-pixel reprojection data
set(expect_standalone "32;9")
set(expect_rectify "32;9")          # rectification reads 8 more samples: no byte more the API implies
set(expect_fill "32;9")             # the fill (no fallback) rereads what the frame wrote: no byte more
set(expect_fill_r1 "32;9")
set(expect_filter_gaussian "32;9")  # 16 history taps, the same unique bytes
set(expect_young12 "33;9")          # nocache on a larger share: the same bytes as nocache
set(expect_young12_fill "33;9")
set(expect_residual "32;9")          # the base (4 bytes a pixel) is read by rrc, not by the roof: its ratio overstates by that
set(configs base ch_2x4 fp32 confidence nocache object_id src_motion src_motion_depth src_camera standalone rectify fill fill_r1 filter_gaussian
            young12 young12_fill residual)
list(JOIN configs "," config_arg)

file(REMOVE_RECURSE "${OUT}")
execute_process(
  COMMAND "${BENCH}" --size ${width}x${height} --reps 2 --warmup 1 --validation --check-roof --no-plot --config ${config_arg} --out "${OUT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rrc-bench failed (${rc}):\n${out}\n${err}")
endif()

file(READ "${OUT}/bench.json" json)
string(JSON messages GET "${json}" validation_messages)
string(JSON validation GET "${json}" validation)
if(NOT messages EQUAL 0 OR NOT validation)
  message(FATAL_ERROR "validation: on=${validation}, ${messages} message(s)")
endif()
string(JSON nrows LENGTH "${json}" rows)
list(LENGTH configs nconfigs)
if(NOT nrows EQUAL nconfigs)
  message(FATAL_ERROR "${nrows} rows for ${nconfigs} configurations")
endif()

math(EXPR last "${nrows} - 1")
set(pixels 8192)  # 128 x 64
foreach(i RANGE ${last})
  string(JSON name GET "${json}" rows ${i} name)
  if(NOT DEFINED expect_${name})
    message(FATAL_ERROR "unexpected row ${name}")
  endif()
  list(REMOVE_ITEM configs ${name})
  # Each time is reported: a JSON number (rrc-bench writes null for one it has not).
  foreach(key kernel_ms_median roof_ms_median ratio_median kernel_ms_min roof_ms_min wall_ms_median)
    string(JSON type TYPE "${json}" rows ${i} ${key})
    if(NOT type STREQUAL "NUMBER")
      message(FATAL_ERROR "${name}: ${key} is ${type}, not a number")
    endif()
  endforeach()
  # The young fraction is read back from the statistics frame: a share of the pixels.
  string(JSON young GET "${json}" rows ${i} young_fraction)
  if(young LESS 0 OR young GREATER 1)
    message(FATAL_ERROR "${name}: young_fraction ${young} outside [0, 1]")
  endif()
  string(JSON check GET "${json}" rows ${i} roof_check)
  if(NOT check STREQUAL "exact")
    message(FATAL_ERROR "${name}: roof outputs are not exact copies: ${check}")
  endif()
  string(JSON r GET "${json}" rows ${i} bytes_read)
  string(JSON w GET "${json}" rows ${i} bytes_written)
  string(JSON total GET "${json}" rows ${i} bytes)
  string(JSON br GET "${json}" rows ${i} bound_bytes_read)
  string(JSON bw GET "${json}" rows ${i} bound_bytes_written)
  list(GET expect_${name} 0 er)
  list(GET expect_${name} 1 ew)
  math(EXPR er "${er} * ${pixels}")
  math(EXPR ew "${ew} * ${pixels}")
  math(EXPR sum "${r} + ${w}")
  if(NOT r EQUAL er OR NOT w EQUAL ew OR NOT br EQUAL r OR NOT bw EQUAL w OR NOT total EQUAL sum)
    message(FATAL_ERROR "${name}: bytes read/written ${r}/${w} (bound ${br}/${bw}, total ${total}), expected ${er}/${ew}")
  endif()
  if(name STREQUAL "standalone")
    string(JSON fps_type TYPE "${json}" rows ${i} standalone_fps)
    string(JSON sb GET "${json}" rows ${i} standalone_bytes)
    if(NOT fps_type STREQUAL "NUMBER" OR NOT sb GREATER 0)
      message(FATAL_ERROR "standalone: fps is ${fps_type}, not a number, or bytes ${sb} not positive")
    endif()
  endif()
endforeach()
if(configs)
  message(FATAL_ERROR "no row for: ${configs}")
endif()
foreach(f bench.csv report.md)
  if(NOT EXISTS "${OUT}/${f}")
    message(FATAL_ERROR "${f} not written")
  endif()
endforeach()
message(STATUS "rrc-bench smoke: ${nrows} configurations, 0 validation messages, roof outputs exact, bytes consistent")
