// The image operations a pixel makes, counted (RRC_SPEC_COUNT_IO; rrc_vulkan_frame_desc.count_io,
// docs/measurements/PERFORMANCE.md "What a pixel moves"): every load and store of the
// per-pixel passes goes through RRC_LOAD or rrc_io_store, which add to this invocation's
// counters; rrc_io_flush (rrc_io_flush.glsl, the passes that count) adds a pixel's counts to
// the statistics buffer's words after the statistics.  Off (the constant false), every
// counter's code is dead and compiled out: the wrappers leave the loads and stores as they were.
#ifndef RRC_IO_GLSL
#define RRC_IO_GLSL

#ifdef RRC_WITHOUT_COUNT_IO
const bool COUNT_IO = false;  // the feature's code removed (tests/spirv)
#else
layout(constant_id = RRC_SPEC_COUNT_IO) const bool COUNT_IO = false;
#endif

uint rrc_io[RRC_IO_COUNTERS] = uint[RRC_IO_COUNTERS](0u, 0u, 0u, 0u, 0u);

// One load instruction of `texels` texels of `bytes` bytes each; the value is `expr`'s.
bool rrc_io_load(uint texels, uint bytes) {
    if (COUNT_IO) {
        rrc_io[RRC_IO_LOADS] += 1u;
        rrc_io[RRC_IO_TEXELS] += texels;
        rrc_io[RRC_IO_LOAD_BYTES] += texels * bytes;
    }
    return true;
}
#define RRC_LOAD(texels, bytes, expr) (rrc_io_load(texels, bytes), (expr))

// One imageStore of a `bytes`-byte texel: called beside the store, under its condition.
void rrc_io_store(uint bytes) {
    if (COUNT_IO) {
        rrc_io[RRC_IO_STORES] += 1u;
        rrc_io[RRC_IO_STORE_BYTES] += bytes;
    }
}

#endif
