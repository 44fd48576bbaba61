# A disabled feature costs nothing (docs/measurements/PERFORMANCE.md): for each optional
# feature of the kernels (compute/rrc_module_*.comp, one module a pass), the
# specialised SPIR-V of a configuration without it must equal, module by
# module, the SPIR-V built with the feature's code removed (-DRRC_WITHOUT_<F>:
# its specialization constant becomes a plain `const false` / `0u`; a channel
# feature is a field of its slot's feature word, and -DRRC_WITHOUT_FEATURES=<bits>
# makes that field read 0 whatever the word).
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
# A channel feature needs nothing here: its row in compute/rrc_channel_options.def
# (a feature field) makes it one of `channel_features`, read from that table.
# A whole-dispatch feature: add its -DRRC_WITHOUT_<F> to the kernels and <F>
# to `dispatch_features` with its ids (F_<F>_IDS) and "on" value below.
#
# Every base is checked three ways per feature: some module really has the
# feature (a dispatch feature's SpecId is declared, and not when built without
# it; a channel feature's "on" module differs from its "off" one somewhere), the
# two "off" builds of every module are equal, and the instruction counts with
# the feature on are reported (where "on" equals "off", the feature has no code
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
foreach(c SOURCE DEPTH_MODE HAS_NOCACHE CHANNEL_COUNT INTEROP STATS HOST_AGE_MASK ADAPTIVE OBJECT_ID CHANNEL_FEATURES CHANNEL_SLOTS COUNT_IO)
  rrc_define(RRC_SPEC_${c} ID_${c})
endforeach()
rrc_define(RRC_DEFAULT_CHANNEL_FEATURES DEFAULT_WORD)
math(EXPR last_slot "${ID_CHANNEL_SLOTS} - 1")
set(SLOT_IDS "")
foreach(c RANGE ${last_slot})
  math(EXPR id "${ID_CHANNEL_FEATURES} + ${c}")
  list(APPEND SLOT_IDS ${id})
endforeach()

