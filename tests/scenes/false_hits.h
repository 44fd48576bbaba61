// Ground-truth false-hit evaluation for a cache's hit/miss mask.
//
// docs/CONVENTIONS.md (hit test): "A false hit [is a hit whose] fetched history belongs to a different
// surface point than the pixel (more than half a pixel away on the surface).
// Contact and intersection lines, where two surfaces share depth, cannot be
// told apart by depth and are excluded when counting."
//
// The exact rule, per pixel (i, j) of frame t with previous frame t' (jitter
// j_t, j_t'; footprint(d) = world size of one pixel at planar depth d =
// 2 d tan(fovy/2) / H; all in double):
//   1. Cast frame t's ray through (i + 0.5 + j_t.x, j + 0.5 + j_t.y): surface
//      point P on object o.  Nothing hit -> BACKGROUND (a HIT there is false).
//   2. Contact (excluded, CONTACT; Scene::near_other_object): P lies within contact_footprints *
//      footprint(d) of the surface of any other object in frame t, or P moved
//      to frame t' (P' = M_o(t') M_o(t)^-1 P) lies within contact_footprints *
//      footprint(d') of another object's surface in frame t' (d' = P''s
//      planar depth there).  This removes contact and intersection lines.
//   3. Centre rule (FALSE_HIT): project P' with the unjittered VP(t'):
//      w <= 0, or its pixel coordinate uv_prev * size more than
//      screen_tolerance_px outside the image, or frame t''s ray through that
//      coordinate (the ray through P' itself) first meets a different object,
//      or the same object farther than distance_footprints * footprint(d')
//      from P' (self-occlusion), means P was not visible: a false hit.
//   4. Strict rule (STRICT_FALSE_HIT, only if 3 passed): the bilinear taps of
//      docs/CONVENTIONS.md at q = uv_prev * size - j_t' (clamped to the
//      image), each with weight > tap_weight_threshold, must all hold
//      object o in frame t' (their texels' own jittered samples).  A tap on
//      another object (or the sky) mixes a foreign surface into the history.
//      Same-object taps are accepted: every object is convex (or the plane),
//      so once P is visible its neighbouring texels on o are the same sheet.
//   5. Otherwise TRUE_HIT: the history at the pixel belongs to P.
#pragma once

#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace rrc_scene {

enum Verdict : uint8_t {
    VERDICT_NOT_CHECKED = 0,  // count_false_hits: pixel not marked HIT
    VERDICT_TRUE_HIT = 1,
    VERDICT_FALSE_HIT = 2,         // rule 3 failed
    VERDICT_STRICT_FALSE_HIT = 3,  // rule 3 passed, rule 4 failed
    VERDICT_CONTACT = 4,           // excluded by rule 2
    VERDICT_BACKGROUND = 5,        // the pixel shows the sky
};

struct FalseHitOptions {
    double contact_footprints = 1.0;     // rule 2 distance, in pixel footprints
    double distance_footprints = 0.5;    // rule 3 distance, in pixel footprints (docs/CONVENTIONS.md: half a pixel)
    double tap_weight_threshold = 1e-3;  // rule 4 ignores taps lighter than this (fp32 weights differ)
    double screen_tolerance_px = 0.01;   // rule 3: how far outside the image uv_prev may land
    bool count_missed = false;           // also classify unmarked pixels (missed_visible)
};

struct FalseHitReport {
    int64_t marked_hits = 0;        // pixels with RRC_MASK_HIT
    int64_t excluded_contact = 0;   // marked hits excluded by rule 2
    int64_t hits_checked = 0;       // marked_hits - excluded_contact
    int64_t false_hits = 0;         // checked hits failing rule 3 (background hits included)
    int64_t strict_false_hits = 0;  // checked hits failing rule 3 or rule 4 (>= false_hits)
    int64_t missed_visible = 0;     // count_missed only: unmarked pixels whose verdict is TRUE_HIT
    std::vector<uint8_t> verdict;   // W*H Verdict per pixel (NOT_CHECKED where not classified)

    double false_hit_ratio() const { return hits_checked ? double(false_hits) / hits_checked : 0.0; }
    double strict_false_hit_ratio() const { return hits_checked ? double(strict_false_hits) / hits_checked : 0.0; }
};

// Classifies pixels of `frame` against `prev_frame` with the rule above.
// Construction casts the previous frame's samples once (for rule 4).
class FalseHitEvaluator {
public:
    FalseHitEvaluator(const Scene& scene, int frame, int prev_frame, const FalseHitOptions& options = {});
    Verdict classify(int i, int j) const;

private:
    const Scene& scene_;
    FrameState cur_, prev_;
    FalseHitOptions options_;
    glm::dmat4 vp_prev_;
    glm::dvec2 jitter_, prev_jitter_;
    std::vector<int32_t> prev_ids_;
};

// Counts the false hits among the pixels whose mask has RRC_MASK_HIT.
// `mask` is W*H RRC_MASK_* bits of the cache's output for `frame`, which
// was reprojected against `prev_frame` (default frame - 1).
FalseHitReport count_false_hits(const Scene& scene, int frame, int prev_frame, const uint8_t* mask, const FalseHitOptions& options = {});
inline FalseHitReport count_false_hits(const Scene& scene, int frame, const uint8_t* mask, const FalseHitOptions& options = {}) {
    return count_false_hits(scene, frame, frame - 1, mask, options);
}

}  // namespace rrc_scene
