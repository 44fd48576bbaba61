// The shading cache recorded into the host's command buffer
// (rrc_vulkan_record_classify / rrc_vulkan_record_resolve): several frames
// pending in one submission, each with its own quad list and statistics,
// give what the standalone classify + resolve gives (mask, listed quads as a
// set, the indirect dispatch, values, ages, counts), under the validation
// layer with synchronization validation.  Both for a context with an
// accumulating channel (resolve runs over every pixel) and for one of REUSE
// channels only (resolve runs on the listed quads, classify writes the
// HITs), with and without rrc_vulkan_frame_desc.split_outputs; and what the
// host's mask image holds right after classify (rrc_vulkan.h: unchanged, or
// with split_outputs this frame's classification).
#include "interop/scene_images.h"
#include "support/rrc_test_context.h"

#include <set>

using namespace rrc_test;

namespace {

const int W = 48, H = 32, N = 5;
const uint32_t kListWords = RRC_QUAD_LIST_BYTES(W, H) / 4;

// reuse_only: the pcf channel is a second REUSE channel (fp32 nearest), so the whole context is a shading cache.
std::vector<rrc_channel_desc> cache_channels(bool reuse_only) {
    return {channel("shade", 4, 0.0f, RRC_HISTORY_FP16, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_BILINEAR),
            reuse_only ? channel("pcf", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST)
                       : channel("pcf", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR)};
}

rrc_scene::SceneConfig cache_scene() { return scene_config(W, H, RRC_DEPTH_MODE_REVERSED); }

rrc_context_desc cache_desc(std::vector<rrc_channel_desc>& channels) {
    rrc_context_desc d = scene_context_desc(cache_scene(), RRC_REPROJECTION_PREV_CLIP, channels);
    d.refresh_policy = RRC_REFRESH_TILED;
    d.refresh_period = 4;
    d.refresh_tiles[0] = d.refresh_tiles[1] = 2;
    d.max_lifetime = 3;
    return d;
}

struct Split {
    std::vector<uint8_t> mask;
    std::set<uint32_t> quads;
    rrc_frame_stats stats{};
    uint64_t refreshed = 0;
    std::vector<float> shade, pcf;
    std::vector<uint16_t> shade_age, pcf_age;
};

// Standalone classify of one frame: its mask.
std::vector<uint8_t> run_classify(Context& ctx, SceneFrameInputs& in) {
    std::vector<uint8_t> mask((size_t)W * H);
    rrc_classify_output co = rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT);
    co.mask = mask.data();
    EXPECT_EQ(rrc_frame_classify(ctx.get(), &in.desc, &co), RRC_SUCCESS) << rrc_last_error();
    return mask;
}

// Standalone classify + resolve of one frame, every sample given.
Split run_split(Context& ctx, SceneFrameInputs& in) {
    Split s;
    const size_t n = (size_t)W * H;
    s.mask.resize(n);
    std::vector<uint32_t> quads(kListWords);
    rrc_classify_output co = rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT);
    co.mask = s.mask.data();
    co.quads = quads.data();
    co.quad_capacity = kListWords;
    EXPECT_EQ(rrc_frame_classify(ctx.get(), &in.desc, &co), RRC_SUCCESS) << rrc_last_error();
    s.quads.insert(quads.begin(), quads.begin() + co.quad_count);
    EXPECT_EQ(s.quads.size(), co.quad_count) << "a quad listed twice";
    rrc_resolve_desc rd = rrc_host::rrc_struct<rrc_resolve_desc>(RRC_STRUCT_TYPE_RESOLVE_DESC);
    rd.channel_count = in.desc.channel_count;
    rd.channels = in.desc.channels;
    s.shade.resize(4 * n);
    s.pcf.resize(n);
    s.shade_age.resize(n);
    s.pcf_age.resize(n);
    rrc_channel_output co2[2] = {rrc_host::channel_output(), rrc_host::channel_output()};
    co2[0].values = s.shade.data();
    co2[0].age = s.shade_age.data();
    co2[1].values = s.pcf.data();
    co2[1].age = s.pcf_age.data();
    rrc_frame_output out = rrc_host::frame_output();
    out.mask = s.mask.data();
    out.channel_count = 2;
    out.channels = co2;
    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &rd, &out), RRC_SUCCESS) << rrc_last_error();
    s.stats = out.stats;
    s.refreshed = out.refreshed;
    return s;
}