# ---- Feature fields, read from the option table ------------------------------
# FIELD_<member> = "bit;width" of each row with a feature field.
file(READ ${KERNEL_DIR}/rrc_channel_options.def table)
string(REGEX MATCHALL "RRC_CHANNEL_OPTION\\(([a-z_0-9]+),[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*," rows "${table}")
set(channel_fields "")
foreach(row IN LISTS rows)
  string(REGEX REPLACE "[ \n]" "" row "${row}")
  string(REGEX MATCH "^RRC_CHANNEL_OPTION\\(([a-z_0-9]+),.*,([0-9]+),([0-9]+),$" _ "${row}")
  if(NOT CMAKE_MATCH_1)
    continue()  # the comment's column names
  endif()
  if(NOT CMAKE_MATCH_3 EQUAL 0)
    set(FIELD_${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${CMAKE_MATCH_3})
    list(APPEND channel_fields ${CMAKE_MATCH_1})
  endif()
endforeach()
# <out> = <value> placed in <member>'s field.
function(rrc_field member value out)
  if(NOT DEFINED FIELD_${member})
    message(FATAL_ERROR "rrc_channel_options.def: no feature field for ${member}")
  endif()
  list(GET FIELD_${member} 0 bit)
  math(EXPR v "${value} << ${bit}")
  set(${out} ${v} PARENT_SCOPE)
endfunction()
# The fields that make up the slot's structure, not optional features.
set(structure_fields components precision blend filter fill_radius)
# Channel feature -> the bits it sets in every slot's word ("on") and the
# bits -DRRC_WITHOUT_FEATURES clears ("removed"): one a feature field, the
# fill with its radius (the default, 2) as its loop bound.
set(channel_features "")
foreach(member IN LISTS channel_fields)
  if(member IN_LIST structure_fields)
    continue()
  endif()
  string(TOUPPER ${member} f)
  if(f STREQUAL "FILL_AGE")
    set(f FILL)
  endif()
  rrc_field(${member} 1 F_${f}_MASK)
  set(F_${f}_BITS ${F_${f}_MASK})
  list(APPEND channel_features ${f})
endforeach()
rrc_field(fill_radius 2 radius_bits)
math(EXPR F_FILL_BITS "${F_FILL_BITS} | ${radius_bits}")

# Whole-dispatch feature -> its spec ids and the value that turns it on.
set(dispatch_features NOCACHE INTEROP ADAPTIVE OBJECT_ID STATS HOST_AGE COUNT_IO)
set(F_NOCACHE_IDS ${ID_HAS_NOCACHE})
set(F_INTEROP_IDS ${ID_INTEROP})
set(F_ADAPTIVE_IDS ${ID_ADAPTIVE})
set(F_OBJECT_ID_IDS ${ID_OBJECT_ID})
set(F_STATS_IDS ${ID_STATS})
set(F_HOST_AGE_IDS ${ID_HOST_AGE_MASK})
set(F_COUNT_IO_IDS ${ID_COUNT_IO})
foreach(f IN LISTS dispatch_features)
  set(F_${f}_ON true)
endforeach()
set(F_HOST_AGE_ON 15)  # every slot's age to the host
set(features ${dispatch_features} ${channel_features})

# ---- Bases: the configuration around the feature ----------------------------
# Each: a list of "id:value" pairs of whole-dispatch constants, its slot words
# (BASE_<b>_WORDS, one a slot), and the features checked there.
rrc_field(components 1 four)
rrc_field(filter 2 catmull_rom)
rrc_field(blend 1 age_aware)
math(EXPR slot1_word "${four} | ${catmull_rom} | ${age_aware}")  # RGBA fp32, Catmull-Rom, AGE_AWARE
# defaults: what rrc_create's defaults specialise (every feature off).
set(base_names defaults interop all_on)
set(BASE_defaults_SET "")
set(BASE_defaults_WORDS ${DEFAULT_WORD} ${DEFAULT_WORD} ${DEFAULT_WORD} ${DEFAULT_WORD})
# BLUR_BOUND, VIEW_LOBE, RESIDUAL and FILL_PRIOR are checked in all_on only: this check
# is the suite's slowest, and all_on is the strictest base (every other
# feature's code beside it).
set(BASE_defaults_FEATURES ${features})
list(REMOVE_ITEM BASE_defaults_FEATURES BLUR_BOUND VIEW_LOBE RESIDUAL FILL_PRIOR)
# interop: host images, REVERSED depth, two channels: slot 0 the default
# packed fp16 scalar, slot 1 RGBA fp32, Catmull-Rom, AGE_AWARE.
set(BASE_interop_SET ${ID_INTEROP}:true ${ID_DEPTH_MODE}:1 ${ID_CHANNEL_COUNT}:2)
set(BASE_interop_WORDS ${DEFAULT_WORD} ${slot1_word} ${DEFAULT_WORD} ${DEFAULT_WORD})
set(BASE_interop_FEATURES NOCACHE ADAPTIVE OBJECT_ID CONFIDENCE STATS HOST_AGE COUNT_IO RECTIFY FILL ANTILAG)
# all_on: the interop base with every other feature on (leave one out;
# INTEROP itself off when it is the feature checked).
set(BASE_all_on_SET ${BASE_interop_SET})
set(BASE_all_on_WORDS ${BASE_interop_WORDS})
set(BASE_all_on_FEATURES ${features})
set(BASE_all_on_OTHERS_ON TRUE)

# <out> = the "id:value" list of <pairs> and the slot words <words> with
# <bits> set in every word.
function(rrc_settings pairs words bits out)
  set(result ${pairs})
  foreach(c RANGE ${last_slot})
    list(GET words ${c} w)
    list(GET SLOT_IDS ${c} id)
    math(EXPR w "${w} | ${bits}")
    list(APPEND result ${id}:${w})
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

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
            ${KERNEL_DIR}/rrc_module_${m}.comp -o ${WORK_DIR}/${name}_${m}.spv)
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

# Compares the specialised modules <a> and <b>: <verdict_out> = equal, or
# "equal (order)" where the two hold the same instructions (ids aside) with the
# module's declarations in another order (the front end emits a constant it
# folded where it first folded it, the optimiser one it froze where it was
# declared), or DIFFERENT; a difference joins `failures` under <label> with the
# two disassemblies to diff.
function(rrc_instructions name out)
  file(STRINGS ${WORK_DIR}/${name}.dis lines)
  list(TRANSFORM lines REPLACE "%[0-9]+" "%")
  # spirv-dis right-aligns each result id: an id with more digits indents its line less.
  list(TRANSFORM lines REPLACE "^ +" "")
  list(SORT lines)
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()
function(rrc_compare a b label verdict_out)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/${a}.spv ${WORK_DIR}/${b}.spv RESULT_VARIABLE differ)
  if(NOT differ)
    set(${verdict_out} equal PARENT_SCOPE)
    return()
  endif()
  rrc_instructions(${a} ia)
  rrc_instructions(${b} ib)
  if(ia STREQUAL ib)
    set(${verdict_out} "equal (order)" PARENT_SCOPE)
  else()
    set(${verdict_out} DIFFERENT PARENT_SCOPE)
    set(failures ${failures} "${label}: ${WORK_DIR}/${a}.dis vs ${WORK_DIR}/${b}.dis" PARENT_SCOPE)
  endif()
