// rrc-sweep --bias-maps (README.md, "Bias maps"): each region's test on a
// made-up frame whose answers are known; the regions' bias² and variance
// adding up to the row's totals; and two small sweeps under the validation
// layer: with nothing moving no target changes and rrc has no bias, with the
// sample's motion the bias sits where the target changed, not on static pixels.
#include "bias_regions.h"
#include "scene.h"
#include "sweep_run.h"

#include <gtest/gtest.h>

#include <rrc/rrc.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

namespace {

using namespace rrc_sweep;

// A 24 x 16 frame: a plane (depth affine in x and y), a block at twice the depth's 1/z in x 16..19,
// the moving object at (4, 4), a young pixel at (10, 10); the world position of each pixel is its
// centre's NDC, and frame t - 1's camera saw every point half a pixel to the left (the camera moved).
struct Made {
    RegionFrame g;
    CheckpointTarget now;
    std::vector<float> position;
    std::vector<float> before;  // the previous target, 1 a pixel
    PreviousTarget prev;
};

Made made_frame() {
    Made m;
    const uint32_t W = 24, H = 16;
    m.g.width = W, m.g.height = H;
    m.g.material.assign(W * H, rrc_sample::kMatGround);
    m.g.mask.assign(W * H, RRC_MASK_HIT);
    m.g.age.assign(W * H, 30);
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            const size_t p = y * W + x;
            const float d = 0.01f + 0.0005f * x + 0.0002f * y;
            m.g.depth.push_back(x >= 16 && x < 20 ? 2.0f * d : d);
            m.position.insert(m.position.end(), {((x + 0.5f) / W) * 2.0f - 1.0f, ((y + 0.5f) / H) * 2.0f - 1.0f, 0.0f, 1.0f});
            // A ramp in x: read half a pixel to the left it is 0.01 lower.
            m.before.push_back(0.02f * x);
            m.now.pixels.push_back((uint32_t)p);
            m.now.target.push_back(0.02f * x);
        }
    m.g.material[4 * W + 4] = rrc_sample::kMatMover;
    m.g.age[10 * W + 10] = 2;
    m.now.target[12 * W + 6] += 0.3;  // its target changed (a moving shadow)
    m.now.is_static.assign(W * H, 1);
    m.prev.values = m.before.data();
    m.prev.stride = 1;
    m.prev.scored.assign(W * H, 1);
    for (int i = 0; i < 16; ++i) m.prev.view_proj[i] = (i % 5 == 0) ? 1.0 : 0.0;
    m.prev.view_proj[12] = -1.0 / W;  // half a pixel (2 / W in NDC is one) to the left
    return m;
}

std::vector<uint8_t> changes(const Made& m, float tau) {
    std::vector<uint8_t> c(m.g.material.size(), 0);
    mark_changes(c, m.now, m.prev, m.position.data(), m.g.material, m.g.width, m.g.height, tau);
    return c;
}

TEST(BiasRegions, EachTestFindsWhatItShould) {
    const Made m = made_frame();
    RegionThresholds t;
    t.object_material = rrc_sample::kMatMover;
    const RegionMap r = classify_regions(m.g, m.now, changes(m, 0.05f), t);
    ASSERT_EQ(r.region.size(), m.now.pixels.size());
    const uint32_t W = m.g.width;
    EXPECT_EQ(r.region[4 * W + 4], kRegionObject);
    EXPECT_EQ(r.region[10 * W + 10], kRegionYoung);
    EXPECT_EQ(r.region[12 * W + 6], kRegionChanged);
    // The block's sides (x 15..16 and 19..20 jump) and one pixel around them are edges; the plane is not.
    for (uint32_t x : {14u, 15u, 16u, 17u, 18u, 19u, 20u, 21u}) EXPECT_EQ(r.region[8 * W + x], kRegionEdge) << "x = " << x;
    for (uint32_t x : {2u, 8u, 12u, 13u, 22u}) EXPECT_EQ(r.region[8 * W + x], kRegionStatic) << "x = " << x;
    // Read bilinearly half a pixel away, the ramp differs by 0.01: not a change at 0.05, a change at 0.005.
    EXPECT_EQ(r.region[3 * W + 8], kRegionStatic);
    EXPECT_EQ(changes(m, 0.005f)[3 * W + 8], 1);
    EXPECT_EQ(changes(m, 0.015f)[3 * W + 8], 0);
    // At the same point (a view-independent signal seen from frame t's camera): compared without resampling,
    // and a pixel showing another surface in t - 1 is a disocclusion, not a change.
    Made same = made_frame();
    same.prev.at_same_point = true;
    same.prev.material = same.g.material;
    same.before[3 * W + 8] += 0.002f;
    same.before[5 * W + 2] += 0.5f;
    same.prev.material[5 * W + 2] = rrc_sample::kMatStone;
    const std::vector<uint8_t> c = changes(same, 1e-3f);
    EXPECT_EQ(c[3 * W + 9], 0) << "the ramp is compared with itself";
    EXPECT_EQ(c[3 * W + 8], 1) << "0.002 is above 1e-3";
    EXPECT_EQ(c[12 * W + 6], 1);
    EXPECT_EQ(c[5 * W + 2], 0) << "another surface: not a change";
    // Precedence: the moving object wins over young.
    Made m2 = made_frame();
    m2.g.age[4 * W + 4] = 1;
    const RegionMap r2 = classify_regions(m2.g, m2.now, changes(m2, 0.05f), t);
    EXPECT_EQ(r2.region[4 * W + 4], kRegionObject);
    EXPECT_TRUE(r2.bits[4 * W + 4] & (1u << kRegionYoung)) << "the raw bits keep every test it passes";
    // A miss seeds an edge around it.
    m2.g.mask[2 * W + 10] = 0;
    const RegionMap r3 = classify_regions(m2.g, m2.now, changes(m2, 0.05f), t);
    EXPECT_EQ(r3.region[3 * W + 11], kRegionEdge);
}

