// The depth setups the visibility suite scores (docs/measurements/ACCURACY.md, "Hit test against true
// visibility"), shared by the suite and the peers' comparison (docs/measurements/COMPARISON.md) so both
// score the same cases: FLOAT32 STANDARD up to far/near 1e4, REVERSED finite and infinite up
// to 1e9, UNORM16 up to 1e3 STANDARD and 1e4 REVERSED, UNORM24, LINEAR.  Likewise the thin
// card's depth setups and wall angles, which both score as the thin-card cases.
#pragma once

#include <rrc/rrc.h>

#include <limits>

namespace rrc_visibility {

inline constexpr double kInfiniteFar = std::numeric_limits<double>::infinity();

struct Depth {
    const char* name;
    rrc_depth_mode mode;
    rrc_depth_format format;
    double near_plane, far_plane;
};

inline const Depth kDepths[] = {
    {"standard_f32_1e3", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_FLOAT32, 0.1, 100.0},
    {"standard_f32_1e4", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_FLOAT32, 0.01, 100.0},
    {"reversed_f32_1e3", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_FLOAT32, 0.1, 100.0},
    {"reversed_f32_1e9", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_FLOAT32, 1e-7, 100.0},
    {"reversed_f32_inf_near_0_1", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_FLOAT32, 0.1, kInfiniteFar},
    {"reversed_f32_inf_near_1e_7", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_FLOAT32, 1e-7, kInfiniteFar},
    {"standard_u16_1e3", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_UNORM16, 0.1, 100.0},
    {"reversed_u16_1e4", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_UNORM16, 0.01, 100.0},
    {"standard_u24_1e4", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_UNORM24, 0.01, 100.0},
    {"reversed_u24_1e4", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_UNORM24, 0.01, 100.0},
    {"linear", RRC_DEPTH_MODE_LINEAR, RRC_DEPTH_FORMAT_FLOAT32, 0.1, 100.0},
};

// The thin card (a wall and a card 1e-3 d in front of it, the wall at kCardAngles degrees
// from its normal) in each of these setups, near 0.1: the formats whose step resolves 1e-3 d
// at the wall (FLOAT32 STANDARD and REVERSED, finite and infinite far, UNORM24) and two that
// cannot (UNORM16, LINEAR).
inline const Depth kCardDepths[] = {
    {"standard_f32", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_FLOAT32, 0.1, 100.0},
    {"reversed_f32", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_FLOAT32, 0.1, 100.0},
    {"reversed_f32_inf", RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_FLOAT32, 0.1, kInfiniteFar},
    {"standard_u24", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_UNORM24, 0.1, 100.0},
    {"standard_u16", RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_UNORM16, 0.1, 100.0},
    {"linear", RRC_DEPTH_MODE_LINEAR, RRC_DEPTH_FORMAT_FLOAT32, 0.1, 100.0},
};
inline constexpr double kCardAngles[] = {0.0, 60.0, 80.0};

}  // namespace rrc_visibility
