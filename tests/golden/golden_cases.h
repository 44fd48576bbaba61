// The golden cases: small two-frame sequences of the analytic scenes, one per
// reprojection source (each with another depth mode), shared by the generator
// (make_golden.cpp) and the test (golden_test.cpp).  A golden file holds both
// frames' inputs and the reference's frame-1 outputs; frame 0 is all misses,
// so the kernel's history after it equals the reference's exactly.
#pragma once

#include "support/rrc_test_context.h"

#include <limits>
#include <string>
#include <vector>

namespace rrc_golden {

struct GoldenCase {
    std::string name;
    rrc_reprojection source;
    rrc_depth_mode depth_mode;
    double far_plane;
    bool object_motion;
    std::vector<rrc_channel_desc> channels;  // channel i reads scene signal1 (1 comp) or signal4 (4 comps)
    // The context's depth_test.  The 0.1 files hold the FIXED test (kept, byte
    // for byte, under their names); the *_adaptive cases hold the 0.2 default.
    rrc_depth_test depth_test;
};

constexpr int kWidth = 48, kHeight = 32;
constexpr int kFirstFrame = 3;  // frames kFirstFrame and kFirstFrame + 1 of the scene

inline std::vector<GoldenCase> golden_cases() {
    using rrc_test::channel;
    const double inf = std::numeric_limits<double>::infinity();
    return {
        {"prev_clip_standard",
         RRC_REPROJECTION_PREV_CLIP,
         RRC_DEPTH_MODE_STANDARD,
         100,
         true,
         {channel("pcf", 1, 0.6f, RRC_HISTORY_FP32), channel("env", 4, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE)},
         RRC_DEPTH_TEST_FIXED},
        {"motion_depth_reversed",
         RRC_REPROJECTION_MOTION_DEPTH,
         RRC_DEPTH_MODE_REVERSED,
         100,
         true,
         {channel("pcf", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_CATMULL_ROM)},
         RRC_DEPTH_TEST_FIXED},
        {"motion_linear",
         RRC_REPROJECTION_MOTION,
         RRC_DEPTH_MODE_LINEAR,
         100,
         true,
         {channel("soft", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_NEAREST, 8)},
         RRC_DEPTH_TEST_FIXED},
        {"camera_reversed_infinite",
         RRC_REPROJECTION_CAMERA,
         RRC_DEPTH_MODE_REVERSED,
         inf,
         false,
         {channel("pcf", 1, 0.6f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1)},
         RRC_DEPTH_TEST_FIXED},
        // The 0.2 default (ADAPTIVE) on the exact sources; plain MOTION has no ADAPTIVE test.
        {"prev_clip_standard_adaptive",
         RRC_REPROJECTION_PREV_CLIP,
         RRC_DEPTH_MODE_STANDARD,
         100,
         true,
         {channel("pcf", 1, 0.6f, RRC_HISTORY_FP32), channel("env", 4, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE)},
         RRC_DEPTH_TEST_DEFAULT},
        {"motion_depth_reversed_adaptive",
         RRC_REPROJECTION_MOTION_DEPTH,
         RRC_DEPTH_MODE_REVERSED,
         100,
         true,
         {channel("pcf", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_CATMULL_ROM)},
         RRC_DEPTH_TEST_DEFAULT},
        {"prev_clip_linear_adaptive",
         RRC_REPROJECTION_PREV_CLIP,
         RRC_DEPTH_MODE_LINEAR,
         100,
         true,
         {channel("soft", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_NEAREST, 8)},
         RRC_DEPTH_TEST_DEFAULT},
        {"camera_reversed_infinite_adaptive",
         RRC_REPROJECTION_CAMERA,
         RRC_DEPTH_MODE_REVERSED,
         inf,
         false,
         {channel("pcf", 1, 0.6f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1)},
         RRC_DEPTH_TEST_DEFAULT},
    };
}

inline std::string golden_file(const std::string& dir, const GoldenCase& c) { return dir + "/golden_" + c.name + ".exr"; }

}  // namespace rrc_golden
