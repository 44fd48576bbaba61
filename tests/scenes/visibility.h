// The oracle of true visibility: which pixels of a frame a depth test should
// hit (docs/measurements/ACCURACY.md, "Hit test against true visibility"), so a test can score a hit/miss mask by recall and false hits.
//
// Definition, per pixel (i, j) of frame t against the previous frame t' (all
// in double; d the planar view depth):
//   X       the exact surface point at the pixel's jittered sample (Scene::cast);
//   X_prev  X moved by its object's exact previous transform.
//   X was visible iff the previous camera's ray through the projection of
//   X_prev first meets the same object within distance_relative * d of X_prev
//   (d = X_prev's depth there).
// Each pixel gets one class, tested in this order:
//   BACKGROUND        the sample hits nothing (a hit there is false).
//   EXCLUDED_QUANTISED X was hit but its STORED depth (Scene::stored_depth)
//                     reads as background: the library must treat it as sky.
//   EXCLUDED_CONTACT  X lies on a contact or intersection line: within
//                     contact_footprints pixel footprints of another object's
//                     surface in frame t or (as X_prev) in t' -- the rule of
//                     false_hits.h (rule 2), Scene::near_other_object.
//   OFFSCREEN         X_prev is behind the previous camera (w <= 0) or its
//                     uv_prev is outside [0, 1]^2: not visible.
//   EXCLUDED_DEPTH_STEP another object's surface crosses the previous ray
//                     within one depth-format step of X_prev's depth (UNORM16
//                     or UNORM24 z increment, or the fp32 ulp of z or of the
//                     LINEAR d, turned into view distance): no depth test can
//                     tell the two apart, whichever is in front.
//   OCCLUDED          not visible (another object first, or the same object
//                     farther than distance_relative * d: self-occlusion).
//   STRADDLING        visible, but one of the bilinear taps of
//                     docs/CONVENTIONS.md at q = uv_prev * size - prev_jitter
//                     (scenes/bilinear.h) with weight > tap_weight_threshold
//                     lies on another object or on background (the object its
//                     texel's own jittered previous sample hit): the fetched
//                     depth mixes surfaces; or any of the four taps, at
//                     any weight and for any q within fp32 rounding of it
//                     (2^-20 of the image size), reads as background: the
//                     library's test must miss there (docs/CONVENTIONS.md).
//                     Counted apart.
//   EXCLUDED_QUANTISED also: visible, every weighted tap on X's object, but
//                     one tap's stored previous depth reads as background.
//   VISIBLE           scored: the depth test should hit.
// Recall = hits / VISIBLE pixels; a false hit = a hit on OCCLUDED, OFFSCREEN
// or BACKGROUND.  The excluded classes and STRADDLING are neither.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "scenes/scene.h"

namespace rrc_scene {

enum VisibilityClass : uint8_t {
    VIS_BACKGROUND = 0,
    VIS_VISIBLE,
    VIS_OCCLUDED,
    VIS_OFFSCREEN,
    VIS_STRADDLING,
    VIS_EXCLUDED_QUANTISED,
    VIS_EXCLUDED_CONTACT,
    VIS_EXCLUDED_DEPTH_STEP,
    VIS_CLASS_COUNT
};

// Short lower-case name of a class, for reports.
const char* visibility_class_name(VisibilityClass c);

struct VisibilityOptions {
    double distance_relative = 1e-4;     // "within 1e-4 d"
    double tap_weight_threshold = 1e-3;  // straddling: taps lighter than this are ignored (fp32 weights differ)
    double contact_footprints = 1.0;     // as FalseHitOptions; 0 disables the contact exclusion (thin card)
};

// Per pixel of one frame, row-major, row 0 at the top.
struct VisibilityMap {
    int width = 0, height = 0;
    std::vector<uint8_t> cls;        // VisibilityClass
    std::vector<int32_t> object;     // X's object (OBJECT_BACKGROUND where none)
    std::vector<double> depth;       // X's planar depth in frame t (+inf on background)
    std::vector<double> prev_depth;  // X_prev's planar depth in frame t' (clip w; +inf on background)
    int64_t counts[VIS_CLASS_COUNT] = {};

    // Visible: the depth test should hit.  Not visible: a hit is false.
    static bool scored(uint8_t c) { return c == VIS_VISIBLE; }
    static bool not_visible(uint8_t c) { return c == VIS_OCCLUDED || c == VIS_OFFSCREEN || c == VIS_BACKGROUND; }
};

// Classifies every pixel of `frame` reprojected into `prev_frame`.
VisibilityMap true_visibility(const Scene& scene, int frame, int prev_frame, const VisibilityOptions& options = {});
inline VisibilityMap true_visibility(const Scene& scene, int frame, const VisibilityOptions& options = {}) {
    return true_visibility(scene, frame, frame - 1, options);
}

// A mask scored against a map, over the pixels `keep` accepts (all if empty).
struct RecallScore {
    int64_t scored = 0;                    // VISIBLE pixels kept
    int64_t hits = 0;                      // of those, marked RRC_MASK_HIT
    int64_t not_visible = 0;               // OCCLUDED, OFFSCREEN, BACKGROUND pixels kept
    int64_t false_hits = 0;                // of those, marked RRC_MASK_HIT
    int64_t counts[VIS_CLASS_COUNT] = {};  // every kept pixel by class

    double recall() const { return scored ? double(hits) / double(scored) : 0.0; }
    RecallScore& operator+=(const RecallScore& o);
};

RecallScore score_mask(const VisibilityMap& map, const uint8_t* mask, const std::function<bool(size_t pixel)>& keep = {});

}  // namespace rrc_scene