TEST(BiasRegions, PartsAddUpToTheRowsTotals) {
    const Made m = made_frame();
    RegionThresholds t;
    t.object_material = rrc_sample::kMatMover;
    const RegionMap r = classify_regions(m.g, m.now, changes(m, 0.05f), t);
    // Two checkpoints, 6 seeds: noise everywhere, a bias of 0.2 on the changed pixel, 0.05 on the edges.
    std::vector<CheckpointTarget> targets = {m.now, m.now};
    for (CheckpointTarget& c : targets) c.noise = 1e-5;
    Ensemble e(2);
    std::mt19937 rng(3);
    std::normal_distribution<double> n01(0.0, 1.0);
    for (size_t c = 0; c < 2; ++c)
        for (int s = 0; s < 6; ++s) {
            std::vector<float> img(m.now.pixels.size());
            for (size_t i = 0; i < img.size(); ++i) {
                const double b = r.region[i] == kRegionChanged ? 0.2 : r.region[i] == kRegionEdge ? 0.05 : 0.0;
                img[i] = (float)(m.now.target[i] + b + 0.03 * n01(rng));
            }
            e.add(c, targets[c], img.data(), 1);
        }
    const Metrics total = e.metrics(targets);
    const RegionParts parts = decompose(e, targets, {r, r});
    double bias2 = 0.0, variance = 0.0, share = 0.0;
    for (int k = 0; k < kRegionCount; ++k) bias2 += parts.bias2[k], variance += parts.variance[k], share += parts.pixel_share[k];
    EXPECT_NEAR(bias2, total.bias2, 1e-12 + 1e-9 * std::abs(total.bias2));
    EXPECT_NEAR(variance, total.variance, 1e-12 + 1e-9 * total.variance);
    EXPECT_NEAR(share, 1.0, 1e-12);
    EXPECT_EQ(parts.checkpoints, 2);
    // One changed pixel of 384 holds 0.04 / 384 of the mean; the edges (a third of the pixels) 0.0025 each.
    EXPECT_NEAR(parts.bias2[kRegionChanged], 0.04 / 384.0, 0.3 * 0.04 / 384.0);
    EXPECT_GT(parts.bias2[kRegionEdge], 5.0 * std::abs(parts.bias2[kRegionStatic]));
    // The map is signed: the changed pixel is too bright by about 0.2.
    const std::vector<float> map = bias_map(e, 0, targets[0], m.now.pixels.size());
    EXPECT_NEAR(map[12 * m.g.width + 6], 0.2, 0.05);
}

TEST(BiasRegions, AgeFollowsTheMaskAsTheSampleDoes) {
    const uint32_t W = 4, H = 1;
    // Every pixel's previous position is its own: clip (x, 0, 0, 1) at the pixel's centre.
    std::vector<float> clip;
    for (uint32_t x = 0; x < W; ++x) clip.insert(clip.end(), {((x + 0.5f) / W) * 2.0f - 1.0f, 0.0f, 0.0f, 1.0f});
    std::vector<uint8_t> mask = {RRC_MASK_HIT, RRC_MASK_HIT, 0, RRC_MASK_BACKGROUND};
    std::vector<uint16_t> age = next_age({}, mask, clip.data(), W, H, 255);  // a reset: nothing to follow
    EXPECT_EQ(age, (std::vector<uint16_t>{1, 1, 1, 0}));
    age = next_age(age, mask, clip.data(), W, H, 255);
    age = next_age(age, mask, clip.data(), W, H, 3);
    EXPECT_EQ(age, (std::vector<uint16_t>{3, 3, 1, 0}));
}

