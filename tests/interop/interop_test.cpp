// The interop path (include/rrc/rrc_vulkan.h) inside a host's own device and
// command buffers: the same frames give bit-identical outputs through the
// standalone and the interop paths, with zero validation messages (the host
// runs the layer with synchronization validation, teardown included).
#include "interop/scene_images.h"
#include "support/rrc_test_context.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <functional>

using namespace rrc_test;

namespace {

const int W = 48, H = 32, kFrames = 6;

std::vector<rrc_channel_desc> test_channels() {
    return {channel("pcf", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR),
            channel("env", 4, 0.7f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM, 0, 1)};
}

// The test's scene (jittered, REVERSED depth, near 0.1, far 100) and the
// PREV_CLIP context over it.
rrc_scene::SceneConfig test_scene() {
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    return sc;
}

rrc_context_desc test_desc(std::vector<rrc_channel_desc>& channels, bool object_id = false) {
    rrc_context_desc d = scene_context_desc(test_scene(), RRC_REPROJECTION_PREV_CLIP, channels);
    d.use_object_id = object_id ? 1u : 0u;
    return d;
}

// Two frames in flight: the test records a frame while the previous one may still be pending.
rrc_vulkan_device_desc device_desc(const VulkanHost& host) { return rrc_host::vulkan_device_desc(host, 2); }

// The test scene's first inputs.size() frames (jittered, REVERSED depth) into
// `inputs`, and the standalone path's results for them on the library's own
// device into `expected`: what the interop path must give.
void run_standalone(std::vector<SceneFrameInputs>& inputs, std::vector<FrameResult>& expected, bool object_id = false) {
    rrc_scene::Scene scene(test_scene());
    std::vector<rrc_channel_desc> channels = test_channels();
    Context ctx(test_desc(channels, object_id));
    ASSERT_TRUE(ctx);
    for (size_t t = 0; t < inputs.size(); ++t) {
        inputs[t].frame = scene.render((int)t);
        make_frame_inputs(inputs[t], RRC_REPROJECTION_PREV_CLIP, {1, 4}, {false, true});
        expected.push_back(ctx.run(inputs[t].desc));
    }
}

// With object ids on, so their path (the host's R16_UINT image, the kernel's
// copy for the next frame) is compared too.  `storage`: the host's inputs
// are storage images in the kernel's formats (rrc_vulkan_frame_desc.storage_inputs),
// read with storage loads, and must give the same bits as the sampled path.
void interop_matches_standalone(bool storage) {
    std::vector<rrc_channel_desc> channels = test_channels();
    std::vector<SceneFrameInputs> inputs(kFrames);
    std::vector<FrameResult> expected;
    ASSERT_NO_FATAL_FAILURE(run_standalone(inputs, expected, true));

    // Interop: the host's device, images and command buffers.
    VulkanHost host;
    rrc_context* ctx = interop_context(device_desc(host), test_desc(channels, true));
    ASSERT_NE(ctx, nullptr);
    uint64_t bytes = 0;
    ASSERT_EQ(rrc_get_memory_usage(ctx, &bytes), RRC_SUCCESS);
    // Ping-pong: depth 2 x 4 B, object ids 2 x 4 B, fp16 history + age 2 x (2 + 2) B,
    // fp32 rgba history + age + weight 2 x (16 + 2 + 4) B, mask 1 B.
    EXPECT_EQ(bytes, (uint64_t)W * H * (8 + 8 + 8 + 44 + 1));

    SceneImages in_img(host, W, H, true, storage);
    HostImage out1 = zeroed_output(host, VK_FORMAT_R32_SFLOAT, W, H);
    HostImage out4 = zeroed_output(host, VK_FORMAT_R32G32B32A32_SFLOAT, W, H);
    HostImage mask = zeroed_output(host, VK_FORMAT_R8_UINT, W, H);
    HostImage ids = host.create_image(VK_FORMAT_R16_UINT, W, H, VK_IMAGE_USAGE_SAMPLED_BIT);

    // The depth is handed over as a depth attachment would leave it; storage
    // inputs as a compute pass that wrote them would.
    const VkImageLayout ro = storage ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkImageLayout dro = storage ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    const VkImageLayout id_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;  // ids are sampled either way
    for (int t = 0; t < kFrames; ++t) {
        const SceneFrameInputs& in = inputs[t];
        in_img.upload(host, in, dro, ro);
        const std::vector<uint16_t> ids16(in.object_id.begin(),
                                          in.object_id.end());  // the sky's 0xFFFFFFFF is 0xFFFF here: still its own id
        host.upload(ids, ids16.data(), W * H * 2, id_layout);

        const rrc_vulkan_channel_images ch[2] = {in_img.channel(1, out1), in_img.channel(4, out4)};
        auto f = in_img.frame(in, ch, host.begin());
        f.mask = view_of(mask, VK_IMAGE_LAYOUT_GENERAL);
        f.object_id = view_of(ids, id_layout);
        ASSERT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_SUCCESS) << rrc_last_error();
        host.submit_and_wait(f.command_buffer);

        EXPECT_EQ(read_back<float>(host, out1), expected[t].values[0]) << "frame " << t;  // fp16 history: the same rounded values
        EXPECT_EQ(read_back<float>(host, out4), expected[t].values[1]) << "frame " << t;
        EXPECT_EQ(read_back<uint8_t>(host, mask), expected[t].mask) << "frame " << t;
        if (t > 0) EXPECT_GT(expected[t].stats.hits, (uint64_t)W * H / 3) << "the comparison must cover hits";
    }
    rrc_context_destroy(ctx);
    in_img.destroy(host);
    for (HostImage* img : {&out1, &out4, &mask, &ids}) host.destroy(*img);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << host.messages().front();
}