void frames_in_flight_match_standalone(bool reuse_only, uint32_t split_outputs) {
    std::vector<rrc_channel_desc> channels = cache_channels(reuse_only);
    rrc_scene::Scene scene(cache_scene());
    std::vector<SceneFrameInputs> inputs(N + 1);
    std::vector<Split> expected;
    std::vector<uint8_t> classified;  // frame N's mask after its classify alone
    {
        Context ctx(cache_desc(channels));
        ASSERT_TRUE(ctx);
        for (int t = 0; t <= N; ++t) {
            inputs[t].frame = scene.render(t);
            make_frame_inputs(inputs[t], RRC_REPROJECTION_PREV_CLIP, {4, 1}, {false, false});
            inputs[t].desc.frame_index = 100 + t;
            if (t < N) expected.push_back(run_split(ctx, inputs[t]));
        }
        classified = run_classify(ctx, inputs[N]);
    }
    uint64_t refreshed = 0, hits = 0;
    for (const Split& e : expected) refreshed += e.refreshed, hits += e.stats.hits;
    ASSERT_GT(refreshed, 0u) << "the comparison must cover refreshes";
    ASSERT_GT(hits, 0u) << "the comparison must cover hits";

    VulkanHost host;
    rrc_context* ctx = interop_context(rrc_host::vulkan_device_desc(host, N), cache_desc(channels));  // N frames pending at once
    ASSERT_NE(ctx, nullptr);

    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, gen = VK_IMAGE_LAYOUT_GENERAL;
    const VkDeviceSize stats_stride = 256, list_stride = (RRC_QUAD_LIST_BYTES(W, H) + 255) / 256 * 256;
    rrc_host::Buffer stats =
        host.create_buffer(stats_stride * N, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    rrc_host::Buffer lists = host.create_buffer(
        list_stride * N, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    std::memset(stats.mapped, 0xAB, stats_stride * N);
    std::memset(lists.mapped, 0xCD, list_stride * N);
    // Channel 0 (shade) is the 4-component one, channel 1 (pcf) the 1-component.
    std::vector<FrameImages> fr;
    for (int t = 0; t <= N; ++t) {
        fr.emplace_back(host, W, H, false);
        fr.back().in.upload(host, inputs[t], ro, ro);
    }

    VkCommandBuffer cmd = host.begin();
    auto list_at = [&](int t) {
        auto list = rrc_host::rrc_struct<rrc_vulkan_quad_list>(RRC_STRUCT_TYPE_VULKAN_QUAD_LIST);
        list.buffer = lists.buffer;
        list.offset = list_stride * (t % N);
        return list;
    };
    auto frame_at = [&](int t, rrc_vulkan_channel_images(&ch)[2]) {
        const FrameImages& p = fr[t];
        ch[0] = p.channel(4);
        ch[1] = p.channel(1);
        auto f = p.in.frame(inputs[t], ch, cmd);  // frame index 100 + t, as the standalone run's
        f.mask = view_of(p.mask, gen);
        f.stats_buffer = stats.buffer;
        f.stats_offset = stats_stride * (t % N);
        f.split_outputs = split_outputs;
        return f;
    };
    for (int t = 0; t < N; ++t) {
        rrc_vulkan_channel_images ch[2];
        auto f = frame_at(t, ch);
        auto list = list_at(t);
        if (t == 0) EXPECT_EQ(rrc_vulkan_record_resolve(ctx, &f), RRC_ERROR_INVALID_ARGUMENT) << "resolve before any classify";
        ASSERT_EQ(rrc_vulkan_record_classify(ctx, &f, &list), RRC_SUCCESS) << rrc_last_error();
        auto wrong = f;
        wrong.frame_index += 1;
        EXPECT_EQ(rrc_vulkan_record_resolve(ctx, &wrong), RRC_ERROR_INVALID_ARGUMENT) << "resolve of another frame index";
        ASSERT_EQ(rrc_vulkan_record_resolve(ctx, &f), RRC_SUCCESS) << rrc_last_error();
    }
    host.submit_and_wait(cmd);  // the one wait

    for (int t = 0; t < N; ++t) {
        SCOPED_TRACE("frame " + std::to_string(t));
        FrameImages& p = fr[t];
        const Split& e = expected[t];
        const uint32_t* words = reinterpret_cast<const uint32_t*>(static_cast<const unsigned char*>(lists.mapped) + list_stride * t);
        const uint32_t count = words[RRC_QUAD_LIST_COUNT];
        EXPECT_EQ(count, e.quads.size());
        EXPECT_EQ(words[RRC_QUAD_LIST_DISPATCH], (count + RRC_QUADS_PER_GROUP - 1) / RRC_QUADS_PER_GROUP);
        EXPECT_EQ(words[RRC_QUAD_LIST_DISPATCH + 1], 1u);
        EXPECT_EQ(words[RRC_QUAD_LIST_DISPATCH + 2], 1u);
        EXPECT_EQ(std::set<uint32_t>(words + RRC_QUAD_LIST_FIRST_QUAD, words + RRC_QUAD_LIST_FIRST_QUAD + count), e.quads);
        rrc_vulkan_frame_stats s;
        std::memcpy(&s, static_cast<const unsigned char*>(stats.mapped) + stats_stride * t, sizeof s);
        EXPECT_EQ(s.hits, e.stats.hits);
        EXPECT_EQ(s.misses, e.stats.misses);
        EXPECT_EQ(s.background, e.stats.background);
        EXPECT_EQ(s.refreshed, e.refreshed);
        EXPECT_EQ(s.invalid_samples, e.stats.invalid_samples);
        EXPECT_EQ(s.invalid_geometry, e.stats.invalid_geometry);
        EXPECT_EQ(s.pixels, (uint32_t)(W * H));
        EXPECT_EQ(read_back<uint8_t>(host, p.mask), e.mask);
        EXPECT_EQ(read_back<float>(host, p.out4), e.shade);
        EXPECT_EQ(read_back<float>(host, p.out1), e.pcf);
        EXPECT_EQ(read_back<uint16_t>(host, p.age4), e.shade_age);
        EXPECT_EQ(read_back<uint16_t>(host, p.age1), e.pcf_age);
    }

    // Frame N's classify alone, into the last frame's mask image: with
    // split_outputs the host has this frame's classification, without it the
    // image still holds what the last resolve wrote (rrc_vulkan.h).
    {
        cmd = host.begin();
        rrc_vulkan_channel_images ch[2];
        auto f = frame_at(N, ch);
        f.mask = view_of(fr[N - 1].mask, gen);
        auto list = list_at(N);
        ASSERT_EQ(rrc_vulkan_record_classify(ctx, &f, &list), RRC_SUCCESS) << rrc_last_error();
        host.submit_and_wait(cmd);
        const std::vector<uint8_t> after = read_back<uint8_t>(host, fr[N - 1].mask);
        EXPECT_EQ(after, split_outputs ? classified : expected[N - 1].mask) << "the host's mask right after classify";
        EXPECT_NE(classified, expected[N - 1].mask) << "the two frames' masks must differ for this to tell";
    }
    rrc_context_destroy(ctx);
    for (FrameImages& p : fr) p.destroy(host);
    static_cast<rrc_host::VulkanBootstrap&>(host).destroy(stats);
    static_cast<rrc_host::VulkanBootstrap&>(host).destroy(lists);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << host.messages().front();
}

TEST(InteropShadingCache, FramesInFlightMatchStandaloneClassifyAndResolve) { frames_in_flight_match_standalone(false, 0); }
TEST(InteropShadingCache, SplitOutputsGiveTheSameBitsAndTheMaskAfterClassify) { frames_in_flight_match_standalone(false, 1); }
TEST(InteropShadingCache, ReuseOnlyResolveOnTheListGivesTheSameBits) { frames_in_flight_match_standalone(true, 0); }
TEST(InteropShadingCache, ReuseOnlySplitOutputsGiveTheSameBits) { frames_in_flight_match_standalone(true, 1); }

}  // namespace
