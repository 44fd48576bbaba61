// Reprojection edge cases (docs/measurements/STABILITY.md): motion far off-screen, vectors
// of a million pixels, previous clip w <= 0 (behind the previous camera, even
// where x/w, y/w, z/w would land inside the image), NaN or Inf in depth,
// motion or previous clip, points just outside the image: all misses, never
// a value fetched from the image edge.
//
// Frame 0 writes history 1000 everywhere; frame 1 brings s = 1 and crafted
// reprojection data per pixel.  A miss must store exactly s with age 1 (no
// trace of the 1000); a hit stores 0.5·1000 + 0.5·1 = 500.5 with age 2.
#include "stability_report.h"
#include "stability_util.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

using namespace rrc_stab;
using rrc_test::channel;

namespace {

constexpr int kW = 16, kH = 16;
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

struct Expect {
    bool hit, invalid;
};

// One pixel's crafted data: writes its reprojection (and may change its
// depth) and says what must happen.
struct PixelCase {
    const char* name;
    std::function<Expect(int i, int j, float* reprojection, float& depth)> make;
};

float uv_x(int i) { return (i + 0.5f) / kW; }
float uv_y(int j) { return (j + 0.5f) / kH; }

std::vector<PixelCase> prev_clip_cases() {
    // Previous clip (x, y, z, w) of a point at uv with NDC depth z, scaled by w.
    auto clip = [](float* c, float u, float v, float z, float w) {
        c[0] = (2.0f * u - 1.0f) * w;
        c[1] = (2.0f * v - 1.0f) * w;
        c[2] = z * w;
        c[3] = w;
    };
    return {
        {"identity (control)",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             return Expect{true, false};
         }},
        {"10 images off-screen",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i) + 10.0f, uv_y(j), 0.5f, 1.0f);
             return Expect{false, false};
         }},
        {"1e6 pixels away",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j) - 1e6f / kH, 0.5f, 1.0f);
             return Expect{false, false};
         }},
        {"w = 0",
         [=](int, int, float* c, float&) {
             clip(c, 0.5f, 0.5f, 0.5f, 0.0f);
             return Expect{false, false};
         }},
        {"w = -0",
         [=](int, int, float* c, float&) {
             clip(c, 0.5f, 0.5f, 0.5f, -0.0f);
             return Expect{false, false};
         }},
        {"w < 0, x/w y/w z/w inside",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j), 0.5f, -1.0f);
             return Expect{false, false};
         }},
        {"w = 1e-38 (x/w overflows)",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             c[3] = 1e-38f;
             return Expect{false, false};
         }},
        {"NaN x",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             c[0] = kNaN;
             return Expect{false, true};
         }},
        {"+Inf w",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             c[3] = kInf;
             return Expect{false, true};
         }},
        {"-Inf z",
         [=](int i, int j, float* c, float&) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             c[2] = -kInf;
             return Expect{false, true};
         }},
        {"just left of the image",
         [=](int, int j, float* c, float&) {
             clip(c, -1e-3f, uv_y(j), 0.5f, 1.0f);
             return Expect{false, false};
         }},
        {"just below the image",
         [=](int i, int, float* c, float&) {
             clip(c, uv_x(i), 1.0f + 1e-3f, 0.5f, 1.0f);
             return Expect{false, false};
         }},
        {"on the image edge uv = 0 (closed square: a hit)",
         [=](int, int j, float* c, float&) {
             clip(c, 0.0f, uv_y(j), 0.5f, 1.0f);
             return Expect{true, false};
         }},
        {"NaN depth",
         [=](int i, int j, float* c, float& d) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             d = kNaN;
             return Expect{false, true};
         }},
        {"+Inf depth",
         [=](int i, int j, float* c, float& d) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             d = kInf;
             return Expect{false, true};
         }},
        {"-Inf depth",
         [=](int i, int j, float* c, float& d) {
             clip(c, uv_x(i), uv_y(j), 0.5f, 1.0f);
             d = -kInf;
             return Expect{false, true};
         }},
    };
}

