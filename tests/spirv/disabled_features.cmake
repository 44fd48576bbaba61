# A disabled feature costs nothing (docs/PERFORMANCE.md): for each optional
# feature of the kernels (compute/rrc_pass_*.comp, one module a pass), the
# specialised SPIR-V of a configuration without it must equal, module by
# module, the SPIR-V built with the feature's code removed (-DRRC_WITHOUT_<F>:
# its specialization constant becomes a plain `const false` / `0u`).
#
#   cmake -DGLSLANG=glslangValidator -DSPIRV_OPT=spirv-opt -DSPIRV_REMAP=spirv-remap
#         -DSPIRV_DIS=spirv-dis -DKERNEL_DIR=compute -DINCLUDE_DIR=include
#         -DWORK_DIR=/tmp/rrc_spirv -P tests/spirv/disabled_features.cmake
#
# Per variant: glslangValidator -V --target-env vulkan1.1 (as cmake/SPIRV.cmake), then
#   spirv-opt [--set-spec-const-default-value "<base>"] --freeze-spec-const
#             --fold-spec-const-op-composite -O      (specialise, remove dead code)
#   spirv-remap --map all --strip all               (canonical ids, no names)
#   spirv-opt --compact-ids                          (ids by first appearance)
# and the two modules must be byte-identical.
#
# --fold-spec-const-op-composite is needed: -O alone folds no OpSpecConstantOp,
# so every branch on a spec-constant expression (`RRC_CH < CH_COUNT`, the
# DEPTH_MODE and SOURCE tests, ...) survives freezing with its code.
# --compact-ids is needed: spirv-remap's ids still depend on the input's
# numbering (where its hashes collide), so two modules equal up to renaming
# can differ in ids when the front end numbered them differently (CONFIDENCE:
# four spec constants against one shared `false`, three ids more).  Neither
# step can hide code: both run on both sides, and the compared modules keep
# every instruction, in order.
#
# A new feature: add its -DRRC_WITHOUT_<F> to the kernels and <F> to
# `features` with its ids (F_<F>_IDS) and "on" value below.
#
# Every base is checked three ways per feature: some module really has (and,
# built without the feature, none has) the feature's SpecId, the two "off"
# builds of every module are equal, and the instruction counts with the
# feature on are reported (where "on" equals "off", the feature has no code
# in that base and module).
cmake_minimum_required(VERSION 3.21)  # file(COPY_FILE)

foreach(var GLSLANG SPIRV_OPT SPIRV_REMAP SPIRV_DIS KERNEL_DIR INCLUDE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "disabled_features.cmake: -D${var}=... is required")
  endif()
endforeach()
# The passes' modules (compute/CMakeLists.txt builds the same list).
set(modules frame list copy_out fill)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/remap)

