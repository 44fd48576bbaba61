// API 0.4's finishing steps on the interop path (include/rrc/rrc_vulkan.h):
// rectification and the GAUSSIAN filter read the host's sampled images, the
// spatial fill writes the host's output image (the displayed value) from the
// host's fallback image, and all of it gives the same bits as the standalone
// path, with zero validation messages (the host runs the layer with
// synchronization validation, teardown included).
#include "interop/vulkan_host.h"
#include "support/rrc_test_context.h"
#include "support/scene_frames.h"

#include <rrc/rrc_vulkan.h>

#include "rrc_interop.h"

using namespace rrc_test;

namespace {

const int W = 48, H = 32, kFrames = 6;

// A one-component fp16 channel (its history packs value and age in one word)
// with rectification, the blur and a fill without fallback; a four-component
// fp32 running mean with a fill from the host's fallback.
std::vector<rrc_channel_desc> test_channels() {
    rrc_channel_desc a = channel("pcf", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_GAUSSIAN);
    a.blur_sigma = 0.7f;
    a.rectify = 1;
    a.rectify_gamma = 2.0f;
    a.fill_age = 4;
    a.fill_radius = 1;
    rrc_channel_desc b = channel("env", 4, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, 32);
    b.fill_age = 8;
    b.fill_radius = 2;
    b.fill_prior = 4.0f;
    return {a, b};
}

rrc_context_desc test_desc(std::vector<rrc_channel_desc>& channels) {
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    return scene_context_desc(sc, RRC_REPROJECTION_PREV_CLIP, channels);
}

std::vector<float> as_floats(const std::vector<unsigned char>& bytes) {
    std::vector<float> f(bytes.size() / 4);
    std::memcpy(f.data(), bytes.data(), bytes.size());
    return f;
}

struct Inputs {
    SceneFrameInputs in;
    std::vector<float> fallback;  // channel 1's: the truth, a few pixels NaN
};

TEST(FinishingInterop, SameOutputsAsStandaloneBitForBit) {
    std::vector<rrc_channel_desc> channels = test_channels();
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    sc.invalid_fraction = 0.02;  // empty histories, filled from the neighbours
    rrc_scene::Scene scene(sc);
    std::vector<Inputs> frames(kFrames);
    std::vector<FrameResult> expected;
    {
        Context ctx(test_desc(channels));
        ASSERT_TRUE(ctx);
        for (int t = 0; t < kFrames; ++t) {
            Inputs& f = frames[t];
            f.in.frame = scene.render(t);
            make_frame_inputs(f.in, RRC_REPROJECTION_PREV_CLIP, channels);
            f.fallback = f.in.frame.truth4;
            for (size_t p = 0; p < (size_t)W * H; p += 23) f.fallback[4 * p + 2] = NAN;
            f.in.inputs[1].fallback = f.fallback.data();
            expected.push_back(ctx.run(f.in.desc));
        }
    }

    VulkanHost host;
    rrc_vulkan_device_desc dd = rrc_host::vulkan_device_desc(host, 2);
    rrc_context_desc cd = test_desc(channels);
    rrc_context* ctx = nullptr;
    ASSERT_EQ(rrc_vulkan_context_create(&cd, &dd, &ctx), RRC_SUCCESS) << rrc_last_error();

    const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT, storage = VK_IMAGE_USAGE_STORAGE_BIT;
    HostImage depth = host.create_image(VK_FORMAT_D32_SFLOAT, W, H, sampled | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    HostImage clip = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, W, H, sampled);
    HostImage s1 = host.create_image(VK_FORMAT_R32_SFLOAT, W, H, sampled);
    HostImage s4 = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, W, H, sampled);
    HostImage fb4 = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, W, H, sampled);
    HostImage out1 = host.create_image(VK_FORMAT_R32_SFLOAT, W, H, storage);
    HostImage out4 = host.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, W, H, storage);
    HostImage age4 = host.create_image(VK_FORMAT_R16_UINT, W, H, storage);
    HostImage mask = host.create_image(VK_FORMAT_R8_UINT, W, H, storage);
    std::vector<unsigned char> zeros((size_t)W * H * 16, 0);
    for (HostImage* img : {&out1, &out4, &age4, &mask})
        host.upload(*img, zeros.data(), (size_t)W * H * img->texel_bytes, VK_IMAGE_LAYOUT_GENERAL);

    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, dro = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    const VkImageLayout gen = VK_IMAGE_LAYOUT_GENERAL;
    for (int t = 0; t < kFrames; ++t) {
        const SceneFrameInputs& in = frames[t].in;
        host.upload(depth, in.frame.depth.data(), W * H * 4, dro);
        host.upload(clip, in.reprojection.data(), W * H * 16, ro);
        host.upload(s1, in.frame.signal1.data(), W * H * 4, ro);
        host.upload(s4, in.frame.signal4.data(), W * H * 16, ro);
        host.upload(fb4, frames[t].fallback.data(), W * H * 16, ro);

        rrc_vulkan_channel_images ch[2];
        for (auto& c : ch) c = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
        ch[0].samples = rrc_host::vulkan_image(s1, ro);
        ch[0].output = rrc_host::vulkan_image(out1, gen);
        ch[1].samples = rrc_host::vulkan_image(s4, ro);
        ch[1].fallback = rrc_host::vulkan_image(fb4, ro);
        ch[1].output = rrc_host::vulkan_image(out4, gen);
        ch[1].age = rrc_host::vulkan_image(age4, gen);
        auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
        f.frame_index = t;
        f.depth = rrc_host::vulkan_image(depth, dro);
        f.reprojection = rrc_host::vulkan_image(clip, ro);
        f.mask = rrc_host::vulkan_image(mask, gen);
        std::memcpy(f.jitter, in.desc.jitter, sizeof f.jitter);
        std::memcpy(f.prev_jitter, in.desc.prev_jitter, sizeof f.prev_jitter);
        f.channel_count = 2;
        f.channels = ch;
        f.command_buffer = host.begin();
        ASSERT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_SUCCESS) << rrc_last_error();
        host.submit_and_wait(f.command_buffer);

        std::vector<float> v1 = as_floats(host.download(out1, gen));
        std::vector<float> v4 = as_floats(host.download(out4, gen));
        std::vector<unsigned char> a4 = host.download(age4, gen), m = host.download(mask, gen);
        std::vector<uint16_t> ages(a4.size() / 2);
        std::memcpy(ages.data(), a4.data(), a4.size());
        // Bit for bit: the displayed values (NaN-free, so == compares bits up to signed zeros).
        EXPECT_EQ(v1, expected[t].values[0]) << "frame " << t;
        EXPECT_EQ(v4, expected[t].values[1]) << "frame " << t;
        EXPECT_EQ(ages, expected[t].age[1]) << "frame " << t;
        EXPECT_EQ(std::vector<uint8_t>(m.begin(), m.end()), expected[t].mask) << "frame " << t;
        if (t > 0) EXPECT_GT(expected[t].stats.hits, (uint64_t)W * H / 3) << "the comparison must cover hits";
    }
    // The fill was on: some young pixels show other than their history (their
    // age is below T), i.e. the comparison covered filled values.
    int64_t young = 0;
    for (uint16_t a : expected[1].age[1]) young += a < 8;
    EXPECT_GT(young, W * H / 2);
    rrc_context_destroy(ctx);
    for (HostImage* img : {&depth, &clip, &s1, &s4, &fb4, &out1, &out4, &age4, &mask}) host.destroy(*img);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << host.messages().front();
}

}  // namespace