std::vector<PixelCase> motion_cases() {
    // Motion in pixels (motion_scale = 1/size), third component: depth change.
    auto mv = [](float* m, float x, float y, float dz) {
        m[0] = x;
        m[1] = y;
        m[2] = dz;
    };
    // The same motion on every pixel.
    auto uniform = [=](float x, float y, float dz, Expect e) {
        return [=](int, int, float* m, float&) {
            mv(m, x, y, dz);
            return e;
        };
    };
    return {
        {"zero motion (control)", uniform(0, 0, 0, {true, false})},
        {"10 images off-screen", uniform(10.0f * kW, 0, 0, {false, false})},
        {"1e6 pixels", uniform(1e6f, -1e6f, 0, {false, false})},
        {"1e38 pixels (scaled: still finite)", uniform(1e38f, 0, 0, {false, false})},
        {"NaN motion", uniform(kNaN, 0, 0, {false, true})},
        {"Inf motion", uniform(0, -kInf, 0, {false, true})},
        {"NaN depth change", uniform(0, 0, kNaN, {false, true})},
        {"Inf depth change", uniform(0, 0, kInf, {false, true})},
        {"huge depth change", uniform(0, 0, 1e30f, {false, false})},
        {"just off the left edge",
         [=](int i, int, float* m, float&) {
             mv(m, -(i + 0.5f) - 1e-3f, 0, 0);
             return Expect{false, false};
         }},
        {"just off the bottom edge",
         [=](int, int j, float* m, float&) {
             mv(m, 0, kH - (j + 0.5f) + 1e-3f, 0);
             return Expect{false, false};
         }},
        {"NaN depth",
         [=](int, int, float* m, float& d) {
             mv(m, 0, 0, 0);
             d = kNaN;
             return Expect{false, true};
         }},
    };
}

// Runs frame 0 (history 1000) and frame 1 (the cases, pixel k gets case
// k mod cases.size()) and checks every pixel.  Returns a report line.
std::string run_cases(rrc_reprojection source, const std::vector<PixelCase>& cases) {
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f, RRC_HISTORY_FP32),
                                              channel("h", 4, 0.5f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_CATMULL_ROM)};
    rrc_context_desc d = rrc_test::context_desc(kW, kH, channels);
    d.reprojection = source;
    d.motion_scale[0] = 1.0f / kW;
    d.motion_scale[1] = 1.0f / kH;
    d.depth_format = RRC_DEPTH_FORMAT_UNORM24;  // absolute epsilon: a depth change of 1e30 is a plain miss
    rrc_test::Context ctx(d);
    if (!ctx) return "context failed";
    const size_t n = kW * kH;
    const int stride = source == RRC_REPROJECTION_PREV_CLIP ? 4 : 3;

    std::vector<FrameData> frames(2);
    std::vector<Expect> expect(n);
    for (int t = 0; t < 2; ++t) {
        FrameData& f = frames[t];
        f.index = t;
        f.depth.assign(n, 0.5f);
        f.reprojection.assign(n * stride, 0.0f);
        const float value = t == 0 ? 1000.0f : 1.0f;
        f.samples = {std::vector<float>(n, value), std::vector<float>(4 * n, value)};
        for (int j = 0; j < kH; ++j)
            for (int i = 0; i < kW; ++i) {
                const size_t p = (size_t)j * kW + i;
                const PixelCase& c = cases[t == 0 ? 0 : p % cases.size()];  // frame 0: the control everywhere
                Expect e = c.make(i, j, &f.reprojection[stride * p], f.depth[p]);
                if (t == 1) expect[p] = e;
            }
    }
    std::vector<rrc_test::FrameResult> r = run_batch(ctx.get(), ctx.desc(), frames);
    EXPECT_EQ(r[0].stats.hits, 0u);
    std::vector<int> seen(cases.size(), 0);
    for (size_t p = 0; p < n; ++p) {
        const PixelCase& c = cases[p % cases.size()];
        const Expect& e = expect[p];
        const uint8_t m = r[1].mask[p];
        EXPECT_EQ((m & RRC_MASK_HIT) != 0, e.hit) << c.name << " pixel " << p;
        EXPECT_EQ((m & RRC_MASK_INVALID_GEOMETRY) != 0, e.invalid) << c.name << " pixel " << p;
        const float want = e.hit ? 500.5f : 1.0f;
        EXPECT_EQ(r[1].values[0][p], want) << c.name << " pixel " << p;
        EXPECT_EQ(r[1].age[0][p], e.hit ? 2 : 1) << c.name << " pixel " << p;
        for (int q = 0; q < 4; ++q) EXPECT_EQ(r[1].values[1][4 * p + q], want) << c.name << " pixel " << p;
        seen[p % cases.size()] += ((m & RRC_MASK_HIT) != 0) == e.hit && r[1].values[0][p] == want;
    }
    int ok = 0;
    for (int s : seen) ok += s > 0;
    return format("%d / %zu cases, %zu pixels: misses store s exactly (age 1), no trace of the old history", ok, cases.size(), n);
}

TEST(ReprojectionEdges, PrevClip) {
    report("reprojection edge cases (16x16)", "PREV_CLIP: off-screen, 1e6 px, w <= 0, tiny w, NaN/Inf x/z/w/depth, just outside",
           "miss, s stored exactly, INVALID_GEOMETRY iff non-finite", run_cases(RRC_REPROJECTION_PREV_CLIP, prev_clip_cases()));
}

