// The channel slots, shared by every pass that reads or writes channels
// (compute/rrc_pass_frame.comp, rrc_pass_copy_out.comp, rrc_pass_fill.comp):
// each slot's specialization constants and their selectors.  The per-channel
// images (rrc_bindings.glsl) are arrays indexed by slot; slots and format
// variants a configuration does not use are bound to 1x1 placeholders and
// never touched.
#ifndef RRC_CHANNEL_SLOTS_GLSL
#define RRC_CHANNEL_SLOTS_GLSL

#include "rrc_values.glsl"  // RRC_MAX_CHANNELS, spec ids, bindings

// The channel slots a module carries code for: the per-channel passes (frame, fill) are built
// once for each count 1..RRC_MAX_CHANNELS (compute/CMakeLists.txt, -DRRC_SLOTS=N) and the library
// takes the module of the context's channel count, so a driver compiles no code for slots the
// context cannot use (docs/PERFORMANCE.md, "One module a channel count").  Unset: every slot.
#ifndef RRC_SLOTS
#define RRC_SLOTS RRC_MAX_CHANNELS
#endif
#if RRC_SLOTS < 1 || RRC_SLOTS > RRC_MAX_CHANNELS || RRC_MAX_CHANNELS != 4
#error "RRC_SLOTS must be 1..RRC_MAX_CHANNELS, and the passes include slots 0..3 (RRC_MAX_CHANNELS 4)"
#endif

layout(constant_id = RRC_SPEC_CHANNEL_COUNT) const uint CH_COUNT = 1u;

