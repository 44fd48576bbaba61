// Self-tests of the false-hit evaluator: it must flag histories that belong to
// another surface and accept correct ones.
#include <gtest/gtest.h>

#include "scenes/false_hits.h"
#include "scenes/scene.h"
#include "scenes/selftest_util.h"

using namespace rrc_scene;
using namespace rrc_scene_test;

namespace {

// Marks every pixel HIT (background included when asked).
std::vector<uint8_t> all_hits(const Frame& f, bool include_background) {
    std::vector<uint8_t> m(f.object_id.size());
    for (size_t k = 0; k < m.size(); ++k) m[k] = (f.object_id[k] >= 0 || include_background) ? RRC_MASK_HIT : RRC_MASK_BACKGROUND;
    return m;
}

}  // namespace

TEST(FalseHits, StaticSceneHasNoFalseHitsButHasContacts) {
    for (bool jitter : {false, true}) {
        const SceneConfig c = static_config(jitter);
        Scene s(c);
        const Frame f = s.render(3);
        const std::vector<uint8_t> mask = all_hits(f, false);
        const FalseHitReport r = count_false_hits(s, 3, mask.data());
        long visible = 0;
        for (int32_t id : f.object_id) visible += id >= 0;
        EXPECT_EQ(r.marked_hits, visible);
        EXPECT_EQ(r.false_hits, 0);
        if (!jitter) {
            EXPECT_EQ(r.strict_false_hits, 0);  // each texel reads exactly itself
        }
        // With jitter the taps straddle texels: only silhouettes may mix in another object.
        EXPECT_LT(r.strict_false_hits, r.hits_checked / 10);
        EXPECT_GT(r.excluded_contact, 0);  // resting sphere and boxes on the ground
        EXPECT_EQ(r.hits_checked + r.excluded_contact, r.marked_hits);
    }
}

TEST(FalseHits, BackgroundMarkedHitIsFalse) {
    SceneConfig c;
    Scene s(c);
    const Frame f = s.render(2);
    const FalseHitReport with_bg = count_false_hits(s, 2, all_hits(f, true).data());
    const FalseHitReport without = count_false_hits(s, 2, all_hits(f, false).data());
    long bg = 0;
    for (int32_t id : f.object_id) bg += id < 0;
    ASSERT_GT(bg, 0);
    EXPECT_EQ(with_bg.false_hits - without.false_hits, bg);
}

TEST(FalseHits, DisocclusionBehindMovingSphereIsFalseHit) {
    // Static camera without jitter: for static surfaces the previous frame's
    // ray through P is the pixel's own ray, so a pixel whose previous sample
    // was the moving sphere and whose current one is not was occluded then.
    Scene s(disocclusion_config());
    const int t = 2;
    const Frame f = s.render(t);
    const std::vector<int32_t> prev_ids = s.object_ids(t - 1);
    const FalseHitReport r = count_false_hits(s, t, all_hits(f, false).data());
    int disoccluded = 0, flagged = 0;
    for (size_t k = 0; k < f.object_id.size(); ++k) {
        if (f.object_id[k] < 0 || f.object_id[k] == OBJECT_SPHERE_MOVING) continue;
        if (prev_ids[k] != OBJECT_SPHERE_MOVING) continue;
        ++disoccluded;
        EXPECT_TRUE(r.verdict[k] == VERDICT_FALSE_HIT || r.verdict[k] == VERDICT_CONTACT) << "pixel " << k;
        flagged += r.verdict[k] == VERDICT_FALSE_HIT;
    }
    EXPECT_GT(disoccluded, 10);
    EXPECT_GT(flagged, 10);
    EXPECT_GE(r.false_hits, flagged);
}

TEST(FalseHits, EpsilonTestMaskIsMostlyCorrect) {
    // A tight epsilon test on the scene's own data must hit most visible
    // pixels and almost never hit falsely; an absurd epsilon hits falsely.
    for (bool jitter : {false, true}) {
        Scene s(fast_sphere_config(jitter));
        const int t = 2;
        const Frame prev = s.render(t - 1), cur = s.render(t);
        long visible = 0;
        for (int32_t id : cur.object_id) visible += id >= 0;

        const std::vector<uint8_t> tight = epsilon_test_mask(cur, prev, 1e-5);
        const FalseHitReport r = count_false_hits(s, t, tight.data());
        EXPECT_GT(r.marked_hits, visible / 2);
        EXPECT_LT(r.false_hit_ratio(), 0.01);
        EXPECT_LT(r.strict_false_hit_ratio(), 0.02);

        const std::vector<uint8_t> loose = epsilon_test_mask(cur, prev, 1.0);
        const FalseHitReport bad = count_false_hits(s, t, loose.data());
        std::printf(
            "jitter %d visible %ld: tight marked %ld checked %ld false %ld strict %ld contact %ld; "
            "loose marked %ld false %ld strict %ld\n",
            int(jitter), visible, long(r.marked_hits), long(r.hits_checked), long(r.false_hits), long(r.strict_false_hits),
            long(r.excluded_contact), long(bad.marked_hits), long(bad.false_hits), long(bad.strict_false_hits));
        EXPECT_GT(bad.false_hits, 10);
        EXPECT_GE(bad.strict_false_hits, bad.false_hits);
    }
}

TEST(FalseHits, SelfOcclusionIsFalseHit) {
    // Across a long skip the camera turns by ~1.5 rad: faces seen now were
    // back faces then.  Such a pixel's previous ray meets the SAME object at
    // another point, which only the distance part of the rule catches.
    Scene s(SceneConfig{});
    const int t = 150, prev = 0;
    const Frame f = s.render(t, prev);
    const FalseHitReport r = count_false_hits(s, t, prev, all_hits(f, false).data());
    int self = 0;
    for (int j = 0; j < f.height; ++j) {
        for (int i = 0; i < f.width; ++i) {
            const size_t k = size_t(j) * f.width + i;
            const int32_t o = f.object_id[k];
            if (o < 0 || r.verdict[k] != VERDICT_FALSE_HIT) continue;
            const float* cp = &f.prev_clip[4 * k];
            if (!(cp[3] > 0.0f)) continue;
            const glm::dvec2 uv = clip_uv(cp);
            if (uv.x < 0 || uv.x > 1 || uv.y < 0 || uv.y > 1) continue;
            self += s.cast(prev, uv.x * f.width, uv.y * f.height).object_id == o;
        }
    }
    EXPECT_GT(self, 10);
}

TEST(FalseHits, CountMissedAndIgnoresOtherBits) {
    Scene s(SceneConfig{});
    const Frame f = s.render(4);
    std::vector<uint8_t> none(f.object_id.size(), RRC_MASK_REFRESHED | RRC_MASK_INVALID_SAMPLE);
    FalseHitOptions o;
    const FalseHitReport r0 = count_false_hits(s, 4, none.data(), o);
    EXPECT_EQ(r0.marked_hits, 0);
    EXPECT_EQ(r0.false_hits, 0);
    o.count_missed = true;
    const FalseHitReport r1 = count_false_hits(s, 4, none.data(), o);
    const FalseHitReport all = count_false_hits(s, 4, all_hits(f, false).data());
    long true_hits = 0;
    for (uint8_t v : all.verdict) true_hits += v == VERDICT_TRUE_HIT;
    EXPECT_EQ(r1.missed_visible, true_hits);
    EXPECT_GT(true_hits, long(f.object_id.size()) / 2);
}