# ---- Specialization-constant ids, read from the kernel interface -----------
file(READ ${KERNEL_DIR}/rrc_kernel_interface.h interface)
function(rrc_define name out)
  if(NOT interface MATCHES "#define ${name} ([0-9]+)")
    message(FATAL_ERROR "rrc_kernel_interface.h defines no ${name}")
  endif()
  set(${out} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()
foreach(c SOURCE DEPTH_MODE HAS_NOCACHE CHANNEL_COUNT INTEROP STATS HOST_AGE_MASK ADAPTIVE OBJECT_ID CHANNEL_SLOTS)
  rrc_define(RRC_SPEC_${c} ID_${c})
endforeach()
# id of property k of slot c: first + slots*k + c, first = 16 (RRC_SPEC_CHANNEL,
# RRC_CHANNEL_PROPERTY_*) or 0.4's second range (RRC_SPEC_CHANNEL2, RRC_CHANNEL2_PROPERTY_*).
if(NOT interface MATCHES "RRC_SPEC_CHANNEL2\\(property, slot\\) \\(([0-9]+) \\+")
  message(FATAL_ERROR "rrc_kernel_interface.h defines no RRC_SPEC_CHANNEL2")
endif()
set(ID_CHANNEL2_FIRST ${CMAKE_MATCH_1})
# 0.6's third range (RRC_SPEC_CHANNEL3, RRC_CHANNEL3_PROPERTY_*).
if(NOT interface MATCHES "RRC_SPEC_CHANNEL3\\(property, slot\\) \\(([0-9]+) \\+")
  message(FATAL_ERROR "rrc_kernel_interface.h defines no RRC_SPEC_CHANNEL3")
endif()
set(ID_CHANNEL3_FIRST ${CMAKE_MATCH_1})
function(rrc_slot_ids prefix first property out)
  rrc_define(${prefix}_${property} k)
  set(ids "")
  math(EXPR last "${ID_CHANNEL_SLOTS} - 1")
  foreach(c RANGE ${last})
    math(EXPR id "${first} + ${ID_CHANNEL_SLOTS} * ${k} + ${c}")
    list(APPEND ids ${id})
  endforeach()
  set(${out} ${ids} PARENT_SCOPE)
endfunction()
foreach(p COMPONENTS FP16 BLEND FILTER CONFIDENCE)
  rrc_slot_ids(RRC_CHANNEL_PROPERTY 16 ${p} IDS_${p})
endforeach()
foreach(p RECTIFY FILL_AGE ANTILAG)
  rrc_slot_ids(RRC_CHANNEL2_PROPERTY ${ID_CHANNEL2_FIRST} ${p} IDS_${p})
endforeach()
rrc_slot_ids(RRC_CHANNEL3_PROPERTY ${ID_CHANNEL3_FIRST} BLUR_BOUND IDS_BLUR_BOUND)
rrc_slot_ids(RRC_CHANNEL3_PROPERTY ${ID_CHANNEL3_FIRST} VIEW_LOBE IDS_VIEW_LOBE)
rrc_slot_ids(RRC_CHANNEL3_PROPERTY ${ID_CHANNEL3_FIRST} RESIDUAL IDS_RESIDUAL)

# Feature -> its spec ids and the value that turns it on.
set(features NOCACHE INTEROP ADAPTIVE OBJECT_ID CONFIDENCE STATS HOST_AGE RECTIFY FILL ANTILAG BLUR_BOUND VIEW_LOBE RESIDUAL)
set(F_NOCACHE_IDS ${ID_HAS_NOCACHE})
set(F_INTEROP_IDS ${ID_INTEROP})
set(F_ADAPTIVE_IDS ${ID_ADAPTIVE})
set(F_OBJECT_ID_IDS ${ID_OBJECT_ID})
set(F_CONFIDENCE_IDS ${IDS_CONFIDENCE})
set(F_STATS_IDS ${ID_STATS})
set(F_HOST_AGE_IDS ${ID_HOST_AGE_MASK})
set(F_RECTIFY_IDS ${IDS_RECTIFY})
set(F_FILL_IDS ${IDS_FILL_AGE})
set(F_ANTILAG_IDS ${IDS_ANTILAG})
set(F_BLUR_BOUND_IDS ${IDS_BLUR_BOUND})
set(F_VIEW_LOBE_IDS ${IDS_VIEW_LOBE})
set(F_RESIDUAL_IDS ${IDS_RESIDUAL})
foreach(f IN LISTS features)
  set(F_${f}_ON true)
endforeach()
set(F_HOST_AGE_ON 15)  # every slot's age to the host
set(F_FILL_ON 4)       # fill_age 4 on every slot

# ---- Bases: the configuration around the feature ----------------------------
# Each: a list of "id:value" pairs, and the features checked there.
list(GET IDS_COMPONENTS 1 slot1_components)
list(GET IDS_FP16 1 slot1_fp16)
list(GET IDS_FILTER 1 slot1_filter)
list(GET IDS_BLEND 1 slot1_blend)
# defaults: what rrc_create's defaults specialise (every feature off).
set(base_names defaults interop all_on)
set(BASE_defaults_SET "")
# BLUR_BOUND (0.6), VIEW_LOBE (0.7) and RESIDUAL (0.9) are checked in all_on only: this check
# is the suite's slowest, and all_on is the strictest base (every other
# feature's code beside it).
set(BASE_defaults_FEATURES ${features})
list(REMOVE_ITEM BASE_defaults_FEATURES BLUR_BOUND VIEW_LOBE RESIDUAL)
# interop: host images, REVERSED depth, two channels: slot 0 the default
# packed fp16 scalar, slot 1 RGBA fp32, Catmull-Rom, AGE_AWARE.
set(BASE_interop_SET ${ID_INTEROP}:true ${ID_DEPTH_MODE}:1 ${ID_CHANNEL_COUNT}:2
    ${slot1_components}:4 ${slot1_fp16}:false ${slot1_filter}:2 ${slot1_blend}:1)
set(BASE_interop_FEATURES NOCACHE ADAPTIVE OBJECT_ID CONFIDENCE STATS HOST_AGE RECTIFY FILL ANTILAG)
# all_on: the interop base with every other feature on (leave one out;
# INTEROP itself off when it is the feature checked).
set(BASE_all_on_SET ${BASE_interop_SET})
set(BASE_all_on_FEATURES ${features})
set(BASE_all_on_OTHERS_ON TRUE)

# ---- Tools -------------------------------------------------------------------
function(rrc_run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}${err}")
  endif()
endfunction()

# Front end: <name>_<module>.spv for every module with the given -D defines,
# as the library builds them (cmake/SPIRV.cmake: --target-env vulkan1.1).
function(rrc_compile name)
  foreach(m IN LISTS modules)
    rrc_run(${GLSLANG} -V --target-env vulkan1.1 --quiet -I${KERNEL_DIR} -I${INCLUDE_DIR} ${ARGN}
            ${KERNEL_DIR}/rrc_pass_${m}.comp -o ${WORK_DIR}/${name}_${m}.spv)
  endforeach()
endfunction()

# The SpecIds the modules of <name> declare, all together.
function(rrc_spec_ids name out)
  set(ids "")
  foreach(m IN LISTS modules)
    execute_process(COMMAND ${SPIRV_DIS} ${WORK_DIR}/${name}_${m}.spv OUTPUT_VARIABLE dis RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "spirv-dis failed on ${name}_${m}.spv")
    endif()
    string(REGEX MATCHALL "SpecId [0-9]+" decorations "${dis}")
    string(REPLACE "SpecId " "" module_ids "${decorations}")
    list(APPEND ids ${module_ids})
  endforeach()
  set(${out} ${ids} PARENT_SCOPE)
endfunction()

# Specialise <src>.spv with the "id:value" list, optimise, canonicalise:
# <dst>.spv and its disassembly <dst>.dis; <count_out> = its instruction count.
# The same <src> with the same list gives the same module (the tools are
# deterministic): it is made once and copied, e.g. the `defaults` base's
# specialised module of a pass, the same for every feature checked there.
function(rrc_specialise src dst settings count_out)
  string(MD5 key "${src} ${settings}")
  if(DEFINED made_${key})
    file(COPY_FILE ${WORK_DIR}/${made_${key}}.spv ${WORK_DIR}/${dst}.spv)
    file(COPY_FILE ${WORK_DIR}/${made_${key}}.dis ${WORK_DIR}/${dst}.dis)
    set(${count_out} ${count_${key}} PARENT_SCOPE)
    return()
  endif()
  set(args "")
  if(settings)
    string(REPLACE ";" " " pairs "${settings}")
    set(args --set-spec-const-default-value "${pairs}")
  endif()
  rrc_run(${SPIRV_OPT} ${args} --freeze-spec-const --fold-spec-const-op-composite -O
          ${WORK_DIR}/${src}.spv -o ${WORK_DIR}/${dst}.opt.spv)
  rrc_run(${SPIRV_REMAP} --map all --strip all -i ${WORK_DIR}/${dst}.opt.spv -o ${WORK_DIR}/remap)
  rrc_run(${SPIRV_OPT} --compact-ids ${WORK_DIR}/remap/${dst}.opt.spv -o ${WORK_DIR}/${dst}.spv)
  rrc_run(${SPIRV_DIS} --raw-id --no-header --no-color ${WORK_DIR}/${dst}.spv -o ${WORK_DIR}/${dst}.dis)
  file(STRINGS ${WORK_DIR}/${dst}.dis lines REGEX "Op[A-Z]")
  list(LENGTH lines n)
  if(n EQUAL 0)
    message(FATAL_ERROR "${dst}: no instructions")
  endif()
  set(${count_out} ${n} PARENT_SCOPE)
  set(made_${key} ${dst} PARENT_SCOPE)
  set(count_${key} ${n} PARENT_SCOPE)
endfunction()

# Compares the specialised modules <a> and <b>: <verdict_out> = equal or DIFFERENT, and a
# difference joins `failures` under <label> with the two disassemblies to diff.
function(rrc_compare a b label verdict_out)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/${a}.spv ${WORK_DIR}/${b}.spv RESULT_VARIABLE differ)
  if(differ)
    set(${verdict_out} DIFFERENT PARENT_SCOPE)
    set(failures ${failures} "${label}: ${WORK_DIR}/${a}.dis vs ${WORK_DIR}/${b}.dis" PARENT_SCOPE)
  else()
    set(${verdict_out} equal PARENT_SCOPE)
  endif()
