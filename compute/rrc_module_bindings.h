// The passes' modules and the descriptor bindings each one declares, written
// once: the kernels (compute/rrc_module_*.comp) declare exactly these bindings
// (rrc_bindings.glsl expands the list), and the library
// (plugin/accumulate_pipeline.cpp) makes each pass's descriptor-set layout
// from the same list and writes only those bindings.  A pass that uses a
// binding its list lacks does not compile.  Preprocessor text only, read by
// GLSL and C++ alike; the binding numbers are rrc_kernel_interface.h's.
#ifndef RRC_MODULE_BINDINGS_H
#define RRC_MODULE_BINDINGS_H

// ---- The modules (the passes each runs: rrc_kernel_interface.h) ------------
#define RRC_MODULE_FRAME 0     // FUSED, CLASSIFY, RESOLVE, RESOLVE_LISTED: one per-pixel body, PASS specialises it
#define RRC_MODULE_LIST 1      // LIST
#define RRC_MODULE_COPY_OUT 2  // COPY_OUT
#define RRC_MODULE_FILL 3      // FILL
#define RRC_MODULE_COUNT 4

// ---- Each pass's bindings: X(name) for RRC_BINDING_<name> ------------------
// The per-pixel passes: every input (a residual's base: FALLBACK), the channels, the mask, the lists.
#define RRC_MODULE_FRAME_BINDINGS(X)                                                                               \
    X(DEPTH) X(PREV_DEPTH) X(REPROJ) X(PREV_OBJECT_ID) X(NOCACHE) X(MASK) X(HOST_DEPTH) X(HOST_REPROJ)           \
    X(HOST_NOCACHE) X(DEPTH_OUT) X(SAMPLE1) X(SAMPLE4) X(CONFIDENCE) X(HIST_PACKED) X(HIST_RGBA16F) X(HIST_R32F) \
    X(HIST_RGBA32F) X(AGE) X(WEIGHT) X(HIST_OUT) X(AGE_OUT) X(WEIGHT_OUT) X(HOST_SAMPLES) X(HOST_CONFIDENCE)     \
    X(HOST_OUT) X(HOST_AGE_OUT) X(OBJECT_ID) X(HOST_OBJECT_ID) X(CLASSIFIED) X(STATS) X(QUADS) X(FILL_LIST) X(VIEW)    \
    X(FALLBACK) X(GATE) X(CHANNEL_PARAMS)
// The list: classify's mask in, the quad list out.
#define RRC_MODULE_LIST_BINDINGS(X) X(MASK) X(CLASSIFIED) X(QUADS)
// Copy-out, bound as the next frame: this frame's history and age, the mask,
// and the host's output, age and mask images.
#define RRC_MODULE_COPY_OUT_BINDINGS(X)                                                                                    \
    X(PREV_DEPTH) X(MASK) X(CLASSIFIED) X(HIST_PACKED) X(HIST_RGBA16F) X(HIST_R32F) X(HIST_RGBA32F) X(AGE) X(HOST_OUT) \
    X(HOST_AGE_OUT)
// The spatial fill, bound as the next frame: this frame's depth, history
// and age, the fallback estimates (a residual's base), the deviation gate's
// state, the fill list; the displayed values out; the statistics buffer,
// where a frame counts its image operations (compute/rrc_io.glsl).
#define RRC_MODULE_FILL_BINDINGS(X)                                                                                         \
    X(PREV_DEPTH) X(HIST_PACKED) X(HIST_RGBA16F) X(HIST_R32F) X(HIST_RGBA32F) X(AGE) X(HOST_OUT) X(FALLBACK) X(GATE) X(FILL_LIST) \
        X(CHANNEL_PARAMS) X(STATS)

#endif  // RRC_MODULE_BINDINGS_H