TEST(Interop, SameOutputsAsStandaloneBitForBit) { interop_matches_standalone(false); }
TEST(Interop, StorageInputsGiveTheSameBits) { interop_matches_standalone(true); }

TEST(Interop, WrongModeAndBadInputAreRefused) {
    VulkanHost host;
    std::vector<rrc_channel_desc> channels = test_channels();
    rrc_context_desc cd = test_desc(channels);
    rrc_vulkan_device_desc dd = device_desc(host);
    rrc_context* ctx = nullptr;

    rrc_vulkan_device_desc bad = dd;
    bad.device = VK_NULL_HANDLE;
    EXPECT_EQ(rrc_vulkan_context_create(&cd, &bad, &ctx), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("device.device"), std::string::npos) << rrc_last_error();
    bad = dd;
    bad.vulkan_api_version = VK_API_VERSION_1_0;
    EXPECT_EQ(rrc_vulkan_context_create(&cd, &bad, &ctx), RRC_ERROR_UNSUPPORTED);
    bad = dd;
    bad.type = RRC_STRUCT_TYPE_CONTEXT_DESC;
    EXPECT_EQ(rrc_vulkan_context_create(&cd, &bad, &ctx), RRC_ERROR_INVALID_STRUCT);
    bad = dd;
    bad.get_instance_proc_addr = nullptr;
    EXPECT_EQ(rrc_vulkan_context_create(&cd, &bad, &ctx), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(ctx, nullptr);

    // Validation asked for (the test environment's RRC_VALIDATION=1, or the
    // descriptor's) cannot apply to commands recorded into the host's device:
    // the context says so, and does not count messages it cannot see.
    std::vector<std::string> warnings;
    cd.enable_validation = 1;
    cd.log = [](void* user, rrc_log_level level, const char* message) {
        if (level == RRC_LOG_WARNING) static_cast<std::vector<std::string>*>(user)->push_back(message);
    };
    cd.log_user = &warnings;
    ASSERT_EQ(rrc_vulkan_context_create(&cd, &dd, &ctx), RRC_SUCCESS) << rrc_last_error();
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("in the host's own instance"), std::string::npos) << warnings[0];
    uint64_t count = 7;
    EXPECT_EQ(rrc_context_validation_messages(ctx, &count), RRC_ERROR_UNSUPPORTED);
    EXPECT_EQ(count, 7u) << "nothing written";
    rrc_frame_desc core = frame_desc();
    EXPECT_EQ(rrc_frame_run(ctx, &core, nullptr), RRC_ERROR_MISSING_INPUT);  // validated first...
    std::vector<float> depth(W * H, 0.5f), clip(W * H * 4, 0.0f), s(W * H * 4, 0.0f);
    std::vector<rrc_channel_input> inputs = {channel_input(s.data()), channel_input(s.data(), s.data())};
    core.depth = depth.data();
    core.reprojection = clip.data();
    core.channel_count = 2;
    core.channels = inputs.data();
    EXPECT_EQ(rrc_frame_run(ctx, &core, nullptr), RRC_ERROR_UNSUPPORTED);  // ...then refused: not standalone
    EXPECT_NE(std::string(rrc_last_error()).find("rrc_vulkan_record_frame"), std::string::npos);

    auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
    EXPECT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("command_buffer"), std::string::npos);
    f.command_buffer = host.begin();
    EXPECT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_ERROR_MISSING_INPUT);
    EXPECT_NE(std::string(rrc_last_error()).find("frame.depth"), std::string::npos);
    EXPECT_EQ(rrc_vulkan_record_frame(ctx, nullptr), RRC_ERROR_INVALID_ARGUMENT);
    host.submit_and_wait(f.command_buffer);  // nothing was recorded into it
    rrc_context_destroy(ctx);

    Context standalone(cd);
    ASSERT_TRUE(standalone);
    EXPECT_EQ(rrc_vulkan_record_frame(standalone.get(), &f), RRC_ERROR_UNSUPPORTED);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << host.messages().front();
}

