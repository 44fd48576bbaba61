// The oracle of true visibility (the rule is documented in visibility.h).
#include "scenes/visibility.h"

#include <algorithm>
#include <cmath>

#include "scenes/bilinear.h"

namespace rrc_scene {
namespace {

// ulp of a value as fp32 stores it: 2^(floor(log2|v|) - 23), 2^-149 at 0
// (docs/CONVENTIONS.md, the FLOAT32 increment).
double fp32_ulp(double v) {
    const float f = static_cast<float>(std::abs(v));
    if (!(f >= 1.1754944e-38f)) return std::ldexp(1.0, -149);
    return std::ldexp(1.0, std::ilogb(f) - 23);
}

// One depth-format step at planar depth d, as a view distance: the z
// increment over |dz/dd| = |zb| / d^2 in the NDC modes (z = za + zb / d), the
// fp32 ulp of d itself in LINEAR.
double depth_step_distance(const Scene& scene, double d) {
    const SceneConfig& c = scene.config();
    if (c.depth_mode == RRC_DEPTH_MODE_LINEAR) return fp32_ulp(d);
    double step_z;
    switch (c.depth_format) {
        case RRC_DEPTH_FORMAT_UNORM16: step_z = 1.0 / 65535.0; break;
        case RRC_DEPTH_FORMAT_UNORM24: step_z = 1.0 / 16777215.0; break;
        default: step_z = fp32_ulp(scene.projection().ndc_z(d)); break;
    }
    return step_z * d * d / std::abs(scene.projection().zb);
}

// Does an object other than `object` cross the ray eye + t dir for t in (lo, hi)?
bool other_surface_on_ray(const Scene& scene, const FrameState& st, int32_t object, const glm::dvec3& dir, double lo, double hi) {
    for (int32_t other : scene.objects()) {
        if (other == object) continue;
        const RigidTransform& m = st.models[other];
        if (intersect_shape(scene.shape(other), m.to_object(st.camera.eye), m.dir_to_object(dir), lo, hi) >= 0.0) return true;
    }
    return false;
}

// The previous frame's samples: each texel's object and whether its stored depth reads as background.
struct PreviousTexels {
    std::vector<int32_t> object;
    std::vector<uint8_t> stored_background;
};

PreviousTexels previous_texels(const Scene& scene, const FrameState& prev, const glm::dvec2& jitter) {
    const int w = scene.width(), h = scene.height();
    const float background = scene.background_depth();
    PreviousTexels p;
    p.object.resize(static_cast<size_t>(w) * h);
    p.stored_background.resize(p.object.size());
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const size_t k = static_cast<size_t>(j) * w + i;
            const Hit hit = scene.cast(prev, i + 0.5 + jitter.x, j + 0.5 + jitter.y);
            p.object[k] = hit.object_id;
            p.stored_background[k] = hit.object_id == OBJECT_BACKGROUND || scene.stored_depth(hit.depth) == background;
        }
    }
    return p;
}

// Does any texel of the four bilinear taps at sample coordinate q (prev
// jitter removed), for any q within kQRounding of it, read as background?
// kQRounding: 2^-20 of the image size, twice the fp32 error of q that
// docs/CONVENTIONS.md ("The ADAPTIVE test", POSITION_ULPS) allows the kernel
// (its input clip position is fp32 too).
bool footprint_reads_background(const glm::dvec2& q, int w, int h, const PreviousTexels& texels) {
    const glm::dvec2 p = q - 0.5, tol = std::ldexp(1.0, -20) * glm::dvec2(w, h);
    const glm::ivec2 lo = glm::ivec2(glm::floor(p - tol)), hi = glm::ivec2(glm::floor(p + tol)) + 1;
    for (int y = std::max(lo.y, 0); y <= std::min(hi.y, h - 1); ++y)
        for (int x = std::max(lo.x, 0); x <= std::min(hi.x, w - 1); ++x)
            if (texels.stored_background[static_cast<size_t>(y) * w + x]) return true;
    // Taps clamped to the image: an out-of-range coordinate reads the edge texel, already covered.
    return false;
}

}  // namespace

const char* visibility_class_name(VisibilityClass c) {
    switch (c) {
        case VIS_BACKGROUND: return "background";
        case VIS_VISIBLE: return "visible";
        case VIS_OCCLUDED: return "occluded";
        case VIS_OFFSCREEN: return "offscreen";
        case VIS_STRADDLING: return "straddling";
        case VIS_EXCLUDED_QUANTISED: return "quantised";
        case VIS_EXCLUDED_CONTACT: return "contact";
        case VIS_EXCLUDED_DEPTH_STEP: return "depth_step";
        default: return "?";
    }
}