TEST(ReprojectionEdges, MotionDepth) {
    report("reprojection edge cases (16x16)", "MOTION_DEPTH: off-screen, 1e6 and 1e38 px, NaN/Inf motion or depth change, just outside",
           "miss, s stored exactly, INVALID_GEOMETRY iff non-finite", run_cases(RRC_REPROJECTION_MOTION_DEPTH, motion_cases()));
}

// CAMERA: a previous camera that sees every point behind it (w < 0 while
// x/w, y/w, z/w are those of the current frame) and one looking 50 images
// to the side: every pixel misses; identity again: every pixel hits.
TEST(ReprojectionEdges, CameraBehindAndAway) {
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f, RRC_HISTORY_FP32)};
    rrc_test::Context ctx(static_desc(kW, kH, channels));
    ASSERT_TRUE(ctx);
    std::vector<FrameData> frames;
    for (int t = 0; t < 4; ++t) {
        FrameData f = static_frame(kW, kH, t);
        f.samples = {std::vector<float>(kW * kH, t == 0 ? 1000.0f : 1.0f)};
        if (t == 1) f.prev_view_proj[15] = -1.0;   // w_prev = -w
        if (t == 2) f.prev_view_proj[12] = 100.0;  // x_prev = x + 100 w: 50 images away
        frames.push_back(f);
    }
    std::vector<rrc_test::FrameResult> r = run_batch(ctx.get(), ctx.desc(), frames);
    EXPECT_EQ(r[1].stats.hits, 0u);
    EXPECT_EQ(r[2].stats.hits, 0u);
    EXPECT_EQ(r[3].stats.hits, (uint64_t)kW * kH);
    EXPECT_EQ(r[1].values[0], std::vector<float>(kW * kH, 1.0f));
    EXPECT_EQ(r[2].values[0], std::vector<float>(kW * kH, 1.0f));
    EXPECT_EQ(r[3].values[0], std::vector<float>(kW * kH, 1.0f));  // the blend of 1 and 1
    report("reprojection edge cases (16x16)", "CAMERA: previous camera facing away (w < 0), looking 50 images aside",
           "every pixel a miss, s stored exactly",
           format("hits %llu and %llu of %d", (unsigned long long)r[1].stats.hits, (unsigned long long)r[2].stats.hits, kW * kH));
}

// Non-finite previous depth: frame 1 has NaN / +Inf / -Inf depth on some
// pixels (invalid geometry then); frame 2 reprojects each pixel onto its own
// centre with valid data of its own.  A pixel any of whose four bilinear taps
// (its texel and the next ones right and down, clamped; weight 0 or not) holds
// such a depth must miss, never produce a NaN.
TEST(ReprojectionEdges, NonFinitePreviousDepthTaps) {
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f, RRC_HISTORY_FP32)};
    rrc_test::Context ctx(static_desc(kW, kH, channels));
    ASSERT_TRUE(ctx);
    std::vector<FrameData> frames;
    const float non_finite[] = {kNaN, kInf, -kInf};
    for (int t = 0; t < 3; ++t) {
        FrameData f = static_frame(kW, kH, t);
        f.samples = {std::vector<float>(kW * kH, t == 0 ? 1000.0f : 1.0f)};
        if (t == 1)
            for (size_t p = 0; p < f.depth.size(); p += 5) f.depth[p] = non_finite[(p / 5) % 3];
        frames.push_back(f);
    }
    std::vector<rrc_test::FrameResult> r = run_batch(ctx.get(), ctx.desc(), frames);
    int64_t misses = 0;
    auto bad = [](int i, int j) { return ((size_t)std::min(j, kH - 1) * kW + std::min(i, kW - 1)) % 5 == 0; };
    for (size_t p = 0; p < (size_t)kW * kH; ++p) {
        const int i = p % kW, j = p / kW;
        const bool bad_tap = bad(i, j) || bad(i + 1, j) || bad(i, j + 1) || bad(i + 1, j + 1);
        EXPECT_EQ((r[2].mask[p] & RRC_MASK_HIT) != 0, !bad_tap) << "pixel " << p;
        EXPECT_EQ(r[2].mask[p] & RRC_MASK_INVALID_GEOMETRY, 0) << "pixel " << p;
        EXPECT_TRUE(std::isfinite(r[1].values[0][p]) && std::isfinite(r[2].values[0][p])) << "pixel " << p;
        if (bad_tap) EXPECT_EQ(r[2].values[0][p], 1.0f) << "pixel " << p;
        misses += bad_tap;
    }
    report("reprojection edge cases (16x16)", "previous depth NaN / +Inf / -Inf under the taps", "miss, finite values",
           format("%lld pixels, all misses with s stored", (long long)misses));
}

}  // namespace