SweepOptions small_sweep(const char* motion, const std::string& out) {
    SweepOptions o;
    o.width = 96;
    o.height = 64;
    o.frames = 18;
    o.first_checkpoint = 13;
    o.checkpoint_every = 4;  // checkpoints 13 and 17
    o.seeds = 4;
    o.rrc_taps = {4};
    o.brute_taps = {4};
    o.lambdas = {0.8f};
    o.soft_caps = {16};
    o.catmull_rom = false;
    o.rotated = false;
    o.finishing = false;
    o.signals = rrc_sample::kSignalPcf;
    o.motion = motion;
    o.bias_maps = true;
    o.change_window = 8;
    o.out = out;
    o.validation = true;
    o.quiet = true;
    return o;
}

const RrcRow& age_aware_row(const SweepResult& r) {
    for (const RrcRow& row : r.rrc)
        if (row.config.channel.blend == RRC_BLEND_AGE_AWARE) return row;
    throw std::runtime_error("no age-aware row");
}

TEST(BiasMaps, NothingMovingNoTargetChangesAndNoBias) {
    const std::string out = testing::TempDir() + "rrc_bias_maps_still";
    const SweepResult r = run_sweep(small_sweep("still", out), nullptr);
    EXPECT_EQ(r.validation_messages, 0u);
    const RrcRow& row = age_aware_row(r);
    ASSERT_TRUE(row.has_regions);
    EXPECT_EQ(row.regions.raw_share[kRegionChanged], 0.0) << "nothing moves: no target changes";
    // Young pixels here are rrc's steady misses (its hit test fails there every frame; age 1): each is the
    // seed of an edge, which comes first.
    EXPECT_EQ(row.regions.pixel_share[kRegionYoung], 0.0) << "nothing moves: a young pixel missed in this very frame";
    EXPECT_LT(std::abs(row.metrics.bias2), 0.05 * row.metrics.variance) << "nothing moves: rrc has no bias";
    double bias2 = 0.0;
    for (double b : row.regions.bias2) bias2 += b;
    EXPECT_NEAR(bias2, row.metrics.bias2, 1e-12);
    EXPECT_TRUE(std::filesystem::exists(out + "/bias_maps/pcf_regions.exr"));
    EXPECT_TRUE(std::filesystem::exists(out + "/bias_maps/pcf_rrc_k4_age-aware_l0.8_bilinear.exr"));
}

TEST(BiasMaps, UnderMotionTheBiasSitsWhereTheTargetChanged) {
    const SweepResult r = run_sweep(small_sweep("all", testing::TempDir() + "rrc_bias_maps_all"), nullptr);
    EXPECT_EQ(r.validation_messages, 0u);
    const RrcRow& row = age_aware_row(r);
    ASSERT_TRUE(row.has_regions);
    const RegionParts& p = row.regions;
    EXPECT_GT(p.pixel_share[kRegionChanged], 0.0) << "the torus's shadow moves";
    EXPECT_GT(p.pixel_share[kRegionObject], 0.0);
    EXPECT_GT(row.metrics.bias2, 0.1 * row.metrics.variance) << "rrc lags under motion";
    // Per pixel, the lag behind a changed target is far above the static pixels' bias.
    EXPECT_GT(p.bias2[kRegionChanged] / p.pixel_share[kRegionChanged], 10.0 * p.bias2[kRegionStatic] / p.pixel_share[kRegionStatic]);
    // The lag detector's row (sweep_configs.cpp) is decomposed like every other: its parts add up to its bias².
    const RrcRow* cured = nullptr;
    for (const RrcRow& c : r.rrc)
        if (c.config.channel.antilag) cured = &c;
    ASSERT_NE(cured, nullptr);
    ASSERT_TRUE(cured->has_regions);
    double cured_bias2 = 0.0;
    for (double b : cured->regions.bias2) cured_bias2 += b;
    EXPECT_NEAR(cured_bias2, cured->metrics.bias2, 1e-12);
    EXPECT_GT(cured->regions.pixel_share[kRegionChanged], 0.0);
    // Brute force is unbiased in every region: its parts stay within its noise.
    ASSERT_EQ(r.brute.size(), 1u);
    EXPECT_LT(std::abs(r.brute[0].metrics.bias2), 0.05 * r.brute[0].metrics.variance);
}

}  // namespace