endfunction()

# ---- The check ---------------------------------------------------------------
rrc_compile(spec)
rrc_spec_ids(spec spec_ids)
foreach(f IN LISTS features)
  rrc_compile(without_${f} -DRRC_WITHOUT_${f})
  rrc_spec_ids(without_${f} without_ids)
  foreach(id IN LISTS F_${f}_IDS)
    # Else the check would compare a build with itself, or miss the feature.
    if(NOT id IN_LIST spec_ids)
      message(FATAL_ERROR "${f}: no kernel declares SpecId ${id}")
    endif()
    if(id IN_LIST without_ids)
      message(FATAL_ERROR "${f}: built with -DRRC_WITHOUT_${f}, a kernel still declares SpecId ${id}")
    endif()
  endforeach()
endforeach()

set(table "")
set(failures "")
foreach(base IN LISTS base_names)
  foreach(f IN LISTS BASE_${base}_FEATURES)
    # The configuration without f: the base, every other feature on in all_on.
    set(off ${BASE_${base}_SET})
    if(BASE_${base}_OTHERS_ON)
      foreach(g IN LISTS features)
        if(NOT g STREQUAL f)
          foreach(id IN LISTS F_${g}_IDS)
            list(APPEND off ${id}:${F_${g}_ON})
          endforeach()
        endif()
      endforeach()
    endif()
    list(REMOVE_DUPLICATES off)  # INTEROP: in the base and among the others
    # f's own constants keep their defaults (off), whatever the base sets.
    foreach(id IN LISTS F_${f}_IDS)
      list(FILTER off EXCLUDE REGEX "^${id}:")
    endforeach()
    set(on ${off})
    foreach(id IN LISTS F_${f}_IDS)
      list(APPEND on ${id}:${F_${f}_ON})
    endforeach()
    foreach(m IN LISTS modules)
      rrc_specialise(spec_${m} ${base}_${f}_${m}_spec "${off}" n_spec)
      rrc_specialise(without_${f}_${m} ${base}_${f}_${m}_removed "${off}" n_removed)
      string(MD5 key "${m} ${on}")
      if(NOT DEFINED on_count_${key})  # all_on: one "every feature on" module a pass
        rrc_specialise(spec_${m} ${base}_${f}_${m}_on "${on}" on_count_${key})
      endif()
      set(n_on ${on_count_${key}})
      rrc_compare(${base}_${f}_${m}_spec ${base}_${f}_${m}_removed "${base}/${f}/${m}" verdict)
      string(APPEND table "| ${base} | ${f} | ${m} | ${n_spec} | ${n_removed} | ${verdict} | ${n_on} |\n")
    endforeach()
  endforeach()
