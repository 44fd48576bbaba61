// What rrc adds to a clean input (docs/measurements/clean-input.md, "The
// library test"): a fronto-parallel plane with a fine, noise-free
// texture, each pixel its exact box average, under a camera panning 0.37
// pixels a frame (CAMERA reprojection, every pixel a hit but the columns the
// pan uncovers), accumulated with every blending preset (rrc_channel_preset;
// the residual variants' base is the texture without its finest term).  The
// ideal output is the input itself: what separates them is the history's
// resampling blur, the fill of young pixels and the clamps.
//
// Per preset it asserts
//   - the kernel's deviation from the input (RMSE over frames 8-15, in units
//     of the input's RMS contrast) equals the double-precision reference's
//     (tests/reference, run on its own chain of frames) within 1 %: the
//     deviation is the conventions' math, not the kernel's arithmetic;
//   - that deviation is within the preset's bound (kBounds), the figures
//     docs/measurements/clean-input.md states; a preset re-tuned to blur more fails here;
//   - a wrong variant (the preset at a fixed lambda of 0.98 through the Gaussian
//     filter, sigma 0.8, with no clamp or shortening)
//     exceeds the bound: the bound catches added blur.
#include "reference/rrc_reference.h"
#include "support/rrc_test_context.h"

#include <cmath>
#include <cstdio>
#include <string>

using namespace rrc_test;

