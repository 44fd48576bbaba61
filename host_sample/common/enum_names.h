// Name <-> value tables for the enumerations the host programs take on their
// command lines (rrc-accumulate, rrc-sample), and the lookups over them: each
// name is spelt once, for parsing, for output and for the list of choices an
// error message gives.  Public API only.
#pragma once

#include <rrc/rrc.h>

#include <cstddef>
#include <string>

namespace rrc_host {

template <typename T>
struct EnumName {
    const char* name;
    T value;
};

/** The value `name` names in `table`; false (and `out` untouched) if none. */
template <typename T, std::size_t N>
bool enum_value(const EnumName<T> (&table)[N], const std::string& name, T& out) {
    for (const EnumName<T>& e : table)
        if (name == e.name) {
            out = e.value;
            return true;
        }
    return false;
}

/** The name of `value` in `table`, "?" if it has none. */
template <typename T, std::size_t N>
const char* enum_name(const EnumName<T> (&table)[N], T value) {
    for (const EnumName<T>& e : table)
        if (e.value == value) return e.name;
    return "?";
}

/** The names in order, for messages: "a, b or c". */
template <typename T, std::size_t N>
std::string enum_choices(const EnumName<T> (&table)[N]) {
    std::string s;
    for (std::size_t i = 0; i < N; ++i) {
        if (i > 0) s += i + 1 == N ? " or " : ", ";
        s += table[i].name;
    }
    return s;
}

inline constexpr EnumName<rrc_blend> kBlendNames[] = {
    {"fixed", RRC_BLEND_FIXED}, {"age_aware", RRC_BLEND_AGE_AWARE}, {"running_mean", RRC_BLEND_RUNNING_MEAN}};
inline constexpr EnumName<rrc_history_filter> kHistoryFilterNames[] = {
    {"nearest", RRC_HISTORY_FILTER_NEAREST}, {"bilinear", RRC_HISTORY_FILTER_BILINEAR}, {"catmull_rom", RRC_HISTORY_FILTER_CATMULL_ROM},
    {"gaussian", RRC_HISTORY_FILTER_GAUSSIAN}};
inline constexpr EnumName<rrc_history_precision> kHistoryPrecisionNames[] = {{"fp16", RRC_HISTORY_FP16}, {"fp32", RRC_HISTORY_FP32}};
inline constexpr EnumName<rrc_depth_mode> kDepthModeNames[] = {
    {"standard", RRC_DEPTH_MODE_STANDARD}, {"reversed", RRC_DEPTH_MODE_REVERSED}, {"linear", RRC_DEPTH_MODE_LINEAR}};
inline constexpr EnumName<rrc_depth_format> kDepthFormatNames[] = {
    {"float32", RRC_DEPTH_FORMAT_FLOAT32}, {"unorm16", RRC_DEPTH_FORMAT_UNORM16}, {"unorm24", RRC_DEPTH_FORMAT_UNORM24}};
inline constexpr EnumName<rrc_reprojection> kReprojectionNames[] = {{"prev_clip", RRC_REPROJECTION_PREV_CLIP},
                                                                    {"motion", RRC_REPROJECTION_MOTION},
                                                                    {"motion_depth", RRC_REPROJECTION_MOTION_DEPTH},
                                                                    {"camera", RRC_REPROJECTION_CAMERA}};

}  // namespace rrc_host