// The mistakes a host can make that rrc can see (docs/guide/integration.md, "What
// rrc checks and what it cannot"), one at a time between two clean frames:
// each is refused with a message naming the member, records nothing (the
// host's outputs and mask read back as before, the statistics bytes keep
// their sentinel), and the next clean frame equals the standalone run that
// never saw a mistake, bit for bit.
TEST(Interop, MistakesAreRefusedWithNothingWrittenAndTheContextIntact) {
    std::vector<rrc_channel_desc> channels = test_channels();
    std::vector<SceneFrameInputs> inputs(2);
    std::vector<FrameResult> expected;
    ASSERT_NO_FATAL_FAILURE(run_standalone(inputs, expected));

    VulkanHost host;
    rrc_context* ctx = interop_context(device_desc(host), test_desc(channels));
    ASSERT_NE(ctx, nullptr);
    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    SceneImages in_img(host, W, H, true, false);
    HostImage out1 = zeroed_output(host, VK_FORMAT_R32_SFLOAT, W, H);
    HostImage out4 = zeroed_output(host, VK_FORMAT_R32G32B32A32_SFLOAT, W, H);
    HostImage mask = zeroed_output(host, VK_FORMAT_R8_UINT, W, H);
    const VkDeviceSize stats_size = 256;
    rrc_host::Buffer stats = host.create_buffer(stats_size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    const VkDeviceSize list_bytes = RRC_QUAD_LIST_BYTES(W, H);
    rrc_host::Buffer quads = host.create_buffer(list_bytes,
                                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                true);
    auto check_frame = [&](int t) {
        EXPECT_EQ(read_back<float>(host, out1), expected[t].values[0]) << "frame " << t;
        EXPECT_EQ(read_back<float>(host, out4), expected[t].values[1]) << "frame " << t;
        EXPECT_EQ(read_back<uint8_t>(host, mask), expected[t].mask) << "frame " << t;
    };
    {
        in_img.upload(host, inputs[0], ro, ro);  // first: the images' views carry the layout it leaves
        VkCommandBuffer cmd = host.begin();
        rrc_vulkan_channel_images ch[2] = {in_img.channel(1, out1), in_img.channel(4, out4)};
        auto f = in_img.frame(inputs[0], ch, cmd);
        f.mask = view_of(mask, VK_IMAGE_LAYOUT_GENERAL);
        ASSERT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_SUCCESS) << rrc_last_error();
        host.submit_and_wait(cmd);
        check_frame(0);
    }
    const std::vector<float> before1 = read_back<float>(host, out1), before4 = read_back<float>(host, out4);
    const std::vector<uint8_t> before_mask = read_back<uint8_t>(host, mask);
    std::memset(stats.mapped, 0xAB, stats_size);

    // The host's stated extents (rrc_vulkan_image_extents on frame.next): every image the frame binds.
    std::vector<rrc_vulkan_image_extent> table;
    auto ext = rrc_host::rrc_struct<rrc_vulkan_image_extents>(RRC_STRUCT_TYPE_EXT_VULKAN_IMAGE_EXTENTS);
    auto state_extents = [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images* ch, uint32_t w, uint32_t h) {
        table.clear();
        for (const rrc_vulkan_image* img : {&f.depth, &f.reprojection, &f.nocache, &f.mask, &f.object_id})
            if (img->image) table.push_back({img->image, w, h});
        for (int c = 0; c < 2; ++c)
            for (const rrc_vulkan_image* img : {&ch[c].samples, &ch[c].confidence, &ch[c].output, &ch[c].age, &ch[c].fallback})
                if (img->image) table.push_back({img->image, w, h});
        ext.count = (uint32_t)table.size(), ext.images = table.data();
        f.next = &ext;
    };
    const rrc_struct_header unknown{0x525243FFu, nullptr, sizeof(rrc_struct_header)};

    struct Mistake {
        const char* name;
        rrc_result code;
        const char* message;  // what the message must name
        std::function<void(rrc_vulkan_frame_desc&, rrc_vulkan_channel_images*)> make;
        bool classify = false;
        VkDeviceSize list_size = 0;
    };
    const std::vector<Mistake> mistakes = {
        {"stats past its buffer", RRC_ERROR_SIZE_MISMATCH, "frame.stats_buffer_size",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) {
             f.stats_buffer = stats.buffer, f.stats_offset = stats_size, f.stats_buffer_size = stats_size;
         }},
        {"I/O counts past the buffer", RRC_ERROR_SIZE_MISMATCH, "rrc_vulkan_frame_stats and rrc_vulkan_io_counts",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) {
             // Room for the statistics, not for the counts after them.
             f.stats_buffer = stats.buffer, f.stats_offset = 0, f.stats_buffer_size = sizeof(rrc_vulkan_frame_stats), f.count_io = 1;
         }},
        {"I/O counts without a statistics buffer", RRC_ERROR_INVALID_ARGUMENT, "frame.count_io",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) { f.count_io = 1; }},
        {"an output that is an input", RRC_ERROR_INVALID_ARGUMENT, "frame.channels[0].output.image is frame.channels[0].samples.image",
         [&](rrc_vulkan_frame_desc&, rrc_vulkan_channel_images* ch) { ch[0].output = ch[0].samples; }},
        {"two outputs in one image", RRC_ERROR_INVALID_ARGUMENT, "two outputs in one image",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) {
             f.mask = view_of(out1, VK_IMAGE_LAYOUT_GENERAL);
             f.mask.format = VK_FORMAT_R8_UINT;  // as declared: only the image is channel 0's output
         }},
        {"an integer output", RRC_ERROR_INVALID_ARGUMENT, "frame.channels[0].output.format is R8Uint",
         [&](rrc_vulkan_frame_desc&, rrc_vulkan_channel_images* ch) { ch[0].output.format = VK_FORMAT_R8_UINT; }},
        {"an undefined depth format", RRC_ERROR_INVALID_ARGUMENT, "frame.depth.format is Undefined",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) { f.depth.format = VK_FORMAT_UNDEFINED; }},
        {"an integer depth format", RRC_ERROR_INVALID_ARGUMENT, "frame.depth.format is R32Uint",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) { f.depth.format = VK_FORMAT_R32_UINT; }},
        {"a mask not R8_UINT", RRC_ERROR_INVALID_ARGUMENT, "frame.mask.format",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) { f.mask.format = VK_FORMAT_R32_UINT; }},
        {"a garbage size", RRC_ERROR_INVALID_STRUCT, "RRC_MAX_STRUCT_SIZE",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) { f.size = 0x7FFFFFFFu; }},
        {"a garbage channel size", RRC_ERROR_INVALID_STRUCT, "RRC_MAX_STRUCT_SIZE",
         [&](rrc_vulkan_frame_desc&, rrc_vulkan_channel_images* ch) { ch[0].size = 0x7FFFFFFFu; }},
        {"a quad list past its buffer", RRC_ERROR_SIZE_MISMATCH, "list.buffer_size",
         [&](rrc_vulkan_frame_desc&, rrc_vulkan_channel_images*) {}, true, list_bytes - 4},
        {"images larger than the context", RRC_ERROR_SIZE_MISMATCH, "is 96x64 (rrc_vulkan_image_extents), the context is 48x32",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images* ch) { state_extents(f, ch, 2 * W, 2 * H); }},
        {"a reprojection image smaller than the frame", RRC_ERROR_SIZE_MISMATCH, "frame.reprojection.image is 24x16",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images* ch) {
             state_extents(f, ch, W, H);
             for (auto& e : table)
                 if (e.image == f.reprojection.image) e.width = W / 2, e.height = H / 2;
         }},
        {"an image the extents leave out", RRC_ERROR_INVALID_ARGUMENT, "frame.channels[1].output.image is not listed",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images* ch) {
             state_extents(f, ch, W, H);
             ext.count = (uint32_t)(std::remove_if(table.begin(), table.end(), [&](const rrc_vulkan_image_extent& e) {
                                        return e.image == ch[1].output.image;
                                    }) - table.begin());
         }},
        {"the same image with two extents", RRC_ERROR_INVALID_ARGUMENT, "listed twice",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images* ch) {
             state_extents(f, ch, W, H);
             table.push_back({f.depth.image, W + 1, H});
             ext.count = (uint32_t)table.size(), ext.images = table.data();
         }},
        {"an extension this library does not know", RRC_ERROR_UNSUPPORTED, "does not know",
         [&](rrc_vulkan_frame_desc& f, rrc_vulkan_channel_images*) { f.next = &unknown; }},
    };
    for (const Mistake& m : mistakes) {
        SCOPED_TRACE(m.name);
        VkCommandBuffer cmd = host.begin();
        rrc_vulkan_channel_images ch[2] = {in_img.channel(1, out1), in_img.channel(4, out4)};
        auto f = in_img.frame(inputs[1], ch, cmd);
        f.mask = view_of(mask, VK_IMAGE_LAYOUT_GENERAL);
        m.make(f, ch);
        rrc_result r;
        if (m.classify) {
            auto list = rrc_host::rrc_struct<rrc_vulkan_quad_list>(RRC_STRUCT_TYPE_VULKAN_QUAD_LIST);
            list.buffer = quads.buffer;
            list.buffer_size = m.list_size;
            r = rrc_vulkan_record_classify(ctx, &f, &list);
        } else {
            r = rrc_vulkan_record_frame(ctx, &f);
        }
        EXPECT_EQ(r, m.code) << rrc_last_error();
        EXPECT_NE(std::string(rrc_last_error()).find(m.message), std::string::npos) << rrc_last_error();
        host.submit_and_wait(cmd);  // nothing was recorded into it
        EXPECT_EQ(read_back<float>(host, out1), before1);
        EXPECT_EQ(read_back<float>(host, out4), before4);
        EXPECT_EQ(read_back<uint8_t>(host, mask), before_mask);
        const unsigned char* bytes = static_cast<const unsigned char*>(stats.mapped);
        EXPECT_EQ(std::count(bytes, bytes + stats_size, 0xAB), (long)stats_size) << "the statistics buffer was written";
    }
    {
        // The context as if it had never seen them.
        in_img.upload(host, inputs[1], ro, ro);
        VkCommandBuffer cmd = host.begin();
        rrc_vulkan_channel_images ch[2] = {in_img.channel(1, out1), in_img.channel(4, out4)};
        auto f = in_img.frame(inputs[1], ch, cmd);
        f.mask = view_of(mask, VK_IMAGE_LAYOUT_GENERAL);
        f.stats_buffer = stats.buffer, f.stats_offset = 0, f.stats_buffer_size = stats_size;  // in range: accepted
        state_extents(f, ch, W, H);                                                             // stated and right: accepted
        ASSERT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_SUCCESS) << rrc_last_error();
        host.submit_and_wait(cmd);
        check_frame(1);
        rrc_vulkan_frame_stats s;
        std::memcpy(&s, stats.mapped, sizeof s);
        EXPECT_EQ(s.hits, expected[1].stats.hits);
        const unsigned char* bytes = static_cast<const unsigned char*>(stats.mapped);
        EXPECT_EQ(std::count(bytes + sizeof s, bytes + stats_size, 0xAB), (long)(stats_size - sizeof s)) << "written past the counters";
    }
    rrc_context_destroy(ctx);
    in_img.destroy(host);
    for (HostImage* img : {&out1, &out4, &mask}) host.destroy(*img);
    static_cast<rrc_host::VulkanBootstrap&>(host).destroy(stats);
    static_cast<rrc_host::VulkanBootstrap&>(host).destroy(quads);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << host.messages().front();
}

