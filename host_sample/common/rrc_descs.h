// Builders for rrc's public C descriptors (include/rrc/rrc.h): zeroed, with
// type and size set, and the fields every caller fills.  rrc-sample,
// rrc-accumulate, the tests' support code and the reference self-tests each
// used to spell these out field by field; they share these instead.  Public
// API only.
#pragma once

#include <rrc/rrc.h>

#include <cstdio>
#include <cstring>
#include <vector>

namespace rrc_host {

/** A zeroed rrc struct with its type tag and size (rrc.h Versioning). */
template <typename T>
T rrc_struct(rrc_struct_type type) {
    T s;
    std::memset(&s, 0, sizeof s);
    s.type = type;
    s.size = sizeof s;
    return s;
}

inline rrc_channel_desc channel(const char* name, uint32_t components, float lambda, rrc_history_precision precision = RRC_HISTORY_FP32,
                                rrc_blend blend = RRC_BLEND_FIXED, rrc_history_filter filter = RRC_HISTORY_FILTER_BILINEAR,
                                uint32_t age_cap = 0, uint32_t confidence = 0) {
    rrc_channel_desc c = rrc_struct<rrc_channel_desc>(RRC_STRUCT_TYPE_CHANNEL_DESC);
    std::snprintf(c.name, sizeof c.name, "%s", name);
    c.components = components;
    c.precision = precision;
    c.lambda = lambda;
    c.blend = blend;
    c.filter = filter;
    c.age_cap = age_cap;
    c.confidence = confidence;
    return c;
}

/** A context of width x height over `channels` (which must outlive the descriptor's use). */
inline rrc_context_desc context_desc(uint32_t width, uint32_t height, const std::vector<rrc_channel_desc>& channels) {
    rrc_context_desc d = rrc_struct<rrc_context_desc>(RRC_STRUCT_TYPE_CONTEXT_DESC);
    d.api_version = RRC_API_VERSION;
    d.width = width;
    d.height = height;
    d.channel_count = (uint32_t)channels.size();
    d.channels = channels.data();
    return d;
}

inline rrc_frame_desc frame_desc() { return rrc_struct<rrc_frame_desc>(RRC_STRUCT_TYPE_FRAME_DESC); }

inline rrc_channel_input channel_input(const float* samples, const float* confidence = nullptr) {
    rrc_channel_input c = rrc_struct<rrc_channel_input>(RRC_STRUCT_TYPE_CHANNEL_INPUT);
    c.samples = samples;
    c.confidence = confidence;
    return c;
}

inline rrc_channel_output channel_output() { return rrc_struct<rrc_channel_output>(RRC_STRUCT_TYPE_CHANNEL_OUTPUT); }
inline rrc_frame_output frame_output() { return rrc_struct<rrc_frame_output>(RRC_STRUCT_TYPE_FRAME_OUTPUT); }

}  // namespace rrc_host
