// The channel slots, shared by every pass that reads or writes channels
// (compute/rrc_module_frame.comp, rrc_module_copy_out.comp, rrc_module_fill.comp):
// each slot's feature word (a specialization constant: what changes code)
// and its fields, one per row of rrc_channel_options.def with a feature
// field.  The slot's parameters (what changes no code) are its parameter
// block, u_params.slot[c] (rrc_bindings.glsl).  The per-channel images
// (rrc_bindings.glsl) are arrays indexed by slot; slots and format variants a
// configuration does not use are bound to 1x1 placeholders and never touched.
#ifndef RRC_CHANNEL_SLOTS_GLSL
#define RRC_CHANNEL_SLOTS_GLSL

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, spec ids, bindings

// The channel slots a module carries code for: the per-channel passes (frame, fill) are built
// once for each count 1..RRC_MAX_CHANNELS (compute/CMakeLists.txt, -DRRC_SLOTS=N) and the library
// takes the module of the context's channel count, so a driver compiles no code for slots the
// context cannot use (docs/design/modules.md, "One module a channel count").  Unset: every slot.
#ifndef RRC_SLOTS
#define RRC_SLOTS RRC_MAX_CHANNELS
#endif
#if RRC_SLOTS < 1 || RRC_SLOTS > RRC_MAX_CHANNELS || RRC_MAX_CHANNELS != 4
#error "RRC_SLOTS must be 1..RRC_MAX_CHANNELS, and the passes include slots 0..3 (RRC_MAX_CHANNELS 4)"
#endif

layout(constant_id = RRC_SPEC_CHANNEL_COUNT) const uint CH_COUNT = 1u;

// Each slot's feature word.  tests/spirv/disabled_features.cmake builds the
// passes with -DRRC_WITHOUT_FEATURES=<bits>: those fields read 0 whatever the
// word, the features' code removed, to compare with a word that leaves them off.
#ifndef RRC_WITHOUT_FEATURES
#define RRC_WITHOUT_FEATURES 0u
#endif
layout(constant_id = RRC_SPEC_CHANNEL_FEATURES + 0) const uint CH0_FEATURE_WORD = RRC_DEFAULT_CHANNEL_FEATURES;
layout(constant_id = RRC_SPEC_CHANNEL_FEATURES + 1) const uint CH1_FEATURE_WORD = RRC_DEFAULT_CHANNEL_FEATURES;
layout(constant_id = RRC_SPEC_CHANNEL_FEATURES + 2) const uint CH2_FEATURE_WORD = RRC_DEFAULT_CHANNEL_FEATURES;
layout(constant_id = RRC_SPEC_CHANNEL_FEATURES + 3) const uint CH3_FEATURE_WORD = RRC_DEFAULT_CHANNEL_FEATURES;
const uint CH0_FEATURES = CH0_FEATURE_WORD & ~uint(RRC_WITHOUT_FEATURES);
const uint CH1_FEATURES = CH1_FEATURE_WORD & ~uint(RRC_WITHOUT_FEATURES);
const uint CH2_FEATURES = CH2_FEATURE_WORD & ~uint(RRC_WITHOUT_FEATURES);
const uint CH3_FEATURES = CH3_FEATURE_WORD & ~uint(RRC_WITHOUT_FEATURES);

// Each feature field, per slot (CHc_<member>), and its selector ch_<member>(c):
// called with a literal slot, it folds to one constant.  A one-bit field is a
// bool (on or off), a wider one a uint.
#define RRC_FEATURE_FIELD(T, member, bit, width, value)                                   \
    const uint CH0_##member##_BITS = (CH0_FEATURES >> uint(bit)) & ((1u << uint(width)) - 1u); \
    const uint CH1_##member##_BITS = (CH1_FEATURES >> uint(bit)) & ((1u << uint(width)) - 1u); \
    const uint CH2_##member##_BITS = (CH2_FEATURES >> uint(bit)) & ((1u << uint(width)) - 1u); \
    const uint CH3_##member##_BITS = (CH3_FEATURES >> uint(bit)) & ((1u << uint(width)) - 1u); \
    const T CH0_##member = value(CH0_##member##_BITS);                                       \
    const T CH1_##member = value(CH1_##member##_BITS);                                       \
    const T CH2_##member = value(CH2_##member##_BITS);                                       \
    const T CH3_##member = value(CH3_##member##_BITS);                                       \
    T ch_##member(int c) { return c == 0 ? CH0_##member : c == 1 ? CH1_##member : c == 2 ? CH2_##member : CH3_##member; }
#define RRC_FEATURE_ON(bits) ((bits) != 0u)
#define RRC_FEATURE_VALUE(bits) (bits)
#define RRC_FEATURE_FIELD_0(member, bit, width)
#define RRC_FEATURE_FIELD_1(member, bit, width) RRC_FEATURE_FIELD(bool, member, bit, width, RRC_FEATURE_ON)
#define RRC_FEATURE_FIELD_2(member, bit, width) RRC_FEATURE_FIELD(uint, member, bit, width, RRC_FEATURE_VALUE)
#define RRC_FEATURE_FIELD_3(member, bit, width) RRC_FEATURE_FIELD(uint, member, bit, width, RRC_FEATURE_VALUE)
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, version, anchor) \
    RRC_FEATURE_FIELD_##width(member, bit, width)
#include "rrc_channel_options.def"
#undef RRC_CHANNEL_OPTION
#undef RRC_FEATURE_FIELD_3
#undef RRC_FEATURE_FIELD_2
#undef RRC_FEATURE_FIELD_1
#undef RRC_FEATURE_FIELD_0
#undef RRC_FEATURE_VALUE
#undef RRC_FEATURE_ON
#undef RRC_FEATURE_FIELD

// Which channel slots write the host's output and age images in this pass
// (interop, and the standalone fill's displayed values): chosen by the frame
// plan (plugin/frame_plan.cpp), each its own pipeline variant
// (plugin/accumulate_pipeline.h, KernelVariant): off, their code is compiled out.
layout(constant_id = RRC_SPEC_HOST_OUT_MASK) const uint HOST_OUT_MASK = 0u;
#ifdef RRC_WITHOUT_HOST_AGE
const uint HOST_AGE_MASK = 0u;  // the feature's code removed (tests/spirv)
#else
layout(constant_id = RRC_SPEC_HOST_AGE_MASK) const uint HOST_AGE_MASK = 0u;
#endif

#endif