// What rrc needs of the device, queried (the host under test enabled exactly
// that: vulkan_host.cpp), and a host's declared features checked at creation.
TEST(Interop, RequirementsAreQueriedAndDeclaredFeaturesChecked) {
    auto req = rrc_host::rrc_struct<rrc_vulkan_requirements>(RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS);
    ASSERT_EQ(rrc_vulkan_get_requirements(&req), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(req.api_version, (uint32_t)VK_API_VERSION_1_1);
    EXPECT_EQ(req.features.shaderStorageImageWriteWithoutFormat, (VkBool32)VK_TRUE);
    EXPECT_EQ(req.features.robustBufferAccess, (VkBool32)VK_FALSE);
    EXPECT_EQ(req.device_extension_count, 0u);
    EXPECT_EQ(req.max_per_stage_storage_images, 64u);
    EXPECT_STREQ(req.optional_instance_extension, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    auto wrong = req;
    wrong.type = RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC;
    EXPECT_EQ(rrc_vulkan_get_requirements(&wrong), RRC_ERROR_INVALID_STRUCT);

    VulkanHost host;
    std::vector<rrc_channel_desc> channels = test_channels();
    rrc_vulkan_device_desc d = device_desc(host);
    EXPECT_EQ(host.enabled_features.shaderStorageImageWriteWithoutFormat, (VkBool32)VK_TRUE);
    const VkPhysicalDeviceFeatures none{};
    d.enabled_features = &none;  // a host that says it enabled nothing
    const rrc_context_desc desc = test_desc(channels);
    rrc_context* ctx = nullptr;
    EXPECT_EQ(rrc_vulkan_context_create(&desc, &d, &ctx), RRC_ERROR_UNSUPPORTED);
    EXPECT_NE(std::string(rrc_last_error()).find("shaderStorageImageWriteWithoutFormat"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(ctx, nullptr);
    d.enabled_features = &host.enabled_features;
    ASSERT_EQ(rrc_vulkan_context_create(&desc, &d, &ctx), RRC_SUCCESS) << rrc_last_error();
    rrc_context_destroy(ctx);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u);
}

// The standalone path's share of the same rule: a garbage size is refused
// before anything past the struct is read, and the context keeps working.
TEST(Standalone, AGarbageSizeIsRefusedBeforeItIsRead) {
    std::vector<SceneFrameInputs> inputs(1);
    std::vector<FrameResult> expected;
    ASSERT_NO_FATAL_FAILURE(run_standalone(inputs, expected));
    std::vector<rrc_channel_desc> channels = test_channels();
    Context ctx(test_desc(channels));
    ASSERT_TRUE(ctx);
    rrc_frame_desc bad = inputs[0].desc;
    bad.size = 0x7FFFFFFFu;
    EXPECT_EQ(rrc_frame_run(ctx.get(), &bad, nullptr), RRC_ERROR_INVALID_STRUCT);
    EXPECT_NE(std::string(rrc_last_error()).find("RRC_MAX_STRUCT_SIZE"), std::string::npos) << rrc_last_error();
    const FrameResult r = ctx.run(inputs[0].desc);
    EXPECT_EQ(r.values[0], expected[0].values[0]);
    EXPECT_EQ(r.mask, expected[0].mask);
}

}  // namespace

// N frames recorded into one command buffer before one wait: each frame
// names its own output, age images and statistics offset, and after the one
// fence every frame's results read back one by one equal the standalone
// path's frame by frame (values, mask, age, every counter).
TEST(Interop, FramesInFlightGiveEachFramesStatisticsAndAges) {
    const int N = 4;
    std::vector<rrc_channel_desc> channels = test_channels();
    std::vector<SceneFrameInputs> inputs(N);
    std::vector<FrameResult> expected;
    ASSERT_NO_FATAL_FAILURE(run_standalone(inputs, expected));

    VulkanHost host;
    rrc_context* ctx = interop_context(rrc_host::vulkan_device_desc(host, N), test_desc(channels));  // N frames pending at once
    ASSERT_NE(ctx, nullptr);

    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDeviceSize stride = 256;  // a multiple of every device's minStorageBufferOffsetAlignment
    rrc_host::Buffer stats = host.create_buffer(stride * N, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    std::memset(stats.mapped, 0xAB, stride * N);
    std::vector<FrameImages> fr;
    for (int t = 0; t < N; ++t) {
        fr.emplace_back(host, W, H, true);
        fr.back().in.upload(host, inputs[t], ro, ro);
    }

    VkCommandBuffer cmd = host.begin();
    for (int t = 0; t < N; ++t) {
        const FrameImages& p = fr[t];
        const rrc_vulkan_channel_images ch[2] = {p.channel(1), p.channel(4)};
        auto f = p.in.frame(inputs[t], ch, cmd);
        f.mask = view_of(p.mask, VK_IMAGE_LAYOUT_GENERAL);
        f.stats_buffer = stats.buffer;
        f.stats_offset = stride * t;
        ASSERT_EQ(rrc_vulkan_record_frame(ctx, &f), RRC_SUCCESS) << rrc_last_error();
    }
    host.submit_and_wait(cmd);  // the one wait

    for (int t = 0; t < N; ++t) {
        FrameImages& p = fr[t];
        rrc_vulkan_frame_stats s;
        std::memcpy(&s, static_cast<const unsigned char*>(stats.mapped) + stride * t, sizeof s);
        const rrc_frame_stats& e = expected[t].stats;
        EXPECT_EQ(s.hits, e.hits) << "frame " << t;
        EXPECT_EQ(s.misses, e.misses) << "frame " << t;
        EXPECT_EQ(s.background, e.background) << "frame " << t;
        EXPECT_EQ(s.invalid_samples, e.invalid_samples) << "frame " << t;
        EXPECT_EQ(s.invalid_geometry, e.invalid_geometry) << "frame " << t;
        EXPECT_EQ(s.refreshed, 0u) << "frame " << t;
        EXPECT_EQ(s.pixels, (uint32_t)(W * H)) << "frame " << t;
        EXPECT_EQ(s.reserved, 0u) << "frame " << t;
        if (t > 0) EXPECT_GT(s.hits, (uint32_t)(W * H / 3)) << "the comparison must cover hits";
        EXPECT_EQ(read_back<float>(host, p.out1), expected[t].values[0]) << "frame " << t;
        EXPECT_EQ(read_back<float>(host, p.out4), expected[t].values[1]) << "frame " << t;
        EXPECT_EQ(read_back<uint8_t>(host, p.mask), expected[t].mask) << "frame " << t;
        EXPECT_EQ(read_back<uint16_t>(host, p.age1), expected[t].age[0]) << "frame " << t << " channel 0";
        EXPECT_EQ(read_back<uint16_t>(host, p.age4), expected[t].age[1]) << "frame " << t << " channel 1";
    }
    rrc_context_destroy(ctx);
    for (FrameImages& p : fr) p.destroy(host);
    static_cast<rrc_host::VulkanBootstrap&>(host).destroy(stats);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << host.messages().front();
}
