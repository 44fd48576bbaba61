// Which depth test a context gets (docs/CONVENTIONS.md, "Which test"): the
// 0.2 default is ADAPTIVE, a 0.1 caller's zero keeps the paper's FIXED test,
// and any host tolerance selects FIXED.  Observed through the masks on a
// curved, moving scene, where the two tests differ.
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"

#include <gtest/gtest.h>

using namespace rrc_test;

namespace {

// The masks of frames 1..3 of the analytic scene (spheres, boxes, moving
// camera and sphere) under the context `edit` makes of the defaults.
template <typename Edit>
std::vector<uint8_t> masks(Edit edit) {
    rrc_scene::SceneConfig sc = scene_config(96, 64, RRC_DEPTH_MODE_STANDARD);
    sc.jitter = true;
    rrc_scene::Scene scene(sc);
    std::vector<rrc_channel_desc> channels = {channel("c", 1, 0.5f, RRC_HISTORY_FP32)};
    rrc_context_desc d = scene_context_desc(sc, RRC_REPROJECTION_PREV_CLIP, channels);
    edit(d);
    Context ctx(d);
    EXPECT_TRUE(ctx);
    if (!ctx) return {};
    std::vector<uint8_t> all;
    for (int t = 0; t < 4; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, channels);
        FrameResult r = ctx.run(in.desc);
        if (t > 0) all.insert(all.end(), r.mask.begin(), r.mask.end());
    }
    return all;
}

size_t hits(const std::vector<uint8_t>& m) {
    size_t n = 0;
    for (uint8_t b : m) n += (b & RRC_MASK_HIT) ? 1 : 0;
    return n;
}

}  // namespace

TEST(DepthTestChoice, DefaultIsAdaptiveOldCallersAndTolerancesAreFixed) {
    const std::vector<uint8_t> by_default = masks([](rrc_context_desc&) {});
    const std::vector<uint8_t> adaptive = masks([](rrc_context_desc& d) { d.depth_test = RRC_DEPTH_TEST_ADAPTIVE; });
    const std::vector<uint8_t> fixed = masks([](rrc_context_desc& d) { d.depth_test = RRC_DEPTH_TEST_FIXED; });
    const std::vector<uint8_t> old_caller = masks([](rrc_context_desc& d) { d.api_version = RRC_MAKE_VERSION(0, 1, 0); });
    const std::vector<uint8_t> scale = masks([](rrc_context_desc& d) { d.epsilon_scale = RRC_DEFAULT_EPSILON_SCALE_FLOAT32; });
    EXPECT_EQ(by_default, adaptive);
    EXPECT_EQ(fixed, old_caller) << "a 0.1 caller's zero means the 0.1 test";
    EXPECT_EQ(fixed, scale) << "a host epsilon_scale (here the FIXED default, 4) selects FIXED";
    // The two tests must differ here, or the comparisons above prove nothing.
    EXPECT_GT(hits(by_default), hits(fixed) + hits(fixed) / 50) << "ADAPTIVE keeps more of the curved surfaces";
}
