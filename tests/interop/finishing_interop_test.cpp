// The 0.4 finishing steps on the interop path (include/rrc/rrc_vulkan.h):
// rectification, the Gaussian history filter and the spatial fill with a
// fallback give the same bits through the host's device and command buffers
// as through the standalone path, under the validation layer with
// synchronization validation.  The fill is a second dispatch writing the
// host's output image: the test also checks that it really changed the
// young pixels (else a fill that never ran would pass) and left the others.
// Run twice: plain, and with the residual (0.9) on pcf, whose base the
// frame's pass reads from the host's fallback image as well as the fill.
#include "interop/scene_images.h"
#include "support/rrc_test_context.h"

using namespace rrc_test;

namespace {

const int W = 48, H = 32, kFrames = 6;

// pcf: packed fp16, rectified, filled with a fallback worth 2 samples (with
// `residual`, 0.9, the fallback is its base, read by the frame's pass too);
// env: fp32 RGBA, Gaussian history with confidence, filled without fallback.
std::vector<rrc_channel_desc> test_channels(bool fill, bool residual) {
    std::vector<rrc_channel_desc> c = {channel("pcf", 1, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR),
                                       channel("env", 4, 0.7f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_GAUSSIAN, 0, 1)};
    c[0].rectify = 1;
    c[0].rectify_gamma = 1.5f;
    c[1].blur_sigma = 0.7f;
    if (fill) {
        c[0].fill_age = 4;
        c[0].fill_prior = 2.0f;
        c[1].fill_age = 3;
        c[1].fill_radius = 1;
    }
    c[0].residual = residual ? 1u : 0u;
    return c;
}

rrc_scene::SceneConfig test_scene() {
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    return sc;
}

std::vector<float> fallback_of(const rrc_scene::Frame& f) {
    std::vector<float> fb(f.signal1.size());
    for (size_t i = 0; i < fb.size(); ++i) fb[i] = 0.25f + 0.5f * (float)((i * 7) % 11) / 11.0f;
    return fb;
}

class InteropFinishing : public ::testing::TestWithParam<bool> {};

TEST_P(InteropFinishing, SameBitsAsStandaloneAndTheFillChangesOnlyYoungPixels) {
    const bool residual = GetParam();
    rrc_scene::Scene scene(test_scene());
    std::vector<SceneFrameInputs> inputs(kFrames);
    std::vector<std::vector<float>> fallbacks(kFrames);
    std::vector<FrameResult> expected, unfilled;
    {
        std::vector<rrc_channel_desc> channels = test_channels(true, residual), plain = test_channels(false, residual);
        Context ctx(scene_context_desc(test_scene(), RRC_REPROJECTION_PREV_CLIP, channels));
        Context twin(scene_context_desc(test_scene(), RRC_REPROJECTION_PREV_CLIP, plain));
        ASSERT_TRUE(ctx);
        ASSERT_TRUE(twin);
        for (int t = 0; t < kFrames; ++t) {
            inputs[t].frame = scene.render(t);
            make_frame_inputs(inputs[t], RRC_REPROJECTION_PREV_CLIP, {1, 4}, {false, true});
            fallbacks[t] = fallback_of(inputs[t].frame);
            inputs[t].inputs[0].fallback = fallbacks[t].data();  // the twin has no fill_prior: ignored unless a base
            inputs[t].desc.channels = inputs[t].inputs.data();
            expected.push_back(ctx.run(inputs[t].desc));
            unfilled.push_back(twin.run(inputs[t].desc));
        }
    }
    // The fill changed young pixels and only them; ages and the next
    // frame's history (the twin's) are the fill's business not at all.
    size_t young = 0, changed = 0;
    for (int t = 0; t < kFrames; ++t)
        for (size_t i = 0; i < (size_t)W * H; ++i) {
            EXPECT_EQ(expected[t].age[0][i], unfilled[t].age[0][i]) << "frame " << t << " pixel " << i;
            const bool is_young = expected[t].age[0][i] < 4 && !(expected[t].mask[i] & RRC_MASK_BACKGROUND);
            young += is_young ? 1 : 0;
            if (!is_young) EXPECT_EQ(expected[t].values[0][i], unfilled[t].values[0][i]) << "frame " << t << " pixel " << i;
            changed += expected[t].values[0][i] != unfilled[t].values[0][i] ? 1 : 0;
        }
    EXPECT_GT(young, (size_t)W * H / 2) << "the scene must have young pixels (frame 0 has every pixel at age <= 1)";
    EXPECT_GT(changed, young / 2) << "the fill must change most young pixels";

    VulkanHost host;
    std::vector<rrc_channel_desc> channels = test_channels(true, residual);
    rrc_context* ctx =
        interop_context(rrc_host::vulkan_device_desc(host, 2), scene_context_desc(test_scene(), RRC_REPROJECTION_PREV_CLIP, channels));
    ASSERT_NE(ctx, nullptr);
    SceneImages in_img(host, W, H, true);
    HostImage fb = host.create_image(VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_USAGE_SAMPLED_BIT);
    HostImage out1 = zeroed_output(host, VK_FORMAT_R32_SFLOAT, W, H);
    HostImage out4 = zeroed_output(host, VK_FORMAT_R32G32B32A32_SFLOAT, W, H);
    HostImage age1 = zeroed_output(host, VK_FORMAT_R16_UINT, W, H);
    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, dro = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    for (int t = 0; t < kFrames; ++t) {
        const SceneFrameInputs& in = inputs[t];
        in_img.upload(host, in, dro, ro);
        host.upload(fb, fallbacks[t].data(), W * H * 4, ro);
        rrc_vulkan_channel_images ch[2] = {in_img.channel(1, out1, &age1), in_img.channel(4, out4)};
        ch[0].fallback = view_of(fb, ro);
        auto f = in_img.frame(in, ch, host.begin());
        ASSERT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_SUCCESS) << rrc_last_error();
        host.submit_and_wait(f.command_buffer);
        EXPECT_EQ(read_back<float>(host, out1), expected[t].values[0]) << "frame " << t;
        EXPECT_EQ(read_back<float>(host, out4), expected[t].values[1]) << "frame " << t;
        EXPECT_EQ(read_back<uint16_t>(host, age1), expected[t].age[0]) << "frame " << t;
    }
    rrc_context_destroy(ctx);
    in_img.destroy(host);
    for (HostImage* img : {&fb, &out1, &out4, &age1}) host.destroy(*img);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << (host.messages().empty() ? "" : host.messages().front());
}

INSTANTIATE_TEST_SUITE_P(Residual, InteropFinishing, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "Residual" : "Plain"; });

}  // namespace
