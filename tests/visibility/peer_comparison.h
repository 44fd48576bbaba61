// docs/measurements/COMPARISON.md's measurement: rrc's hit test (ADAPTIVE, the default,
// and FIXED, both through the double-precision reference,
// tests/reference/run_frame.cpp) beside each peer's validity test
// (tests/reference/peer_tests.h), scored by the analytic scenes' oracle
// (tests/scenes/visibility.h) on PREV_CLIP frames.  Per test: recall, false
// hits, and the false hits whose fetched history takes weight from a texel
// that held another object (or the sky) in the previous frame ("mixing").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"
#include "scenes/visibility.h"

namespace rrc_peer {

constexpr int kTestCount = 7;  // rrc ADAPTIVE, rrc FIXED, then the peers in kAllPeerTests' order
const char* test_label(int test);  // "rrc ADAPTIVE", "NRD ReBLUR", ...
const char* test_slug(int test);   // file-name form: "rrc_adaptive", "nrd_reblur", ...

// A weight above this puts a texel into the fetched history (the oracle's own tap threshold).
constexpr double kMixWeight = 1e-3;

struct CaseSpec {
    std::string name;
    rrc_scene::SceneConfig config;
    int frames = 5;  // frame 0 renders the first history; frames 1 .. frames-1 are scored
    rrc_scene::VisibilityOptions visibility;
};

// The visibility suite's PREV_CLIP cases (tests/visibility/hit_test_recall_test.cpp): every
// depth setup under the orbiting and the grazing camera, and the thin card at 0, 60 and 80
// degrees in each depth setup, at 96x64.
std::vector<CaseSpec> comparison_cases();

struct TestScore {
    rrc_scene::RecallScore score;  // recall over VISIBLE pixels, false hits over every pixel
    int64_t mixing = 0;            // false hits whose history takes weight from another object's texel
};

struct CaseResult {
    std::string name;
    TestScore tests[kTestCount];
    // The last scored frame, for the pictures: the oracle's map and each test's hits (0/1).
    rrc_scene::VisibilityMap last_map;
    std::vector<uint8_t> last_hits[kTestCount];
    // Every frame's rrc ADAPTIVE mask and the reference's near_threshold flags (frame 0 included).
    std::vector<std::vector<uint8_t>> adaptive_masks, adaptive_near;
};

CaseResult evaluate(const CaseSpec& spec);

}  // namespace rrc_peer
