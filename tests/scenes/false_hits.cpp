// Ground-truth false-hit evaluation (the rule is documented in false_hits.h).
#include "scenes/false_hits.h"

#include <cmath>

#include "scenes/bilinear.h"

namespace rrc_scene {

FalseHitEvaluator::FalseHitEvaluator(const Scene& scene, int frame, int prev_frame, const FalseHitOptions& options)
    : scene_(scene),
      cur_(scene.frame_state(frame)),
      prev_(scene.frame_state(prev_frame)),
      options_(options),
      vp_prev_(scene.view_proj(prev_frame)),
      jitter_(scene.jitter(frame)),
      prev_jitter_(scene.jitter(prev_frame)),
      prev_ids_(scene.object_ids(prev_frame)) {}

Verdict FalseHitEvaluator::classify(int i, int j) const {
    const int w = scene_.width(), h = scene_.height();
    // Rule 1: the pixel's own sample.
    const Hit cur = scene_.cast(cur_, i + 0.5 + jitter_.x, j + 0.5 + jitter_.y);
    if (cur.object_id == OBJECT_BACKGROUND) return VERDICT_BACKGROUND;
    const int32_t o = cur.object_id;

    // Rule 2, current frame.
    if (scene_.near_other_object(o, cur_, cur.world, options_.contact_footprints * scene_.pixel_footprint(cur.depth)))
        return VERDICT_CONTACT;

    // P moved with its object to the previous frame and projected there.
    const glm::dvec3 p_prev = prev_.models[o].to_world(cur.object);
    const glm::dvec4 clip = vp_prev_ * glm::dvec4(p_prev, 1.0);
    if (!(clip.w > 0.0)) return VERDICT_FALSE_HIT;  // behind the previous camera
    const double fp_prev = scene_.pixel_footprint(clip.w);

    // Rule 2, previous frame.
    if (scene_.near_other_object(o, prev_, p_prev, options_.contact_footprints * fp_prev)) return VERDICT_CONTACT;

    // Rule 3: is P' the first surface on the previous frame's ray through it?
    const double px = (clip.x / clip.w + 1.0) * 0.5 * w;
    const double py = (clip.y / clip.w + 1.0) * 0.5 * h;
    const double tol = options_.screen_tolerance_px;
    if (px < -tol || px > w + tol || py < -tol || py > h + tol) return VERDICT_FALSE_HIT;
    const Hit seen = scene_.cast(prev_, px, py);
    if (seen.object_id != o) return VERDICT_FALSE_HIT;
    if (glm::length(seen.world - p_prev) > options_.distance_footprints * fp_prev) return VERDICT_FALSE_HIT;

    // Rule 4: the bilinear taps of the history fetch (CONVENTIONS.md).
    const BilinearTaps taps = bilinear_taps(glm::dvec2(px, py), prev_jitter_, w, h);
    for (int t = 0; t < 4; ++t) {
        if (!(taps.weight[t] > options_.tap_weight_threshold)) continue;
        if (prev_ids_[taps.index(t, w)] != o) return VERDICT_STRICT_FALSE_HIT;
    }
    return VERDICT_TRUE_HIT;
}

FalseHitReport count_false_hits(const Scene& scene, int frame, int prev_frame, const uint8_t* mask, const FalseHitOptions& options) {
    const int w = scene.width(), h = scene.height();
    FalseHitEvaluator eval(scene, frame, prev_frame, options);
    FalseHitReport r;
    r.verdict.assign(static_cast<size_t>(w) * h, VERDICT_NOT_CHECKED);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const size_t k = static_cast<size_t>(j) * w + i;
            const bool marked = (mask[k] & RRC_MASK_HIT) != 0;
            if (!marked && !options.count_missed) continue;
            const Verdict v = eval.classify(i, j);
            r.verdict[k] = v;
            if (!marked) {
                if (v == VERDICT_TRUE_HIT) ++r.missed_visible;
                continue;
            }
            ++r.marked_hits;
            if (v == VERDICT_CONTACT) {
                ++r.excluded_contact;
                continue;
            }
            ++r.hits_checked;
            if (v == VERDICT_FALSE_HIT || v == VERDICT_BACKGROUND) ++r.false_hits;
            if (v != VERDICT_TRUE_HIT) ++r.strict_false_hits;
        }
    }
    return r;
}

}  // namespace rrc_scene
