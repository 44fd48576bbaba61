// Views (rrc_context_desc.view_count, rrc_frame_desc.view/.reproject_from):
// a frame writes its own view's state and reprojects from its own previous
// frame or another view's latest one (docs/CONVENTIONS.md, "Views").  A
// stereo-like pair on a fronto-parallel plane: view 1's camera is view 0's
// shifted by exactly two pixels, so every reprojected texel centre lands on
// a texel centre and the expected values are exact.
#include "support/rrc_test_context.h"
#include "support/split_frame.h"

#include <cmath>
#include <set>

namespace {

constexpr uint32_t W = 16, H = 8, N = W * H;
constexpr int kShift = 2;  // pixels between the two views

struct Pair {
    std::vector<rrc_channel_desc> channels{
        rrc_test::channel("shade", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST),
        rrc_test::channel("avg", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_FIXED)};
    rrc_context_desc desc() const {
        rrc_context_desc d = rrc_test::context_desc(W, H, channels);
        d.reprojection = RRC_REPROJECTION_CAMERA;
        d.view_count = 2;
        return d;
    }
};

// Clip = T * ndc: view 1 sees the plane kShift pixels to the right of view 0.
void camera(int view, double m[16]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    if (view == 1) m[12] = 2.0 * kShift / W;  // column 3, row 0: x translation in NDC
}

struct Inputs {
    std::vector<float> depth = std::vector<float>(N, 0.5f), shade = std::vector<float>(N), avg = std::vector<float>(N);
    std::vector<rrc_channel_input> in;
    rrc_frame_desc frame(uint32_t view, uint32_t from_view_plus_one, int prev_camera, uint64_t index) {
        in = {rrc_test::channel_input(shade.data()), rrc_test::channel_input(avg.data())};
        rrc_frame_desc f = rrc_test::frame_desc();
        f.frame_index = index;
        f.depth = depth.data();
        f.channel_count = 2;
        f.channels = in.data();
        f.view = view;
        f.reproject_from = from_view_plus_one;
        camera((int)view, f.view_proj);
        camera(prev_camera, f.prev_view_proj);
        return f;
    }
};

float value0(uint32_t x, uint32_t y) { return 10.0f * x + y; }

// The stereo pair's context, and view 0's first shading (value0) in the inputs.
class Views : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_TRUE(ctx); }
    void shade_view0() {
        for (uint32_t i = 0; i < N; ++i) in.shade[i] = value0(i % W, i / W), in.avg[i] = 1.0f;
    }
    Pair pair;
    rrc_test::Context ctx{pair.desc()};
    Inputs in;
};

TEST_F(Views, AnEyeReusesTheOtherEyesShadingAndLeavesItsStateAlone) {
    shade_view0();
    const auto a = ctx.run(in.frame(0, 0, 0, 0));  // view 0, no history: all misses
    for (uint32_t i = 0; i < N; ++i) ASSERT_EQ(a.mask[i] & RRC_MASK_HIT, 0u);

    for (uint32_t i = 0; i < N; ++i) in.shade[i] = 1000.0f + i, in.avg[i] = 3.0f;
    const auto b = ctx.run(in.frame(1, 1, 0, 0));  // view 1 from view 0 (same time: same index)
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            const uint32_t i = y * W + x;
            SCOPED_TRACE("x " + std::to_string(x) + " y " + std::to_string(y));
            if (x >= (uint32_t)kShift) {
                EXPECT_EQ(b.mask[i] & RRC_MASK_HIT, (unsigned)RRC_MASK_HIT);
                EXPECT_EQ(b.values[0][i], value0(x - kShift, y)) << "view 0's shading, reused";
                EXPECT_EQ(b.age[0][i], 2u);
                EXPECT_EQ(b.values[1][i], 2.0f) << "0.5 * view 0's 1 + 0.5 * 3";
            } else {
                EXPECT_EQ(b.mask[i] & RRC_MASK_HIT, 0u) << "reprojects outside view 0";
                EXPECT_EQ(b.values[0][i], 1000.0f + i);
                EXPECT_EQ(b.age[0][i], 1u);
            }
        }

    for (uint32_t i = 0; i < N; ++i) in.shade[i] = -1.0f, in.avg[i] = 5.0f;
    const auto c = ctx.run(in.frame(0, 0, 0, 1));  // view 0 again, from its own previous frame
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            const uint32_t i = y * W + x;
            EXPECT_EQ(c.mask[i] & RRC_MASK_HIT, (unsigned)RRC_MASK_HIT);
            EXPECT_EQ(c.values[0][i], value0(x, y)) << "view 1's frame did not touch view 0's cache";
            EXPECT_EQ(c.values[1][i], 3.0f) << "0.5 * view 0's own 1 + 0.5 * 5";
        }
}

TEST_F(Views, ClassifyListsOnlyWhatTheOtherEyeCannotGive) {
    shade_view0();
    ctx.run(in.frame(0, 0, 0, 7));
    rrc_frame_desc f = in.frame(1, 1, 0, 7);
    rrc_test::Classification cl(W, H);
    ASSERT_EQ(cl.run(ctx.get(), f), RRC_SUCCESS) << rrc_last_error();
    std::set<uint32_t> expected;
    for (uint32_t qy = 0; qy < H / 2; ++qy) expected.insert(0u | qy << 16);  // the quad column x = 0..1
    EXPECT_EQ(cl.listed(), expected);
    EXPECT_EQ(cl.out.stats.hits, (uint64_t)(W - kShift) * H);
}

TEST_F(Views, AViewWithoutAFrameGivesNothingAndBadViewsAreRefused) {
    const auto r = ctx.run(in.frame(1, 1, 0, 0));  // view 0 has no frame yet
    for (uint32_t i = 0; i < N; ++i) ASSERT_EQ(r.mask[i] & RRC_MASK_HIT, 0u);
    for (auto bad : {std::make_pair(2u, 0u), std::make_pair(0u, 3u)}) {
        rrc_frame_desc f = in.frame(0, 0, 0, 1);
        f.view = bad.first;
        f.reproject_from = bad.second;
        EXPECT_EQ(rrc_frame_run(ctx.get(), &f, nullptr), RRC_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(rrc_last_error()).find(bad.first ? "frame.view" : "frame.reproject_from"), std::string::npos)
            << rrc_last_error();
    }
    rrc_context_desc d = pair.desc();
    d.view_count = RRC_MAX_VIEWS + 1;
    EXPECT_EQ(rrc_validate_context_desc(&d), RRC_ERROR_INVALID_ARGUMENT);
}

}  // namespace
