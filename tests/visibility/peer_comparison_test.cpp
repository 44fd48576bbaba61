// docs/measurements/COMPARISON.md's generator (peer_comparison.h) on one small case: its
// rrc ADAPTIVE masks, made by the double-precision reference, are the
// library's (the visibility suite's) wherever the reference is sure of the
// decision, with the suite's 0 false hits; and every test's counts are
// consistent with the oracle's and with the history each test fetches.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "peer_comparison.h"
#include "peer_scene.h"
#include "peer_tests.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"

using namespace rrc_peer;

namespace {

CaseSpec small_case() {
    for (CaseSpec s : comparison_cases())
        if (s.name == "objects_prev_clip_reversed_f32_inf_near_0_1") {
            s.frames = 3;
            return s;
        }
    ADD_FAILURE() << "case missing";
    return {};
}

TEST(PeerComparison, ReferenceAdaptiveIsTheLibrarysDefaultTest) {
    const CaseSpec spec = small_case();
    const CaseResult r = evaluate(spec);
    const rrc_scene::Scene scene(spec.config);
    const std::vector<rrc_channel_desc> channels = {rrc_test::channel("s", 1, 0.6f)};
    rrc_context_desc desc = rrc_test::scene_context_desc(spec.config, RRC_REPROJECTION_PREV_CLIP, channels);
    desc.depth_test = RRC_DEPTH_TEST_DEFAULT;
    rrc_test::Context ctx(desc);
    ASSERT_TRUE(ctx);
    int64_t sure = 0, differ = 0;
    for (int frame = 0; frame < spec.frames; ++frame) {
        rrc_test::SceneFrameInputs in;
        in.frame = scene.render(frame);
        rrc_test::make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, channels);
        const std::vector<uint8_t> lib = ctx.run(in.desc).mask;
        ASSERT_EQ(lib.size(), r.adaptive_masks[frame].size());
        for (size_t k = 0; k < lib.size(); ++k) {
            const bool a = lib[k] & RRC_MASK_HIT, b = r.adaptive_masks[frame][k] & RRC_MASK_HIT;
            if (r.adaptive_near[frame][k]) continue;
            ++sure;
            differ += a != b;
        }
    }
    EXPECT_GT(sure, int64_t(spec.config.width) * spec.config.height) << "most decisions are sure";
    EXPECT_EQ(differ, 0) << "the reference's sure decisions are the library's";
    // The visibility suite's contract for PREV_CLIP: no false hit, recall >= 99.5 %.
    EXPECT_EQ(r.tests[0].score.false_hits, 0);
    EXPECT_GE(r.tests[0].score.recall(), 0.995);
}

TEST(PeerComparison, CountsAreConsistent) {
    const CaseSpec spec = small_case();
    const CaseResult r = evaluate(spec);
    for (int t = 0; t < kTestCount; ++t) {
        const TestScore& s = r.tests[t];
        EXPECT_EQ(s.score.scored, r.tests[0].score.scored) << test_label(t) << ": one oracle for every test";
        EXPECT_EQ(s.score.not_visible, r.tests[0].score.not_visible) << test_label(t);
        EXPECT_LE(s.score.hits, s.score.scored) << test_label(t);
        EXPECT_LE(s.score.false_hits, s.score.not_visible) << test_label(t);
        EXPECT_LE(s.mixing, s.score.false_hits) << test_label(t);
        // Every test but FSR2 keeps most visible pixels; FSR2's required separation
        // (Ksep d tan(fovy/2) W/2) is below one pixel's depth slope at 96 pixels wide.
        if (std::string(test_label(t)) != "FSR2") EXPECT_GT(s.score.hits, s.score.scored / 2) << test_label(t);
        // The last frame's hits are the ones scored.
        int64_t last_false = 0;
        for (size_t k = 0; k < r.last_hits[t].size(); ++k)
            last_false += r.last_hits[t][k] && rrc_scene::VisibilityMap::not_visible(r.last_map.cls[k]);
        EXPECT_LE(last_false, s.score.false_hits) << test_label(t);
    }
    // Each peer's fetched history is a normalised set of texels (ReLAX may keep history whose
    // passing taps all have zero bilinear weight: then none).
    const rrc_scene::Scene scene(spec.config);
    const rrc_scene::Frame f0 = scene.render(0), f1 = scene.render(1);
    const rrc_ref::peers::GBuffer g0 = make_gbuffer(scene, f0), g1 = make_gbuffer(scene, f1);
    const rrc_ref::peers::Reprojection rp = make_reprojection(scene, f1);
    for (rrc_ref::peers::PeerTest t : rrc_ref::peers::kAllPeerTests) {
        int hits = 0;
        for (const rrc_ref::peers::Decision& d : rrc_ref::peers::run_peer_test(t, g1, rp, g0)) {
            if (!d.hit) continue;
            ++hits;
            double sum = 0.0;
            for (int k = 0; k < d.taps; ++k) sum += d.tap[k].weight;
            if (d.taps > 0 || t != rrc_ref::peers::PeerTest::NRD_RELAX) EXPECT_NEAR(sum, 1.0, 1e-9) << rrc_ref::peers::peer_name(t);
        }
        EXPECT_GT(hits, 0) << rrc_ref::peers::peer_name(t);
    }
}

}  // namespace
