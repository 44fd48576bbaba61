// What the kernels receive of a channel's options, made from the rows of
// compute/rrc_channel_options.def: the slot's feature word (a specialization
// constant; its fields change code) and its parameter block (a uniform
// buffer; its members change no code).  The GLSL declarations of both come
// from the same rows (compute/rrc_channel_slots.glsl, rrc_bindings.glsl).
#pragma once

#include "config.h"

#include <cstdint>

namespace rrc {

// One slot's parameter block: the PARAM rows in row order, 32 bits each,
// std140 (a struct in an array: its stride a multiple of 16 bytes).
struct alignas(16) KernelChannelParams {
#define RRC_PARAM_NONE(ctype, member)
#define RRC_PARAM_PARAM(ctype, member) ctype member = 0;
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, ...) RRC_PARAM_##param(ctype, member)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_PARAM_PARAM
#undef RRC_PARAM_NONE
};
// std140 lays 32-bit scalars 4 bytes apart: only float and uint32_t rows can be PARAM.
#define RRC_PARAM_NONE(ctype, member)
#define RRC_PARAM_PARAM(ctype, member) \
    static_assert(sizeof(ctype) == 4 && alignof(ctype) == 4, #member ": a PARAM row is a 32-bit float or uint32_t");
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, ...) RRC_PARAM_##param(ctype, member)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_PARAM_PARAM
#undef RRC_PARAM_NONE

// The block as the kernel reads it: RRC_MAX_CHANNELS slots (unused slots 0).
struct KernelParamBlock {
    KernelChannelParams slot[RRC_MAX_CHANNELS];
};

inline KernelChannelParams kernel_channel_params(const ChannelConfig& c) {
    KernelChannelParams p;
#define RRC_PARAM_NONE(member)
#define RRC_PARAM_PARAM(member) p.member = c.member;
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, ...) RRC_PARAM_##param(member)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_PARAM_PARAM
#undef RRC_PARAM_NONE
    return p;
}

// The feature word's fields: each row's `feature` at its `bit`, `width` bits.
constexpr uint32_t feature_field_mask(uint32_t bit, uint32_t width) { return width == 0 ? 0u : ((1u << width) - 1u) << bit; }
// No two fields overlap, and each fits the word.
constexpr bool feature_fields_disjoint() {
    uint32_t used = 0;
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, ...) \
    if ((used & feature_field_mask(bit, width)) != 0 || (bit) + (width) > 32) return false;                     \
    used |= feature_field_mask(bit, width);
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    return true;
}
static_assert(feature_fields_disjoint(), "rrc_channel_options.def: two feature fields overlap");

inline uint32_t channel_feature_word(const ChannelConfig& c) {
    uint32_t word = 0;
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, ...) \
    word |= ((uint32_t)(feature) << (bit)) & feature_field_mask(bit, width);
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    return word;
}

}  // namespace rrc