endforeach()

# ---- One module a channel count ----------------------------------------------
# The library builds the per-channel passes once for each channel count n (compute/CMakeLists.txt,
# -DRRC_SLOTS=n) and gives a context of n channels the n-slot module (docs/PERFORMANCE.md, "One
# module a channel count"). Specialised as such a context (CHANNEL_COUNT n; the defaults base, and
# the all_on base with every feature on), it must equal the full module specialised the same:
# the slots it leaves out are code no n-channel context runs.
file(READ ${INCLUDE_DIR}/rrc/rrc_values.h values)
if(NOT values MATCHES "#define RRC_MAX_CHANNELS ([0-9]+)")
  message(FATAL_ERROR "rrc_values.h defines no RRC_MAX_CHANNELS")
endif()
math(EXPR fewer "${CMAKE_MATCH_1} - 1")
set(every_feature_on ${BASE_interop_SET})
list(FILTER every_feature_on EXCLUDE REGEX "^${ID_CHANNEL_COUNT}:")
foreach(g IN LISTS features)
  foreach(id IN LISTS F_${g}_IDS)
    list(APPEND every_feature_on ${id}:${F_${g}_ON})
  endforeach()
endforeach()
list(REMOVE_DUPLICATES every_feature_on)
set(slot_table "")
foreach(n RANGE 1 ${fewer})
  foreach(m frame fill)
    rrc_run(${GLSLANG} -V --target-env vulkan1.1 --quiet -I${KERNEL_DIR} -I${INCLUDE_DIR} -DRRC_SLOTS=${n}
            ${KERNEL_DIR}/rrc_pass_${m}.comp -o ${WORK_DIR}/slots${n}_${m}.spv)
    foreach(base defaults all_on)
      set(settings ${ID_CHANNEL_COUNT}:${n})
      if(base STREQUAL "all_on")
        list(APPEND settings ${every_feature_on})
      endif()
      rrc_specialise(spec_${m} slots_${base}_${n}_${m}_full "${settings}" n_full)
      rrc_specialise(slots${n}_${m} slots_${base}_${n}_${m}_own "${settings}" n_own)
      rrc_compare(slots_${base}_${n}_${m}_full slots_${base}_${n}_${m}_own "${n} channels/${base}/${m}" verdict)
      string(APPEND slot_table "| ${n} | ${base} | ${m} | ${n_full} | ${n_own} | ${verdict} |\n")
    endforeach()
  endforeach()
endforeach()
message(STATUS "One module a channel count, SPIR-V instructions after specialisation:\n\n"
        "| channels | base | pass | full module | its own module | comparison |\n"
        "|---|---|---|---:|---:|---|\n${slot_table}")

message(STATUS "SPIR-V instructions after specialisation (tests/spirv/disabled_features.cmake):\n\n"
        "| base | feature | pass | spec constant off | code removed | comparison | feature on |\n"
        "|---|---|---|---:|---:|---|---:|\n${table}")
if(failures)
  string(REPLACE ";" "\n  " failures "${failures}")
  message(FATAL_ERROR "A disabled feature costs something, or a channel count's module is not the full one "
                      "specialised: the specialised SPIR-V differs (diff the disassemblies):\n  ${failures}")
endif()
message(STATUS "every disabled feature specialises to the SPIR-V built without its code")