endfunction()

# ---- The check ---------------------------------------------------------------
rrc_compile(spec)
rrc_spec_ids(spec spec_ids)
foreach(f IN LISTS dispatch_features)
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
foreach(id IN LISTS SLOT_IDS)
  if(NOT id IN_LIST spec_ids)
    message(FATAL_ERROR "no kernel declares the slot feature word's SpecId ${id}")
  endif()
endforeach()
foreach(f IN LISTS channel_features)
  rrc_compile(without_${f} -DRRC_WITHOUT_FEATURES=${F_${f}_MASK}u)
endforeach()

set(table "")
set(failures "")
foreach(base IN LISTS base_names)
  foreach(f IN LISTS BASE_${base}_FEATURES)
    # The configuration without f: the base, every other feature on in all_on.
    set(off ${BASE_${base}_SET})
    set(bits_off 0)
    if(BASE_${base}_OTHERS_ON)
      foreach(g IN LISTS features)
        if(NOT g STREQUAL f)
          foreach(id IN LISTS F_${g}_IDS)
            list(APPEND off ${id}:${F_${g}_ON})
          endforeach()
          if(DEFINED F_${g}_BITS)
            math(EXPR bits_off "${bits_off} | ${F_${g}_BITS}")
          endif()
        endif()
      endforeach()
    endif()
    list(REMOVE_DUPLICATES off)  # INTEROP: in the base and among the others
    # f's own constants keep their defaults (off), whatever the base sets.
    foreach(id IN LISTS F_${f}_IDS)
      list(FILTER off EXCLUDE REGEX "^${id}:")
    endforeach()
    set(on ${off})
    set(bits_on ${bits_off})
    foreach(id IN LISTS F_${f}_IDS)
      list(APPEND on ${id}:${F_${f}_ON})
    endforeach()
    if(DEFINED F_${f}_BITS)
      math(EXPR bits_on "${bits_on} | ${F_${f}_BITS}")
    endif()
    rrc_settings("${off}" "${BASE_${base}_WORDS}" ${bits_off} off)
    rrc_settings("${on}" "${BASE_${base}_WORDS}" ${bits_on} on)
    foreach(m IN LISTS modules)
      rrc_specialise(spec_${m} ${base}_${f}_${m}_spec "${off}" n_spec)
      rrc_specialise(without_${f}_${m} ${base}_${f}_${m}_removed "${off}" n_removed)
      string(MD5 key "${m} ${on}")
      if(NOT DEFINED on_count_${key})  # all_on: one "every feature on" module a pass
        rrc_specialise(spec_${m} ${base}_${f}_${m}_on "${on}" on_count_${key})
      endif()
      set(n_on ${on_count_${key}})
      if(NOT n_on EQUAL n_spec)
        set(has_code_${f} TRUE)
      endif()
      rrc_compare(${base}_${f}_${m}_spec ${base}_${f}_${m}_removed "${base}/${f}/${m}" verdict)
      string(APPEND table "| ${base} | ${f} | ${m} | ${n_spec} | ${n_removed} | ${verdict} | ${n_on} |\n")
    endforeach()
  endforeach()
endforeach()
# A channel feature whose "on" never changes a module is not in the kernels:
# the check would compare a build with itself.
foreach(f IN LISTS channel_features)
  if(NOT has_code_${f})
    message(FATAL_ERROR "${f}: turning it on changes no module (its feature field is read nowhere?)")
  endif()
endforeach()

# ---- One module a channel count ----------------------------------------------
# The library builds the per-channel passes once for each channel count n (compute/CMakeLists.txt,
# -DRRC_SLOTS=n) and gives a context of n channels the n-slot module (docs/measurements/PERFORMANCE.md, "One
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
set(every_bit 0)
foreach(g IN LISTS features)
  foreach(id IN LISTS F_${g}_IDS)
    list(APPEND every_feature_on ${id}:${F_${g}_ON})
  endforeach()
  if(DEFINED F_${g}_BITS)
    math(EXPR every_bit "${every_bit} | ${F_${g}_BITS}")
  endif()
endforeach()
list(REMOVE_DUPLICATES every_feature_on)
rrc_settings("${every_feature_on}" "${BASE_interop_WORDS}" ${every_bit} every_feature_on)
set(slot_table "")
foreach(n RANGE 1 ${fewer})
  foreach(m frame fill)
    rrc_run(${GLSLANG} -V --target-env vulkan1.1 --quiet -I${KERNEL_DIR} -I${INCLUDE_DIR} -DRRC_SLOTS=${n}
            ${KERNEL_DIR}/rrc_module_${m}.comp -o ${WORK_DIR}/slots${n}_${m}.spv)
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
