// rrc_vulkan_frame_desc.count_io (include/rrc/rrc_vulkan.h): a counted frame
// gives the same bits as a plain one, and what it counts is the kernel's image
// operations, exactly.  Every pixel of the frame pass makes the same loads and
// stores whatever its mask (the kernel has no early return and loads its taps
// on a miss too), and the fill adds a fixed number at each pixel it lists, so
// the counts are known from the code: docs/measurements/PERFORMANCE.md, "What a
// pixel moves", lists them term by term.
#include "interop/scene_images.h"
#include "support/rrc_test_context.h"

#include <cstring>
#include <vector>

using namespace rrc_test;

namespace {

const int W = 48, H = 32, kFrames = 5;

// The image operations of one pixel (or of one fill-listed pixel).
struct Ops {
    uint64_t loads, texels, bytes_loaded, stores, bytes_stored;
};

// A FUSED frame's pixel: one packed channel (1 component, fp16, bilinear),
// ADAPTIVE, PREV_CLIP, the host's inputs sampled, the host's mask and age images bound.
//   loads:  the depth's cross, 5 gathers of 4 R32F texels (80 B); the
//           reprojection, 1 RGBA32F (16 B); the previous depth's 4 bilinear
//           taps (16 B); the sample, 1 R32F (4 B); the history's 4 bilinear
//           taps, one R32_UINT value|age word each (16 B).
//   stores: the depth copy (4 B), the history word (4 B), the host's value
//           (R16F at the channel's precision, 2 B), its age (2 B), the mask (1 B).
constexpr Ops kFramePixel{5 + 1 + 4 + 1 + 4, 20 + 1 + 4 + 1 + 4, 80 + 16 + 16 + 4 + 16, 5, 4 + 4 + 2 + 2 + 1};
// A fill-listed pixel, radius 2: its depth and word (8 B), then the 25 taps'
// words and depths, the centre's included (200 B); its displayed value (2 B),
// which the frame pass then does not store (the fill would overwrite it).
constexpr Ops kFillPixel{2 + 50, 2 + 50, 8 + 200, 1 - 1, 2 - 2};

struct Setup {
    const char* name;
    uint32_t fill_age;  // 0: no fill
};

rrc_scene::SceneConfig test_scene() {
    rrc_scene::SceneConfig sc = scene_config(W, H, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    return sc;
}

rrc_vulkan_io_counts read_counts(const rrc_host::Buffer& stats) {
    rrc_vulkan_io_counts n;
    std::memcpy(&n, static_cast<const unsigned char*>(stats.mapped) + sizeof(rrc_vulkan_frame_stats), sizeof n);
    return n;
}

void counted_frames(const Setup& setup) {
    SCOPED_TRACE(setup.name);
    std::vector<rrc_channel_desc> channels = {rrc_host::channel("pcf", 1, 0.6f, RRC_HISTORY_FP16)};
    channels[0].fill_age = setup.fill_age;
    rrc_context_desc desc = scene_context_desc(test_scene(), RRC_REPROJECTION_PREV_CLIP, channels);
    desc.depth_test = RRC_DEPTH_TEST_ADAPTIVE;

    VulkanHost host;
    // Two contexts on the same frames: one plain, one counting.
    rrc_context* plain = interop_context(rrc_host::vulkan_device_desc(host, 1), desc);
    rrc_context* counted = interop_context(rrc_host::vulkan_device_desc(host, 1), desc);
    ASSERT_NE(plain, nullptr);
    ASSERT_NE(counted, nullptr);
    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    SceneImages in_img(host, W, H, false, false);
    struct Outputs {
        HostImage value, age, mask;
    };
    Outputs out[2];
    for (Outputs& o : out)
        o = {zeroed_output(host, VK_FORMAT_R16_SFLOAT, W, H), zeroed_output(host, VK_FORMAT_R16_UINT, W, H),
             zeroed_output(host, VK_FORMAT_R8_UINT, W, H)};
    const VkDeviceSize stats_size = 256;
    rrc_host::Buffer stats[2];
    for (rrc_host::Buffer& s : stats)
        s = host.create_buffer(stats_size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    std::memset(stats[1].mapped, 0xAB, stats_size);

    rrc_scene::Scene scene(test_scene());
    uint64_t listed_total = 0;
    for (int t = 0; t < kFrames; ++t) {
        SceneFrameInputs in;
        in.frame = scene.render(t);
        make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, {1}, {false});
        in_img.upload(host, in, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, ro);
        for (int k = 0; k < 2; ++k) {
            const rrc_vulkan_channel_images ch[1] = {in_img.channel(1, out[k].value, &out[k].age)};
            auto f = in_img.frame(in, ch, host.begin());
            f.mask = view_of(out[k].mask, VK_IMAGE_LAYOUT_GENERAL);
            f.stats_buffer = stats[k].buffer, f.stats_buffer_size = stats_size;
            f.count_io = k == 1 ? 1u : 0u;
            ASSERT_EQ(rrc_vulkan_record_frame(k == 1 ? counted : plain, &f), RRC_SUCCESS) << rrc_last_error();
            host.submit_and_wait(f.command_buffer);
        }
        // The same bits, counting or not.
        const std::vector<uint16_t> age = read_back<uint16_t>(host, out[1].age);
        const std::vector<uint8_t> mask = read_back<uint8_t>(host, out[1].mask);
        EXPECT_EQ(read_back<uint16_t>(host, out[1].value), read_back<uint16_t>(host, out[0].value)) << "frame " << t;
        EXPECT_EQ(age, read_back<uint16_t>(host, out[0].age)) << "frame " << t;
        EXPECT_EQ(mask, read_back<uint8_t>(host, out[0].mask)) << "frame " << t;
        EXPECT_EQ(std::memcmp(stats[0].mapped, stats[1].mapped, sizeof(rrc_vulkan_frame_stats)), 0) << "frame " << t;

        // The fill lists the surface pixels younger than fill_age (docs/CONVENTIONS.md, "The spatial fill").
        uint64_t listed = 0;
        for (size_t i = 0; setup.fill_age && i < mask.size(); ++i) listed += !(mask[i] & RRC_MASK_BACKGROUND) && age[i] < setup.fill_age;
        listed_total += listed;
        const uint64_t px = (uint64_t)W * H;
        const rrc_vulkan_io_counts n = read_counts(stats[1]);
        EXPECT_EQ(n.loads, kFramePixel.loads * px + kFillPixel.loads * listed) << "frame " << t << ", " << listed << " listed";
        EXPECT_EQ(n.texels_loaded, kFramePixel.texels * px + kFillPixel.texels * listed) << "frame " << t;
        EXPECT_EQ(n.bytes_loaded, kFramePixel.bytes_loaded * px + kFillPixel.bytes_loaded * listed) << "frame " << t;
        EXPECT_EQ(n.stores, kFramePixel.stores * px + kFillPixel.stores * listed) << "frame " << t;
        EXPECT_EQ(n.bytes_stored, kFramePixel.bytes_stored * px + kFillPixel.bytes_stored * listed) << "frame " << t;
        const unsigned char* bytes = static_cast<const unsigned char*>(stats[1].mapped);
        const size_t end = sizeof(rrc_vulkan_frame_stats) + sizeof(rrc_vulkan_io_counts);
        EXPECT_EQ(std::count(bytes + end, bytes + stats_size, 0xAB), (long)(stats_size - end)) << "written past the counts";
    }
    if (setup.fill_age) EXPECT_GT(listed_total, 0u) << "the fill's counts must be exercised";

    rrc_context_destroy(plain);
    rrc_context_destroy(counted);
    in_img.destroy(host);
    for (Outputs& o : out)
        for (HostImage* img : {&o.value, &o.age, &o.mask}) host.destroy(*img);
    for (rrc_host::Buffer& s : stats) static_cast<rrc_host::VulkanBootstrap&>(host).destroy(s);
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << "validation messages, first: " << host.messages().front();
}

}  // namespace

TEST(IoCounts, ACountedFrameGivesTheSameBitsAndTheKernelsOperations) { counted_frames({"frame pass only", 0}); }
TEST(IoCounts, TheFillCountsItsListedPixels) { counted_frames({"with a fill", 4}); }
