#include "peer_comparison.h"

#include <cmath>

#include "depth_setups.h"
#include "peer_scene.h"
#include "peer_tests.h"
#include "rrc_reference.h"
#include "support/scene_frames.h"

namespace rrc_peer {

namespace {

using rrc_ref::peers::kAllPeerTests;
using rrc_ref::peers::PeerTest;
using rrc_visibility::Depth;
using rrc_visibility::kCardAngles;
using rrc_visibility::kCardDepths;
using rrc_visibility::kDepths;

rrc_scene::SceneConfig config_of(const Depth& d) {
    rrc_scene::SceneConfig sc = rrc_test::scene_config(96, 64, d.mode, d.format, d.far_plane);
    sc.near_plane = d.near_plane;
    sc.jitter = true;
    return sc;
}

// The history a test fetched for pixel k takes weight from a texel that held another object.
bool mixes(const rrc_ref::peers::Decision& d, const std::vector<int32_t>& prev_ids, int32_t object) {
    for (int t = 0; t < d.taps; ++t)
        if (d.tap[t].weight > kMixWeight && prev_ids[d.tap[t].texel] != object) return true;
    return false;
}

// rrc's history: the bilinear taps of docs/CONVENTIONS.md at q = uv_prev * size - prev_jitter, all four.
rrc_ref::peers::Decision rrc_decision(const rrc_ref::FrameResult& res, size_t k, const rrc_scene::Frame& f) {
    rrc_ref::peers::Decision d;
    d.hit = (res.mask[k] & RRC_MASK_HIT) != 0;
    if (!d.hit) return d;
    const double qx = res.uv_prev_x[k] * f.width - f.prev_jitter[0] - 0.5, qy = res.uv_prev_y[k] * f.height - f.prev_jitter[1] - 0.5;
    const int x0 = static_cast<int>(std::floor(qx)), y0 = static_cast<int>(std::floor(qy));
    const double fx = qx - x0, fy = qy - y0;
    for (int t = 0; t < 4; ++t) {
        const int x = std::min(std::max(x0 + (t & 1), 0), f.width - 1), y = std::min(std::max(y0 + (t >> 1), 0), f.height - 1);
        const double w = ((t & 1) ? fx : 1 - fx) * ((t >> 1) ? fy : 1 - fy);
        d.tap[d.taps++] = {static_cast<size_t>(y) * f.width + x, w};
    }
    return d;
}

}  // namespace

const char* test_label(int test) {
    static const char* const kLabels[kTestCount] = {"rrc ADAPTIVE", "rrc FIXED", "NRD ReBLUR", "NRD ReLAX", "SVGF", "FSR2", "relative 1 %"};
    return kLabels[test];
}

const char* test_slug(int test) {
    if (test == 0) return "rrc_adaptive";
    if (test == 1) return "rrc_fixed";
    return rrc_ref::peers::peer_name(kAllPeerTests[test - 2]);
}

std::vector<CaseSpec> comparison_cases() {
    std::vector<CaseSpec> c;
    for (const char* layout : {"objects", "grazing"})
        for (const Depth& d : kDepths) {
            CaseSpec s{std::string(layout) + "_prev_clip_" + d.name, config_of(d), 5, {}};
            if (std::string(layout) == "grazing") s.config.camera_path = rrc_scene::CameraPath::GRAZING;
            c.push_back(s);
        }
    // The suite's 1280x720 geometries (hd_cases), 2 frames: FSR2's required depth separation grows
    // with the image width (Ksep d tan(fovy/2) W/2), so 96x64 alone would misjudge it.
    for (int i : {3, 1, 8}) {
        CaseSpec s{std::string(i == 1 ? "grazing" : "objects") + "_prev_clip_" + kDepths[i].name + "_1280x720", config_of(kDepths[i]), 2, {}};
        s.config.width = 1280;
        s.config.height = 720;
        if (i == 1) s.config.camera_path = rrc_scene::CameraPath::GRAZING;
        c.push_back(s);
    }
    for (double angle : kCardAngles)
        for (const Depth& d : kCardDepths) {
            CaseSpec s{"card_" + std::to_string(int(angle)) + "deg_prev_clip_" + d.name, config_of(d), 4, {}};
            s.config.jitter = false;  // as the visibility suite's card (scene_config's default)
            s.config.layout = rrc_scene::SceneLayout::THIN_CARD;
            s.config.wall_angle_degrees = angle;
            s.visibility.contact_footprints = 0.0;  // the card is closer to the wall than a footprint
            c.push_back(s);
        }
    return c;
}

CaseResult evaluate(const CaseSpec& spec) {
    CaseResult out;
    out.name = spec.name;
    const rrc_scene::Scene scene(spec.config);
    const std::vector<rrc_channel_desc> channels = {rrc_host::channel("s", 1, 0.6f)};
    rrc_context_desc ctx[2];
    for (int t = 0; t < 2; ++t) {
        ctx[t] = rrc_test::scene_context_desc(spec.config, RRC_REPROJECTION_PREV_CLIP, channels);
        ctx[t].depth_test = t == 0 ? RRC_DEPTH_TEST_DEFAULT : RRC_DEPTH_TEST_FIXED;
    }
    rrc_ref::PreviousFrame prev_state[2];
    rrc_ref::peers::GBuffer prev_g;
    rrc_ref::peers::Options peer_options;
    peer_options.inverted_depth = spec.config.depth_mode == RRC_DEPTH_MODE_REVERSED;
    std::vector<int32_t> prev_ids;
    for (int frame = 0; frame < spec.frames; ++frame) {
        rrc_test::SceneFrameInputs in;
        in.frame = scene.render(frame);
        rrc_test::make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, channels);
        const rrc_scene::Frame& f = in.frame;
        rrc_ref::FrameResult res[2];
        for (int t = 0; t < 2; ++t) {
            res[t] = rrc_ref::run_frame(ctx[t], prev_state[t], in.desc);
            prev_state[t] = rrc_ref::as_previous(ctx[t], in.desc, res[t]);
        }
        out.adaptive_masks.push_back(res[0].mask);
        out.adaptive_near.push_back(res[0].near_threshold);
        const rrc_ref::peers::GBuffer g = make_gbuffer(scene, f);
        if (frame > 0) {
            const rrc_scene::VisibilityMap map = rrc_scene::true_visibility(scene, frame, spec.visibility);
            const rrc_ref::peers::Reprojection r = make_reprojection(scene, f);
            const size_t n = g.size();
            for (int test = 0; test < kTestCount; ++test) {
                std::vector<rrc_ref::peers::Decision> dec(n);
                if (test < 2) {
                    for (size_t k = 0; k < n; ++k) dec[k] = rrc_decision(res[test], k, f);
                } else {
                    dec = rrc_ref::peers::run_peer_test(kAllPeerTests[test - 2], g, r, prev_g, peer_options);
                }
                std::vector<uint8_t> mask(n, 0), hits(n, 0);
                for (size_t k = 0; k < n; ++k) {
                    hits[k] = dec[k].hit;
                    mask[k] = dec[k].hit ? RRC_MASK_HIT : 0;
                    if (dec[k].hit && rrc_scene::VisibilityMap::not_visible(map.cls[k]) && mixes(dec[k], prev_ids, map.object[k]))
                        ++out.tests[test].mixing;
                }
                out.tests[test].score += rrc_scene::score_mask(map, mask.data());
                if (frame == spec.frames - 1) out.last_hits[test] = hits;
            }
            if (frame == spec.frames - 1) out.last_map = map;
        }
        prev_g = g;
        prev_ids = f.object_id;
    }
    return out;
}

}  // namespace rrc_peer