// Per-slot specialization constants: RRC_SPEC_CHANNEL(property, slot), i.e.
// id 16 + 4*property + slot (rrc_kernel_interface.h).
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 0)) const uint CH0_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 1)) const uint CH1_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 2)) const uint CH2_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_COMPONENTS, 3)) const uint CH3_COMPONENTS = 1u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 0)) const bool CH0_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 1)) const bool CH1_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 2)) const bool CH2_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FP16, 3)) const bool CH3_FP16 = true;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 0)) const uint CH0_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 1)) const uint CH1_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 2)) const uint CH2_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_BLEND, 3)) const uint CH3_BLEND = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 0)) const uint CH0_FILTER = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 1)) const uint CH1_FILTER = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 2)) const uint CH2_FILTER = 0u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_FILTER, 3)) const uint CH3_FILTER = 0u;
#ifdef RRC_WITHOUT_CONFIDENCE  // the feature's code removed (tests/spirv)
const bool CH0_CONFIDENCE = false;
const bool CH1_CONFIDENCE = false;
const bool CH2_CONFIDENCE = false;
const bool CH3_CONFIDENCE = false;
#else
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 0)) const bool CH0_CONFIDENCE = false;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 1)) const bool CH1_CONFIDENCE = false;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 2)) const bool CH2_CONFIDENCE = false;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_CONFIDENCE, 3)) const bool CH3_CONFIDENCE = false;
#endif
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 0)) const float CH0_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 1)) const float CH1_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 2)) const float CH2_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_LAMBDA, 3)) const float CH3_LAMBDA = 0.6;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 0)) const uint CH0_AGE_CAP = 255u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 1)) const uint CH1_AGE_CAP = 255u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 2)) const uint CH2_AGE_CAP = 255u;
layout(constant_id = RRC_SPEC_CHANNEL(RRC_CHANNEL_PROPERTY_AGE_CAP, 3)) const uint CH3_AGE_CAP = 255u;
// 0.4, the finishing steps (docs/CONVENTIONS.md, "Finishing steps"):
// RRC_SPEC_CHANNEL2(property, slot).  Each is off (false / 0) by default.
#define RRC_SLOTS2(T, NAME, property, off)                                                  \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 0)) const T CH0_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 1)) const T CH1_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 2)) const T CH2_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL2(RRC_CHANNEL2_PROPERTY_##property, 3)) const T CH3_##NAME = off;
#define RRC_SLOTS_OFF(T, NAME, off) const T CH0_##NAME = off, CH1_##NAME = off, CH2_##NAME = off, CH3_##NAME = off;
#ifdef RRC_WITHOUT_RECTIFY  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(bool, RECTIFY, false)
#else
RRC_SLOTS2(bool, RECTIFY, RECTIFY, false)
#endif
RRC_SLOTS2(float, RECTIFY_GAMMA, RECTIFY_GAMMA, 1.0)
RRC_SLOTS2(float, BLUR_G, BLUR_G, 0.125)
#ifdef RRC_WITHOUT_FILL  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(uint, FILL_AGE, 0u)
#else
RRC_SLOTS2(uint, FILL_AGE, FILL_AGE, 0u)
#endif
RRC_SLOTS2(uint, FILL_RADIUS, FILL_RADIUS, 2u)
RRC_SLOTS2(float, FILL_TOLERANCE, FILL_TOLERANCE, 0.005)
RRC_SLOTS2(float, FILL_PRIOR, FILL_PRIOR, 0.0)
// 0.5, the lag detector (docs/CONVENTIONS.md, "The lag detector").
#ifdef RRC_WITHOUT_ANTILAG  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(bool, ANTILAG, false)
#else
RRC_SLOTS2(bool, ANTILAG, ANTILAG, false)
#endif
RRC_SLOTS2(float, ANTILAG_GAMMA, ANTILAG_GAMMA, 2.0)
RRC_SLOTS2(float, ANTILAG_THRESHOLD, ANTILAG_THRESHOLD, 0.5)
#undef RRC_SLOTS2
// 0.6, the blur bound (docs/CONVENTIONS.md, "The blur bound"): the third range,
// RRC_SPEC_CHANNEL3(property, slot).
#define RRC_SLOTS3(T, NAME, property, off)                                                  \
    layout(constant_id = RRC_SPEC_CHANNEL3(RRC_CHANNEL3_PROPERTY_##property, 0)) const T CH0_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL3(RRC_CHANNEL3_PROPERTY_##property, 1)) const T CH1_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL3(RRC_CHANNEL3_PROPERTY_##property, 2)) const T CH2_##NAME = off; \
    layout(constant_id = RRC_SPEC_CHANNEL3(RRC_CHANNEL3_PROPERTY_##property, 3)) const T CH3_##NAME = off;
#ifdef RRC_WITHOUT_BLUR_BOUND  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(bool, BLUR_BOUND, false)
#else
RRC_SLOTS3(bool, BLUR_BOUND, BLUR_BOUND, false)
#endif
RRC_SLOTS3(float, BLUR_BOUND_PX2, BLUR_BOUND_PX2, 0.0)
// 0.7, the view-dependent history (docs/CONVENTIONS.md, "The view-dependent history"): the same range.
#ifdef RRC_WITHOUT_VIEW_LOBE  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(bool, VIEW_LOBE, false)
#else
RRC_SLOTS3(bool, VIEW_LOBE, VIEW_LOBE, false)
#endif
RRC_SLOTS3(float, VIEW_LOBE_RAD, VIEW_LOBE_RAD, 0.0)
// 0.9, the residual (docs/CONVENTIONS.md, "The residual"): the same range.
#ifdef RRC_WITHOUT_RESIDUAL  // the feature's code removed (tests/spirv)
RRC_SLOTS_OFF(bool, RESIDUAL, false)
#else
RRC_SLOTS3(bool, RESIDUAL, RESIDUAL, false)
#endif
#undef RRC_SLOTS3
#undef RRC_SLOTS_OFF
// Slot selectors: called with a literal slot, they fold to one constant.
#define RRC_SLOT_SELECT(T, name) \
    T ch_##name(int c) { return c == 0 ? CH0_##name : c == 1 ? CH1_##name : c == 2 ? CH2_##name : CH3_##name; }
RRC_SLOT_SELECT(uint, COMPONENTS)
RRC_SLOT_SELECT(bool, FP16)
RRC_SLOT_SELECT(uint, BLEND)
RRC_SLOT_SELECT(uint, FILTER)
RRC_SLOT_SELECT(bool, CONFIDENCE)
RRC_SLOT_SELECT(float, LAMBDA)
RRC_SLOT_SELECT(uint, AGE_CAP)
RRC_SLOT_SELECT(bool, RECTIFY)
RRC_SLOT_SELECT(float, RECTIFY_GAMMA)
RRC_SLOT_SELECT(float, BLUR_G)
RRC_SLOT_SELECT(uint, FILL_AGE)
RRC_SLOT_SELECT(uint, FILL_RADIUS)
RRC_SLOT_SELECT(float, FILL_TOLERANCE)
RRC_SLOT_SELECT(float, FILL_PRIOR)
RRC_SLOT_SELECT(bool, ANTILAG)
RRC_SLOT_SELECT(float, ANTILAG_GAMMA)
RRC_SLOT_SELECT(float, ANTILAG_THRESHOLD)
RRC_SLOT_SELECT(bool, BLUR_BOUND)
RRC_SLOT_SELECT(float, BLUR_BOUND_PX2)
RRC_SLOT_SELECT(bool, VIEW_LOBE)
RRC_SLOT_SELECT(float, VIEW_LOBE_RAD)
RRC_SLOT_SELECT(bool, RESIDUAL)

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