namespace {

const int kW = 64, kH = 40, kFrames = 16, kFrom = 8;
const double kSpeed = 0.37;  // pixels a frame, x
const double kPi = 3.14159265358979323846;

// The average over [a, a + 1] of sin(2 pi f x + p).
double box_sin(double f, double p, double a) {
    const double w = 2.0 * kPi * f;
    return (std::cos(w * a + p) - std::cos(w * (a + 1.0) + p)) / w;
}

// The texture's exact average over pixel (i, j) with the plane shifted by
// `shift` pixels: a sum of separable sinusoids, the finest at 0.41 cycles a
// pixel along x and 0.29 along y.  `fine` = false leaves the finest term out
// (the residual variants' base: a smooth, deterministic estimate).
double texel(int i, int j, double shift, bool fine) {
    const double x = i - shift, y = j;
    double v = 0.5 + 0.2 * box_sin(0.09, 0.3, x) * box_sin(0.06, 1.1, y);
    if (fine) v += 0.12 * box_sin(0.41, 1.0, x) * box_sin(0.29, 0.4, y) + 0.08 * box_sin(0.23, 2.0, x);
    return v;
}

// A camera panned by `shift` pixels in x: identity matrices but for the NDC
// x translation; its eye 10 units behind the plane, moving with it (the view
// lobe's turn, which is small here).
void pan(double shift, double m[16], double eye[3]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    m[12] = 2.0 * shift / kW;
    eye[0] = -2.0 * shift / kW, eye[1] = 0.0, eye[2] = -10.0;
}

struct Preset {
    rrc_preset preset;
    uint32_t flags;
    const char* name;
    double bound;  // the deviation's bound, in units of the input's RMS contrast (docs/measurements/clean-input.md)
};
const Preset kPresets[] = {
    {RRC_PRESET_PCF_SHADOWS, RRC_PRESET_FLAG_BASE, "pcf base", 0.41},
    {RRC_PRESET_PCF_SHADOWS, 0, "pcf", 0.45},
    {RRC_PRESET_ENV_BUMP, RRC_PRESET_FLAG_BASE, "env base", 0.41},
    {RRC_PRESET_ENV_BUMP, 0, "env", 0.35},
    {RRC_PRESET_SOFT_SHADOWS, RRC_PRESET_FLAG_BASE, "soft base", 0.35},
    {RRC_PRESET_SOFT_SHADOWS, 0, "soft", 0.68},
    {RRC_PRESET_OFFLINE, 0, "offline", 0.39},
};

struct Deviation {
    double kernel = 0.0, reference = 0.0;  // RMSE of the displayed value against the input over frames kFrom..
};

// The preset's channel (fp32, one component), or with `blurred` the wrong variant.
rrc_channel_desc preset_channel(const Preset& p, bool blurred) {
    rrc_channel_desc c = channel("clean", 1, 0.0f, RRC_HISTORY_FP32);
    EXPECT_EQ(rrc_channel_preset(p.preset, p.flags, 0, &c), RRC_SUCCESS) << rrc_last_error();
    if (blurred) {
        c.lambda = 0.98f;
        c.blend = RRC_BLEND_FIXED;
        c.filter = RRC_HISTORY_FILTER_GAUSSIAN;
        c.blur_sigma = 0.8f;
        c.antilag = 0, c.antilag_gamma = 0.0f, c.antilag_threshold = 0.0f;
        c.rectify = 0, c.rectify_gamma = 0.0f;
        c.blur_bound = 0.0f, c.view_lobe = 0.0f;
    }
    return c;
}

Deviation deviation(const Preset& p, bool blurred, double* contrast) {
    const std::vector<rrc_channel_desc> chs = {preset_channel(p, blurred)};
    rrc_context_desc d = context_desc(kW, kH, chs);
    d.reprojection = RRC_REPROJECTION_CAMERA;
    Context ctx(d);
    EXPECT_TRUE(ctx);
    if (!ctx) return {};
    const size_t n = (size_t)kW * kH;
    std::vector<float> depth(n, 0.5f), s(n), b(n);
    double sum_k = 0.0, sum_r = 0.0, sum_v = 0.0, sum_v2 = 0.0;
    size_t count = 0;
    rrc_ref::PreviousFrame prev;
    for (int t = 0; t < kFrames; ++t) {
        const double shift = kSpeed * t, prev_shift = kSpeed * (t - 1);
        for (int j = 0; j < kH; ++j)
            for (int i = 0; i < kW; ++i) {
                s[(size_t)j * kW + i] = (float)texel(i, j, shift, true);
                b[(size_t)j * kW + i] = (float)texel(i, j, shift, false);
            }
        rrc_channel_input in = channel_input(s.data());
        in.fallback = b.data();  // the residual's base, the fill's prior
        rrc_frame_desc f = frame_desc();
        f.frame_index = (uint64_t)t;
        f.depth = depth.data();
        f.channel_count = 1;
        f.channels = &in;
        pan(shift, f.view_proj, f.camera_position);
        pan(prev_shift, f.prev_view_proj, f.prev_camera_position);
        const FrameResult k = ctx.run(f);
        const rrc_ref::FrameResult r = rrc_ref::run_frame(ctx.desc(), prev, f);
        prev = rrc_ref::as_previous(ctx.desc(), f, r);
        if (t < kFrom) continue;
        const rrc_ref::ChannelResult& rc = r.channels[0];
        for (size_t i = 0; i < n; ++i) {
            const double rv = rc.shown.empty() ? rc.out[i] : rc.shown[i];
            sum_k += (k.values[0][i] - (double)s[i]) * (k.values[0][i] - (double)s[i]);
            sum_r += (rv - (double)s[i]) * (rv - (double)s[i]);
            sum_v += s[i], sum_v2 += (double)s[i] * s[i];
            ++count;
        }
    }
    const double mean = sum_v / count;
    *contrast = std::sqrt(sum_v2 / count - mean * mean);
    return {std::sqrt(sum_k / count), std::sqrt(sum_r / count)};
}

TEST(CleanMotion, ThePresetsDeviationFromACleanMovingTextureIsBounded) {
    for (const Preset& p : kPresets) {
        SCOPED_TRACE(p.name);
        double contrast = 0.0, contrast_blurred = 0.0;
        const Deviation dv = deviation(p, false, &contrast);
        const Deviation wrong = deviation(p, true, &contrast_blurred);
        ASSERT_GT(contrast, 0.05) << "the texture must have contrast";
        const double k = dv.kernel / contrast, r = dv.reference / contrast, w = wrong.reference / contrast;
        std::printf("clean motion: %-10s kernel %.4f reference %.4f (bound %.3f); blurrier variant: %.4f\n", p.name, k, r, p.bound, w);
        EXPECT_NEAR(k, r, 0.01 * r + 1e-6) << "the kernel's deviation is not the reference's";
        EXPECT_LE(r, p.bound) << "the preset adds more than its bound to a clean input";
        EXPECT_GT(w, p.bound) << "the bound would not notice a blurrier history";
    }
}

}  // namespace