VisibilityMap true_visibility(const Scene& scene, int frame, int prev_frame, const VisibilityOptions& options) {
    const int w = scene.width(), h = scene.height();
    const size_t n = static_cast<size_t>(w) * h;
    const FrameState cur = scene.frame_state(frame), prev = scene.frame_state(prev_frame);
    const glm::dvec2 jitter = scene.jitter(frame), prev_jitter = scene.jitter(prev_frame);
    const glm::dmat4 vp_prev = scene.view_proj(prev_frame);
    const PreviousTexels texels = previous_texels(scene, prev, prev_jitter);
    const float background = scene.background_depth();

    VisibilityMap map;
    map.width = w;
    map.height = h;
    map.cls.assign(n, VIS_BACKGROUND);
    map.object.assign(n, OBJECT_BACKGROUND);
    map.depth.assign(n, INFINITY);
    map.prev_depth.assign(n, INFINITY);

    // The class of one pixel; fills its depths on the way.
    auto classify = [&](int i, int j, size_t k) -> VisibilityClass {
        const Hit x = scene.cast(cur, i + 0.5 + jitter.x, j + 0.5 + jitter.y);
        if (x.object_id == OBJECT_BACKGROUND) return VIS_BACKGROUND;
        const int32_t o = x.object_id;
        map.object[k] = o;
        map.depth[k] = x.depth;
        if (scene.stored_depth(x.depth) == background) return VIS_EXCLUDED_QUANTISED;

        const glm::dvec3 x_prev = prev.models[o].to_world(x.object);
        const glm::dvec4 clip = vp_prev * glm::dvec4(x_prev, 1.0);
        map.prev_depth[k] = clip.w;
        const double contact = options.contact_footprints;
        if (contact > 0.0) {
            if (scene.near_other_object(o, cur, x.world, contact * scene.pixel_footprint(x.depth))) return VIS_EXCLUDED_CONTACT;
            if (clip.w > 0.0 && scene.near_other_object(o, prev, x_prev, contact * scene.pixel_footprint(clip.w)))
                return VIS_EXCLUDED_CONTACT;
        }
        if (!(clip.w > 0.0)) return VIS_OFFSCREEN;
        const glm::dvec2 uv_prev = (glm::dvec2(clip) / clip.w + 1.0) * 0.5;
        if (!(uv_prev.x >= 0.0 && uv_prev.x <= 1.0 && uv_prev.y >= 0.0 && uv_prev.y <= 1.0)) return VIS_OFFSCREEN;

        const glm::dvec2 pixel = uv_prev * glm::dvec2(w, h);
        const Hit seen = scene.cast(prev, pixel.x, pixel.y);
        // The previous ray through X_prev: its parameter is the planar depth (Hit::direction).
        const double step = depth_step_distance(scene, clip.w);
        if (other_surface_on_ray(scene, prev, o, seen.direction, clip.w - step, clip.w + step)) return VIS_EXCLUDED_DEPTH_STEP;
        if (seen.object_id != o || glm::length(seen.world - x_prev) > options.distance_relative * clip.w) return VIS_OCCLUDED;

        const BilinearTaps taps = bilinear_taps(pixel, prev_jitter, w, h);
        bool tap_stored_background = false;
        for (int t = 0; t < 4; ++t) {
            if (!(taps.weight[t] > options.tap_weight_threshold)) continue;
            const size_t tk = taps.index(t, w);
            if (texels.object[tk] != o) return VIS_STRADDLING;
            tap_stored_background |= texels.stored_background[tk] != 0;
        }
        if (tap_stored_background) return VIS_EXCLUDED_QUANTISED;
        // The library's test misses on a background tap whatever its weight
        // (docs/CONVENTIONS.md, Previous depth fetch and the hit test), and
        // it computes q in fp32: a texel that q's rounding can bring into the
        // four taps (with weight 0 when q lands on a texel centre, as on a
        // still camera without jitter) counts as one of them.
        if (footprint_reads_background(pixel - prev_jitter, w, h, texels)) return VIS_STRADDLING;
        return VIS_VISIBLE;
    };

    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const size_t k = static_cast<size_t>(j) * w + i;
            const VisibilityClass c = classify(i, j, k);
            map.cls[k] = c;
            ++map.counts[c];
        }
    }
    return map;
}

RecallScore& RecallScore::operator+=(const RecallScore& o) {
    scored += o.scored;
    hits += o.hits;
    not_visible += o.not_visible;
    false_hits += o.false_hits;
    for (int c = 0; c < VIS_CLASS_COUNT; ++c) counts[c] += o.counts[c];
    return *this;
}

RecallScore score_mask(const VisibilityMap& map, const uint8_t* mask, const std::function<bool(size_t)>& keep) {
    RecallScore s;
    for (size_t k = 0; k < map.cls.size(); ++k) {
        if (keep && !keep(k)) continue;
        const uint8_t c = map.cls[k];
        const bool hit = (mask[k] & RRC_MASK_HIT) != 0;
        ++s.counts[c];
        if (VisibilityMap::scored(c)) {
            ++s.scored;
            s.hits += hit;
        } else if (VisibilityMap::not_visible(c)) {
            ++s.not_visible;
            s.false_hits += hit;
        }
    }
    return s;
}

}  // namespace rrc_scene
