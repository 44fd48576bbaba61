// Bad input at every entry point of the C API (docs/measurements/STABILITY.md, "Bad input"), beyond the
// descriptor cases of tests/api/api_validation_test.cpp: each case is a test that
// checks the specific code, a message naming the field, outputs left exactly
// as they were, and the context's history intact (the next good frame hits
// everywhere with the age one higher, so no frame of a refused call ran).
// Leaks are LeakSanitizer's job (the sanitizer build runs this file).
//
// Frame-level cases run twice: through rrc_frame_run, and through
// rrc_frame_run_batch as frames[1] of three (the message must then say
// "frames[1]: ...", and frames[0] must not have run either).  Every case with
// a Vulkan-path equivalent runs a third time through rrc_vulkan_record_frame
// on a context of rrc_vulkan_context_create inside a host device
// (tests/abi/vulkan_path.h): the same code and field, nothing recorded (the
// library's vkCmd* calls are counted through the device description's
// get_*_proc_addr), the host's output images untouched once the command
// buffer has run, and history intact (the next good frame continues the
// lambda recursion with the age one higher).  The host's validation layer
// must report nothing.
#include "abi/vulkan_path.h"
#include "stability_report.h"
#include "stability_util.h"

#include <cmath>
#include <functional>
#include <limits>
#include <memory>

using namespace rrc_test;

namespace {

constexpr uint32_t kW = 16, kH = 8, kN = kW * kH;
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// A frame output that writes only `mask`.
rrc_frame_output mask_output(std::vector<uint8_t>& mask) {
    rrc_frame_output o = rrc_host::frame_output();
    o.mask = mask.data();
    return o;
}

// A static one-channel frame of w x h (rrc_stab::static_frame, samples 1)
// and its descriptor.
struct StaticFrame {
    rrc_stab::FrameData data;
    std::vector<rrc_channel_input> inputs;
    rrc_frame_desc desc;
    StaticFrame(uint32_t w, uint32_t h) : data(rrc_stab::static_frame(w, h, 0)) {
        data.samples = {std::vector<float>((size_t)w * h, 1.0f)};
        desc = rrc_stab::frame_desc_of(data, 1, inputs);
    }
    StaticFrame(const StaticFrame&) = delete;
};

// A static_desc context of one 1-component channel, for the cases that need
// their own context.
const std::vector<rrc_channel_desc> kOneChannel = {channel("s", 1, 0.5f)};
rrc_context_desc one_channel_desc(uint32_t w, uint32_t h) { return rrc_stab::static_desc(w, h, kOneChannel); }

// What create must leave in its output on failure.
rrc_context* const kSentinelContext = reinterpret_cast<rrc_context*>(0x1234);

// The largest valid extent with the widest inputs (both channels RGBA32F,
// one with confidence, PREV_CLIP): far more than a device can allocate.
const std::vector<rrc_channel_desc> kWidestChannels = {
    channel("a", 4, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1), channel("b", 4, 0.5f, RRC_HISTORY_FP32)};
rrc_context_desc largest_extent_desc() {
    rrc_context_desc d = context_desc(RRC_MAX_EXTENT, RRC_MAX_EXTENT, kWidestChannels);
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    return d;
}

// rrc_vulkan_record_frame and the queries refuse `ctx` as a handle and write
// nothing; `message`, where not NULL, is in the Vulkan call's error.
void expect_vulkan_and_queries_refuse_handle(rrc_context* ctx, const char* message) {
    rrc_vulkan_frame_desc vf = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
    EXPECT_EQ(rrc_vulkan_record_frame(ctx, &vf), RRC_ERROR_INVALID_HANDLE);
    if (message) EXPECT_NE(std::string(rrc_last_error()).find(message), std::string::npos) << rrc_last_error();
    char name[64] = "sentinel";
    uint64_t count = 99;
    EXPECT_EQ(rrc_context_device_name(ctx, name, sizeof name), RRC_ERROR_INVALID_HANDLE);
    EXPECT_EQ(rrc_context_validation_messages(ctx, &count), RRC_ERROR_INVALID_HANDLE);
    EXPECT_STREQ(name, "sentinel");
    EXPECT_EQ(count, 99u);
}

// Everything a frame call passes, good by default; cases spoil one thing.
struct Call {
    std::vector<float> depth = std::vector<float>(kN, 0.5f), clip = std::vector<float>(4 * kN), s1 = std::vector<float>(kN, 1.0f),
                       s4 = std::vector<float>(4 * kN, 1.0f), conf = std::vector<float>(kN, 1.0f);
    std::vector<uint8_t> nocache = std::vector<uint8_t>(kN, 0);
    std::vector<uint32_t> object_id = std::vector<uint32_t>(kN, 3);
    rrc_channel_input inputs[2];
    rrc_frame_desc frame;
    // Outputs with sentinel contents.
    std::vector<float> out1 = std::vector<float>(kN, -7.0f), out4 = std::vector<float>(4 * kN, -7.0f),
                       weight = std::vector<float>(kN, -7.0f);
    std::vector<uint16_t> age1 = std::vector<uint16_t>(kN, 777), age4 = std::vector<uint16_t>(kN, 777);
    std::vector<uint8_t> mask = std::vector<uint8_t>(kN, 0xEE);
    rrc_channel_output outs[2];
    rrc_frame_output output;

    Call() {
        for (uint32_t j = 0; j < kH; ++j)  // a static frame: each pixel's own clip position
            for (uint32_t i = 0; i < kW; ++i) {
                float* c = &clip[4 * (j * kW + i)];
                c[0] = 2.0f * (i + 0.5f) / kW - 1.0f;
                c[1] = 2.0f * (j + 0.5f) / kH - 1.0f;
                c[2] = 0.5f;
                c[3] = 1.0f;
            }
        inputs[0] = channel_input(s1.data(), conf.data());
        inputs[1] = channel_input(s4.data());
        frame = frame_desc();
        frame.depth = depth.data();
        frame.reprojection = clip.data();
        frame.nocache = nocache.data();
        frame.object_id = object_id.data();
        frame.channel_count = 2;
        frame.channels = inputs;
        for (rrc_channel_output& o : outs) o = rrc_host::channel_output();
        outs[0].values = out1.data();
        outs[0].age = age1.data();
        outs[0].weight = weight.data();
        outs[1].values = out4.data();
        outs[1].age = age4.data();
        output = mask_output(mask);
        output.channel_count = 2;
        output.channels = outs;
        output.stats.hits = 4242;
    }
    Call(const Call&) = delete;

    bool outputs_untouched() const {
        return out1 == std::vector<float>(kN, -7.0f) && out4 == std::vector<float>(4 * kN, -7.0f) &&
               weight == std::vector<float>(kN, -7.0f) && age1 == std::vector<uint16_t>(kN, 777) &&
               age4 == std::vector<uint16_t>(kN, 777) && mask == std::vector<uint8_t>(kN, 0xEE) && output.stats.hits == 4242;
    }
};

// One lazily made T for the whole program (SharedTeardown destroys it).
template <typename T>
class LazyInstance {
public:
    static std::unique_ptr<T>& instance() {
        static std::unique_ptr<T> s;
        return s;
    }
    static T& get() {
        if (!instance()) instance().reset(new T);
        return *instance();
    }
};

// One context for all cases: channel 0 has confidence (1 component, fp32),
// channel 1 has none (4 components, fp16); PREV_CLIP, a do-not-cache mask and object ids,
// so every optional input is required somewhere.
const std::vector<rrc_channel_desc> kSharedChannels = {
    channel("conf", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1),
    channel("color", 4, 0.5f, RRC_HISTORY_FP16)};
rrc_context_desc shared_desc() {
    rrc_context_desc d = context_desc(kW, kH, kSharedChannels);
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    d.use_nocache_mask = 1;
    d.use_object_id = 1;
    return d;
}

class Shared : public LazyInstance<Shared> {
    friend LazyInstance<Shared>;

public:
    rrc_context* ctx() { return ctx_->get(); }
    // Runs a good frame; returns false unless it hit everywhere with the age
    // one above the previous good frame's.
    ::testing::AssertionResult good_frame_continues_history() {
        Call call;
        rrc_result r = rrc_frame_run(ctx(), &call.frame, &call.output);
        if (r != RRC_SUCCESS) return ::testing::AssertionFailure() << "good frame failed: " << rrc_last_error();
        const uint16_t want = (uint16_t)std::min<uint32_t>(++frames_, 255);
        if (frames_ > 1 && call.output.stats.hits != kN) return ::testing::AssertionFailure() << call.output.stats.hits << " hits";
        if (call.age1 != std::vector<uint16_t>(kN, want) || call.age4 != std::vector<uint16_t>(kN, want))
            return ::testing::AssertionFailure() << "age " << call.age1[0] << ", expected " << want << ": a refused call ran a frame";
        return ::testing::AssertionSuccess();
    }

private:
    Shared() {
        rrc_context_desc d = shared_desc();
        ctx_.reset(new Context(d));
        EXPECT_TRUE(good_frame_continues_history());
    }
    std::unique_ptr<Context> ctx_;
    uint32_t frames_ = 0;
};

// Destroys the shared context inside the test program, so its destructor's
// checks (validation messages, leaks reported at destruction) still count.
void reset_vulkan_shared();
class SharedTeardown : public ::testing::Environment {
public:
    void TearDown() override {
        Shared::instance().reset();
        reset_vulkan_shared();
    }
};
const ::testing::Environment* const kSharedTeardown = ::testing::AddGlobalTestEnvironment(new SharedTeardown);

// One summary row for the whole file: every test ends with done().
void done(const char* suite) {
    static int passed = 0, failed = 0;
    (::testing::Test::HasFailure() ? failed : passed) += 1;
    rrc_stab::report("bad input at the C API",
                     "api_bad_input_test.cpp: frame cases via rrc_frame_run and as frames[1] of a batch, "
                     "batch arguments, NULL/destroyed/foreign handles, queries, create, camera matrices",
                     "specific code, message naming the field, outputs untouched, history intact",
                     rrc_stab::format("%d tests passed, %d failed (last: %s)", passed, failed, suite));
}

using rrc_test::vkpath::VkFrame;

struct FrameCase {
    const char* name;
    rrc_result code;
    const char* field;                       // must appear in the message
    std::function<void(Call&)> spoil;        // standalone (NULL: a Vulkan-only case)
    std::function<void(VkFrame&)> vk_spoil;  // the Vulkan path's equivalent (NULL: none)
};

// A chained struct of a type no version defines (rrc.h Versioning, rule 5).
struct UnknownExtension {
    rrc_struct_type type = 0x525243EFu;
    const void* next = nullptr;
    uint32_t size = sizeof(UnknownExtension);
};
const UnknownExtension kUnknownExtension{};
const rrc_frame_desc kBaseStruct = frame_desc();  // a base struct's tag in a chain: INVALID_STRUCT

std::vector<FrameCase> frame_cases() {
    const VkImageView no_view = VK_NULL_HANDLE;
    (void)no_view;
    return {
        {"frame_wrong_type", RRC_ERROR_INVALID_STRUCT, "frame.type", [](Call& c) { c.frame.type = RRC_STRUCT_TYPE_CONTEXT_DESC; },
         [](VkFrame& f) { f.desc.type = RRC_STRUCT_TYPE_CONTEXT_DESC; }},
        {"frame_size_too_small", RRC_ERROR_INVALID_STRUCT, "frame.size", [](Call& c) { c.frame.size = 12; },
         [](VkFrame& f) { f.desc.size = 12; }},
        // 0.2: `next` is an extension chain; a base struct's tag in it is INVALID_STRUCT.
        {"frame_next_set", RRC_ERROR_INVALID_STRUCT, "frame.next", [](Call& c) { c.frame.next = &c.inputs[0]; },
         [](VkFrame& f) { f.desc.next = &kBaseStruct; }},
        {"frame_next_unknown_extension", RRC_ERROR_UNSUPPORTED, "frame.next[0].type", [](Call& c) { c.frame.next = &kUnknownExtension; },
         [](VkFrame& f) { f.desc.next = &kUnknownExtension; }},
        {"depth_null", RRC_ERROR_MISSING_INPUT, "frame.depth", [](Call& c) { c.frame.depth = nullptr; },
         [](VkFrame& f) { f.desc.depth = rrc_vulkan_image{}; }},
        {"reprojection_null", RRC_ERROR_MISSING_INPUT, "frame.reprojection", [](Call& c) { c.frame.reprojection = nullptr; },
         [](VkFrame& f) { f.desc.reprojection = rrc_vulkan_image{}; }},
        {"nocache_null", RRC_ERROR_MISSING_INPUT, "frame.nocache", [](Call& c) { c.frame.nocache = nullptr; },
         [](VkFrame& f) { f.desc.nocache = rrc_vulkan_image{}; }},
        {"object_id_null", RRC_ERROR_MISSING_INPUT, "frame.object_id", [](Call& c) { c.frame.object_id = nullptr; },
         [](VkFrame& f) { f.desc.object_id = rrc_vulkan_image{}; }},
        {"channel_count_zero", RRC_ERROR_SIZE_MISMATCH, "frame.channel_count", [](Call& c) { c.frame.channel_count = 0; },
         [](VkFrame& f) { f.desc.channel_count = 0; }},
        {"channel_count_too_many", RRC_ERROR_SIZE_MISMATCH, "frame.channel_count", [](Call& c) { c.frame.channel_count = 3; },
         [](VkFrame& f) { f.desc.channel_count = 3; }},
        {"channels_null", RRC_ERROR_MISSING_INPUT, "frame.channels", [](Call& c) { c.frame.channels = nullptr; },
         [](VkFrame& f) { f.desc.channels = nullptr; }},
        {"channel_input_wrong_type", RRC_ERROR_INVALID_STRUCT, "frame.channels[1].type", [](Call& c) { c.inputs[1].type = 0; },
         [](VkFrame& f) { f.channels[1].type = 0; }},
        {"channel_input_size_too_small", RRC_ERROR_INVALID_STRUCT, "frame.channels[1].size", [](Call& c) { c.inputs[1].size = 8; },
         [](VkFrame& f) { f.channels[1].size = 8; }},
        {"channel_input_next_set", RRC_ERROR_INVALID_STRUCT, "frame.channels[0].next", [](Call& c) { c.inputs[0].next = &c.frame; },
         [](VkFrame& f) { f.channels[0].next = &kBaseStruct; }},
        {"channel_input_next_unknown_extension", RRC_ERROR_UNSUPPORTED, "frame.channels[0].next[0].type",
         [](Call& c) { c.inputs[0].next = &kUnknownExtension; }, [](VkFrame& f) { f.channels[0].next = &kUnknownExtension; }},
        {"samples_null", RRC_ERROR_MISSING_INPUT, "frame.channels[1].samples", [](Call& c) { c.inputs[1].samples = nullptr; },
         [](VkFrame& f) { f.channels[1].samples = rrc_vulkan_image{}; }},
        {"confidence_null", RRC_ERROR_MISSING_INPUT, "frame.channels[0].confidence", [](Call& c) { c.inputs[0].confidence = nullptr; },
         [](VkFrame& f) { f.channels[0].confidence = rrc_vulkan_image{}; }},
        {"jitter_nan", RRC_ERROR_INVALID_ARGUMENT, "jitter", [](Call& c) { c.frame.jitter[1] = kNaN; },
         [](VkFrame& f) { f.desc.jitter[1] = kNaN; }},
        {"jitter_beyond_a_pixel", RRC_ERROR_INVALID_ARGUMENT, "jitter", [](Call& c) { c.frame.jitter[0] = 1.5f; },
         [](VkFrame& f) { f.desc.jitter[0] = 1.5f; }},
        {"prev_jitter_inf", RRC_ERROR_INVALID_ARGUMENT, "prev_jitter", [](Call& c) { c.frame.prev_jitter[0] = -kInf; },
         [](VkFrame& f) { f.desc.prev_jitter[0] = -kInf; }},
        {"output_wrong_type", RRC_ERROR_INVALID_STRUCT, "output.type", [](Call& c) { c.output.type = RRC_STRUCT_TYPE_FRAME_DESC; }, {}},
        {"output_size_too_small", RRC_ERROR_INVALID_STRUCT, "output.size", [](Call& c) { c.output.size = 4; }, {}},
        {"output_next_set", RRC_ERROR_INVALID_STRUCT, "output.next", [](Call& c) { c.output.next = &c.frame; }, {}},
        {"output_channel_count_mismatch", RRC_ERROR_SIZE_MISMATCH, "output.channel_count", [](Call& c) { c.output.channel_count = 1; }, {}},
        {"output_channels_null", RRC_ERROR_INVALID_ARGUMENT, "output.channels", [](Call& c) { c.output.channels = nullptr; }, {}},
        {"output_channel_wrong_type", RRC_ERROR_INVALID_STRUCT, "output.channels[1].type", [](Call& c) { c.outs[1].type = 99; }, {}},
        {"output_channel_size_too_small", RRC_ERROR_INVALID_STRUCT, "output.channels[0].size", [](Call& c) { c.outs[0].size = 1; }, {}},
        {"output_weight_without_confidence",
         RRC_ERROR_INVALID_ARGUMENT,
         "output.channels[1].weight",
         [](Call& c) { c.outs[1].weight = c.weight.data(); },
         {}},
        // The Vulkan path's own inputs (no standalone equivalent).
        {"vk_command_buffer_null",
         RRC_ERROR_INVALID_ARGUMENT,
         "frame.command_buffer",
         {},
         [](VkFrame& f) { f.desc.command_buffer = VK_NULL_HANDLE; }},
        {"vk_depth_view_null", RRC_ERROR_MISSING_INPUT, "frame.depth", {}, [](VkFrame& f) { f.desc.depth.view = VK_NULL_HANDLE; }},
        {"vk_output_image_null",
         RRC_ERROR_MISSING_INPUT,
         "frame.channels[1].output",
         {},
         [](VkFrame& f) { f.channels[1].output = rrc_vulkan_image{}; }},
        {"vk_channel_images_mixed_sizes",
         RRC_ERROR_INVALID_STRUCT,
         "frame.channels[1].size",
         {},
         [](VkFrame& f) { f.channels[1].size = (uint32_t)sizeof(rrc_vulkan_channel_images) - 8; }},
        {"vk_object_id_wrong_format",
         RRC_ERROR_INVALID_ARGUMENT,
         "frame.object_id.format",
         {},
         [](VkFrame& f) { f.desc.object_id.format = VK_FORMAT_R8_UINT; }},
        {"vk_storage_inputs_depth_attachment",
         RRC_ERROR_INVALID_ARGUMENT,
         "frame.depth.format",
         {},
         [](VkFrame& f) {
             f.desc.storage_inputs = 1;  // a depth format is never a storage image
             f.desc.depth.format = VK_FORMAT_D32_SFLOAT;
         }},
        {"vk_storage_inputs_samples_fp16",
         RRC_ERROR_INVALID_ARGUMENT,
         "frame.channels[0].samples.format",
         {},
         [](VkFrame& f) {
             f.desc.storage_inputs = 1;
             f.desc.depth.format = VK_FORMAT_R32_SFLOAT;  // refused before any Vulkan use: only the samples are wrong
             f.channels[0].samples.format = VK_FORMAT_R16_SFLOAT;
         }},
    };
}

std::vector<FrameCase> standalone_cases() {
    std::vector<FrameCase> v;
    for (FrameCase& c : frame_cases())
        if (c.spoil) v.push_back(c);
    return v;
}

std::vector<FrameCase> vulkan_cases() {
    std::vector<FrameCase> v;
    for (FrameCase& c : frame_cases())
        if (c.vk_spoil) v.push_back(c);
    return v;
}

// ctest shows the parameter: print its name, not its bytes.
void PrintTo(const FrameCase& c, std::ostream* os) { *os << c.name; }

class FrameRun : public ::testing::TestWithParam<FrameCase> {};

TEST_P(FrameRun, RefusedUntouchedHistoryIntact) {
    const FrameCase& fc = GetParam();
    Shared& shared = Shared::get();
    Call call;
    fc.spoil(call);
    EXPECT_EQ(rrc_frame_run(shared.ctx(), &call.frame, &call.output), fc.code) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find(fc.field), std::string::npos) << rrc_last_error();
    EXPECT_STREQ(rrc_context_last_error(shared.ctx()), rrc_last_error());
    EXPECT_TRUE(call.outputs_untouched());
    EXPECT_TRUE(shared.good_frame_continues_history());
    done("FrameRun.RefusedUntouchedHistoryIntact");
}

INSTANTIATE_TEST_SUITE_P(Api, FrameRun, ::testing::ValuesIn(standalone_cases()),
                         [](const ::testing::TestParamInfo<FrameCase>& i) { return std::string(i.param.name); });

class FrameRunBatch : public ::testing::TestWithParam<FrameCase> {};

TEST_P(FrameRunBatch, RefusedAsFrameOneOfThree) {
    const FrameCase& fc = GetParam();
    Shared& shared = Shared::get();
    Call a, b, c;
    fc.spoil(b);
    rrc_frame_desc frames[3] = {a.frame, b.frame, c.frame};
    rrc_frame_output outputs[3] = {a.output, b.output, c.output};
    EXPECT_EQ(rrc_frame_run_batch(shared.ctx(), 3, frames, outputs), fc.code) << rrc_last_error();
    const std::string message = rrc_last_error();
    EXPECT_NE(message.find(std::string("frames[1]: ")), std::string::npos) << message;
    EXPECT_NE(message.find(fc.field), std::string::npos) << message;
    EXPECT_TRUE(a.outputs_untouched() && b.outputs_untouched() && c.outputs_untouched());
    for (auto& o : outputs) EXPECT_EQ(o.stats.hits, 4242u);
    EXPECT_TRUE(shared.good_frame_continues_history());
    done("FrameRunBatch.RefusedAsFrameOneOfThree");
}

INSTANTIATE_TEST_SUITE_P(Api, FrameRunBatch, ::testing::ValuesIn(standalone_cases()),
                         [](const ::testing::TestParamInfo<FrameCase>& i) { return std::string(i.param.name); });

// ---- the Vulkan path: rrc_vulkan_record_frame ------------------------------

using rrc_test::vkpath::VulkanRig;

// The shared context's twin on a host device: the same channels, PREV_CLIP
// and do-not-cache mask, so every case above has its equivalent.
class VulkanShared : public LazyInstance<VulkanShared> {
    friend LazyInstance<VulkanShared>;

public:
    ~VulkanShared() {
        rig_.reset();
        host_->shutdown();
        EXPECT_EQ(host_->message_count(), 0u) << (host_->messages().empty() ? "" : host_->messages().front());
    }
    rrc_context* ctx() { return rig_->ctx; }
    VulkanRig& rig() { return *rig_; }
    rrc_test::VulkanHost& host() { return *host_; }

    // Records a good frame whose samples alternate 1, 2, 1, ... and checks it
    // continues the lambda recursion (0.5) of the previous good frame: a
    // refused call that ran, or that moved the ping-pong, shows here.
    ::testing::AssertionResult good_frame_continues_history() {
        const uint32_t k = frames_++;
        const float s = k % 2 ? 2.0f : 1.0f;
        expected_ = k == 0 ? s : 0.5 * expected_ + 0.5 * s;
        rig_->upload_samples(0, std::vector<float>(kN, s));
        rig_->upload_samples(1, std::vector<float>(4 * kN, s));
        rig_->fill_outputs();
        VkFrame f = rig_->frame(k);
        uint64_t recorded = 0;
        rrc_result r = rig_->record(f, {}, &recorded);
        if (r != RRC_SUCCESS) return ::testing::AssertionFailure() << "good frame failed: " << rrc_last_error();
        if (recorded == 0) return ::testing::AssertionFailure() << "a good frame recorded nothing";
        const std::vector<float> v0 = rig_->values(0), v1 = rig_->values(1);
        for (float x : v0)  // fp32 history: exact (dyadic values)
            if (std::fabs(x - expected_) > 1e-6) return ::testing::AssertionFailure() << "value " << x << ", expected " << expected_;
        for (float x : v1)  // fp16 history: rounding, at most ~1e-3 here; a wrong history is >= 0.25 off
            if (std::fabs(x - expected_) > 4e-3) return ::testing::AssertionFailure() << "fp16 value " << x << ", expected " << expected_;
        if (rig_->mask_bytes() != std::vector<uint8_t>(kN, k ? RRC_MASK_HIT : 0))
            return ::testing::AssertionFailure() << "mask " << (int)rig_->mask_bytes()[0] << " on good frame " << k;
        const uint16_t want_age = (uint16_t)std::min<uint32_t>(k + 1, 255);
        if (rig_->age(0) != std::vector<uint16_t>(kN, want_age) || rig_->age(1) != std::vector<uint16_t>(kN, want_age))
            return ::testing::AssertionFailure()
                   << "age " << rig_->age(0)[0] << ", expected " << want_age << ": a refused call ran a frame";
        const rrc_vulkan_frame_stats st = rig_->frame_stats();
        if (st.hits != (k ? kN : 0) || st.pixels != kN) return ::testing::AssertionFailure() << st.hits << " hits of " << st.pixels;
        return ::testing::AssertionSuccess();
    }

private:
    VulkanShared() : host_(new rrc_test::VulkanHost) {
        rrc_context_desc d = shared_desc();
        rig_.reset(new VulkanRig(*host_, d));
        EXPECT_EQ(rig_->create_result, RRC_SUCCESS) << rrc_last_error();
        Call inputs;  // the standalone cases' static frame
        rig_->upload_depth(inputs.depth);
        rig_->upload_reprojection(inputs.clip);
        rig_->upload_nocache(inputs.nocache);
        rig_->upload_object_id(inputs.object_id);
        rig_->upload_confidence(0, inputs.conf);
        EXPECT_TRUE(good_frame_continues_history());
    }
    std::unique_ptr<rrc_test::VulkanHost> host_;
    std::unique_ptr<VulkanRig> rig_;
    uint32_t frames_ = 0;
    double expected_ = 0.0;
};

void reset_vulkan_shared() { VulkanShared::instance().reset(); }

// Refused: the code and field of the standalone path, nothing recorded into
// the command buffer, nothing written once it ran, history intact.
::testing::AssertionResult refused_on_vulkan(VulkanRig& rig, const std::function<void(VkFrame&)>& spoil, rrc_result code,
                                             const char* field) {
    for (uint32_t c = 0; c < rig.images.size(); ++c)  // had anything run, 100 would show
        rig.upload_samples(c, std::vector<float>(rig.pixels() * rig.images[c].samples.texel_bytes / 4, 100.0f));
    rig.fill_outputs();
    VkFrame f = rig.frame(1000);
    uint64_t recorded = 99;
    const rrc_result r = rig.record(f, spoil, &recorded);
    const std::string message = rrc_last_error();
    if (r != code)
        return ::testing::AssertionFailure() << rrc_result_to_string(r) << " instead of " << rrc_result_to_string(code) << ": " << message;
    if (message.find(field) == std::string::npos) return ::testing::AssertionFailure() << "message must name " << field << ": " << message;
    if (message != rrc_context_last_error(rig.ctx)) return ::testing::AssertionFailure() << "rrc_context_last_error differs";
    if (recorded != 0) return ::testing::AssertionFailure() << recorded << " commands recorded by a refused call";
    for (uint32_t c = 0; c < rig.images.size(); ++c) {
        for (float x : rig.values(c))
            if (x != -7.0f) return ::testing::AssertionFailure() << "output " << c << " written: " << x;
        if (rig.age(c) != std::vector<uint16_t>(rig.pixels(), 777)) return ::testing::AssertionFailure() << "age " << c << " written";
    }
    if (rig.mask_bytes() != std::vector<uint8_t>(rig.pixels(), 0xEE)) return ::testing::AssertionFailure() << "mask written";
    const rrc_vulkan_frame_stats st = rig.frame_stats();
    const std::vector<unsigned char> sb((const unsigned char*)&st, (const unsigned char*)&st + sizeof st);
    if (sb != std::vector<unsigned char>(sizeof st, 0xEE) || !rig.stats_guard_untouched())
        return ::testing::AssertionFailure() << "stats written";
    return ::testing::AssertionSuccess();
}

class VulkanRecord : public ::testing::TestWithParam<FrameCase> {};

TEST_P(VulkanRecord, RefusedNothingRecordedHistoryIntact) {
    const FrameCase& fc = GetParam();
    VulkanShared& shared = VulkanShared::get();
    EXPECT_TRUE(refused_on_vulkan(shared.rig(), fc.vk_spoil, fc.code, fc.field));
    EXPECT_TRUE(shared.good_frame_continues_history());
    done("VulkanRecord.RefusedNothingRecordedHistoryIntact");
}

INSTANTIATE_TEST_SUITE_P(Api, VulkanRecord, ::testing::ValuesIn(vulkan_cases()),
                         [](const ::testing::TestParamInfo<FrameCase>& i) { return std::string(i.param.name); });

// CAMERA on the Vulkan path: a singular or non-finite view_proj is refused
// by name, as on the standalone path (ApiCamera below).
TEST(ApiVulkanCamera, SingularViewProjection) {
    rrc_test::VulkanHost host;
    {
        VulkanRig rig(host, one_channel_desc(4, 4));
        ASSERT_EQ(rig.create_result, RRC_SUCCESS) << rrc_last_error();
        rig.upload_depth(std::vector<float>(16, 0.5f));
        auto zero = [](VkFrame& f) { std::memset(f.desc.view_proj, 0, sizeof f.desc.view_proj); };
        EXPECT_TRUE(refused_on_vulkan(rig, zero, RRC_ERROR_INVALID_ARGUMENT, "frame.view_proj"));
        auto rank3 = [](VkFrame& f) { f.desc.view_proj[15] = 0.0; };
        EXPECT_TRUE(refused_on_vulkan(rig, rank3, RRC_ERROR_INVALID_ARGUMENT, "frame.view_proj"));
        auto nan = [](VkFrame& f) { f.desc.prev_view_proj[7] = std::numeric_limits<double>::quiet_NaN(); };
        EXPECT_TRUE(refused_on_vulkan(rig, nan, RRC_ERROR_INVALID_ARGUMENT, "view_proj"));
        rig.upload_samples(0, std::vector<float>(16, 1.0f));
        rig.fill_outputs();
        VkFrame f = rig.frame(0);
        EXPECT_EQ(rig.record(f), RRC_SUCCESS) << rrc_last_error();
        EXPECT_EQ(rig.age(0), std::vector<uint16_t>(16, 1)) << "the refused calls must not have run";
    }
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << (host.messages().empty() ? "" : host.messages().front());
    done("ApiVulkanCamera.SingularViewProjection");
}

// A depth image whose VkFormat disagrees with the context's depth_format
// (epsilon is made from the format) is refused, naming depth.
struct DepthFormatCase {
    rrc_depth_format context_format;
    VkFormat image_format;
    rrc_result code;
};

TEST(ApiVulkanDepth, ImageFormatDisagreesWithDepthFormat) {
    rrc_test::VulkanHost host;
    for (const DepthFormatCase& c : {DepthFormatCase{RRC_DEPTH_FORMAT_FLOAT32, VK_FORMAT_D16_UNORM, RRC_ERROR_INVALID_ARGUMENT},
                                     DepthFormatCase{RRC_DEPTH_FORMAT_UNORM24, VK_FORMAT_D32_SFLOAT, RRC_ERROR_INVALID_ARGUMENT},
                                     DepthFormatCase{RRC_DEPTH_FORMAT_UNORM16, VK_FORMAT_D32_SFLOAT, RRC_ERROR_INVALID_ARGUMENT},
                                     DepthFormatCase{RRC_DEPTH_FORMAT_UNORM16, VK_FORMAT_D16_UNORM, RRC_SUCCESS},
                                     DepthFormatCase{RRC_DEPTH_FORMAT_FLOAT32, VK_FORMAT_D32_SFLOAT, RRC_SUCCESS}}) {
        SCOPED_TRACE(::testing::Message() << "depth_format " << c.context_format << ", image format " << c.image_format);
        rrc_context_desc d = one_channel_desc(4, 4);
        d.depth_format = c.context_format;
        VulkanRig rig(host, d, c.image_format);
        ASSERT_EQ(rig.create_result, RRC_SUCCESS) << rrc_last_error();
        rig.upload_depth(std::vector<float>(16, 0.5f));
        if (c.code == RRC_SUCCESS) {
            rig.upload_samples(0, std::vector<float>(16, 1.0f));
            rig.fill_outputs();
            VkFrame f = rig.frame(0);
            EXPECT_EQ(rig.record(f), RRC_SUCCESS) << rrc_last_error();
        } else {
            EXPECT_TRUE(refused_on_vulkan(rig, {}, c.code, "depth"));
        }
    }
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << (host.messages().empty() ? "" : host.messages().front());
    done("ApiVulkanDepth.ImageFormatDisagreesWithDepthFormat");
}

TEST(ApiVulkanCreate, NullDescOrDeviceLeavesOutputUntouched) {
    VulkanShared& shared = VulkanShared::get();
    rrc_context_desc d = one_channel_desc(4, 4);
    rrc_vulkan_device_desc dd = rrc_test::vkpath::device_desc(shared.host());
    rrc_context* out = kSentinelContext;
    EXPECT_EQ(rrc_vulkan_context_create(nullptr, &dd, &out), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("desc"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(rrc_vulkan_context_create(&d, nullptr, &out), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("device"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(out, kSentinelContext);
    done("ApiVulkanCreate.NullDescOrDeviceLeavesOutputUntouched");
}

// The largest valid extent on the host's device: OUT_OF_MEMORY, nothing left behind.
TEST(ApiVulkanCreate, LargestExtentBeyondTheDeviceFailsCleanly) {
    VulkanShared& shared = VulkanShared::get();
    rrc_context_desc d = largest_extent_desc();
    rrc_vulkan_device_desc dd = rrc_test::vkpath::device_desc(shared.host());
    rrc_context* out = kSentinelContext;
    EXPECT_EQ(rrc_vulkan_context_create(&d, &dd, &out), RRC_ERROR_OUT_OF_MEMORY) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find("memory"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(out, kSentinelContext);
    EXPECT_TRUE(shared.good_frame_continues_history());
    done("ApiVulkanCreate.LargestExtentBeyondTheDeviceFailsCleanly");
}

// ---- rrc_frame_run_batch's own arguments --------------------------------

TEST(ApiBatch, CountZero) {
    Call call;
    EXPECT_EQ(rrc_frame_run_batch(Shared::get().ctx(), 0, &call.frame, &call.output), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("count"), std::string::npos) << rrc_last_error();
    EXPECT_TRUE(call.outputs_untouched());
    EXPECT_TRUE(Shared::get().good_frame_continues_history());
    done("ApiBatch.CountZero");
}

TEST(ApiBatch, CountAbsurd) {
    Call call;  // one frame behind a count of 2^32 - 1: must be refused before anything is read
    EXPECT_EQ(rrc_frame_run_batch(Shared::get().ctx(), 0xFFFFFFFFu, &call.frame, &call.output), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("count"), std::string::npos) << rrc_last_error();
    EXPECT_TRUE(call.outputs_untouched());
    EXPECT_TRUE(Shared::get().good_frame_continues_history());
    done("ApiBatch.CountAbsurd");
}

TEST(ApiBatch, FramesNull) {
    Call call;
    EXPECT_EQ(rrc_frame_run_batch(Shared::get().ctx(), 2, nullptr, &call.output), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("frames"), std::string::npos) << rrc_last_error();
    EXPECT_TRUE(call.outputs_untouched());
    EXPECT_TRUE(Shared::get().good_frame_continues_history());
    done("ApiBatch.FramesNull");
}

// A batch whose staging memory exceeds what the device can allocate in one
// piece (65,536 frames of 512x512: 128 GiB of inputs) fails cleanly:
// OUT_OF_MEMORY, outputs untouched, history intact, the context usable.
TEST(ApiBatch, StagingBeyondTheDeviceFailsCleanly) {
    const uint32_t W = 512, H = 512, count = 65536;
    Context ctx(one_channel_desc(W, H));
    ASSERT_TRUE(ctx);
    StaticFrame f(W, H);
    ASSERT_EQ(rrc_stab::run_batch(ctx.get(), ctx.desc(), {f.data, f.data}).back().stats.hits, (uint64_t)W * H);
    std::vector<rrc_frame_desc> frames(count, f.desc);
    std::vector<uint8_t> mask(W * H, 0xEE);
    std::vector<rrc_frame_output> outputs(count, mask_output(mask));
    EXPECT_EQ(rrc_frame_run_batch(ctx.get(), count, frames.data(), outputs.data()), RRC_ERROR_OUT_OF_MEMORY) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find("memory"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(mask, std::vector<uint8_t>(W * H, 0xEE));
    rrc_test::FrameResult after = ctx.run(f.desc);
    EXPECT_EQ(after.stats.hits, (uint64_t)W * H);
    EXPECT_EQ(after.age[0], std::vector<uint16_t>(W * H, 3)) << "the refused batch must not have run";
    done("ApiBatch.StagingBeyondTheDeviceFailsCleanly");
}

// ---- handles --------------------------------------------------------------

TEST(ApiHandle, NullContextEverywhere) {
    Call call;
    EXPECT_EQ(rrc_frame_run(nullptr, &call.frame, &call.output), RRC_ERROR_INVALID_HANDLE);
    EXPECT_NE(std::string(rrc_last_error()).find("context is NULL"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(rrc_frame_run_batch(nullptr, 1, &call.frame, &call.output), RRC_ERROR_INVALID_HANDLE);
    expect_vulkan_and_queries_refuse_handle(nullptr, "context is NULL");
    EXPECT_TRUE(call.outputs_untouched());
    EXPECT_NE(std::string(rrc_context_last_error(nullptr)), "");  // a message, never a crash
    done("ApiHandle.NullContextEverywhere");
}

// A destroyed handle is detected (the library tracks live contexts) and a
// second destroy is ignored: calls in the wrong order fail, never crash.
TEST(ApiHandle, DestroyedContextEverywhere) {
    rrc_context_desc d = one_channel_desc(4, 4);
    rrc_context* ctx = nullptr;
    ASSERT_EQ(rrc_context_create(&d, &ctx), RRC_SUCCESS) << rrc_last_error();
    rrc_context_destroy(ctx);
    StaticFrame f(4, 4);
    EXPECT_EQ(rrc_frame_run(ctx, &f.desc, nullptr), RRC_ERROR_INVALID_HANDLE);
    EXPECT_NE(std::string(rrc_last_error()).find("not a live rrc context"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(rrc_frame_run_batch(ctx, 1, &f.desc, nullptr), RRC_ERROR_INVALID_HANDLE);
    expect_vulkan_and_queries_refuse_handle(ctx, "not a live rrc context");
    EXPECT_NE(std::string(rrc_context_last_error(ctx)).find("not a live"), std::string::npos);
    rrc_context_destroy(ctx);  // twice: ignored
    done("ApiHandle.DestroyedContextEverywhere");
}

TEST(ApiHandle, ForeignPointerEverywhere) {
    alignas(64) unsigned char garbage[512];
    std::memset(garbage, 0x5A, sizeof garbage);
    auto* fake = reinterpret_cast<rrc_context*>(garbage);
    Call call;
    EXPECT_EQ(rrc_frame_run_batch(fake, 1, &call.frame, &call.output), RRC_ERROR_INVALID_HANDLE);
    expect_vulkan_and_queries_refuse_handle(fake, nullptr);
    EXPECT_NE(std::string(rrc_context_last_error(fake)).find("not a live"), std::string::npos);
    rrc_context_destroy(fake);  // ignored, never freed
    EXPECT_EQ(garbage[100], 0x5A);
    EXPECT_TRUE(call.outputs_untouched());
    done("ApiHandle.ForeignPointerEverywhere");
}

// ---- queries --------------------------------------------------------------

TEST(ApiQuery, DeviceNameNullBuffer) {
    EXPECT_EQ(rrc_context_device_name(Shared::get().ctx(), nullptr, 64), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("out_name"), std::string::npos) << rrc_last_error();
    done("ApiQuery.DeviceNameNullBuffer");
}

TEST(ApiQuery, DeviceNameZeroCapacity) {
    char name[8] = "keep";
    EXPECT_EQ(rrc_context_device_name(Shared::get().ctx(), name, 0), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("capacity"), std::string::npos) << rrc_last_error();
    EXPECT_STREQ(name, "keep");
    done("ApiQuery.DeviceNameZeroCapacity");
}

TEST(ApiQuery, DeviceNameOneByteShort) {
    char name[256];
    ASSERT_EQ(rrc_context_device_name(Shared::get().ctx(), name, sizeof name), RRC_SUCCESS);
    const size_t need = std::strlen(name) + 1;
    std::vector<char> buffer(need, 'x');
    EXPECT_EQ(rrc_context_device_name(Shared::get().ctx(), buffer.data(), need - 1), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("capacity"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(buffer, std::vector<char>(need, 'x')) << "nothing may be written on error";
    EXPECT_EQ(rrc_context_device_name(Shared::get().ctx(), buffer.data(), need), RRC_SUCCESS);
    EXPECT_STREQ(buffer.data(), name);
    done("ApiQuery.DeviceNameOneByteShort");
}

TEST(ApiQuery, ValidationMessagesNullCount) {
    EXPECT_EQ(rrc_context_validation_messages(Shared::get().ctx(), nullptr), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("out_count"), std::string::npos) << rrc_last_error();
    uint64_t count = 99;
    EXPECT_EQ(rrc_context_validation_messages(Shared::get().ctx(), &count), RRC_SUCCESS);
    EXPECT_EQ(count, 0u) << "the validation layer reported something";
    done("ApiQuery.ValidationMessagesNullCount");
}

// A successful call clears rrc_last_error; the per-context message is that
// context's own.
TEST(ApiQuery, LastErrorIsClearedBySuccessAndKeptPerContext) {
    Call bad;
    bad.frame.depth = nullptr;
    EXPECT_EQ(rrc_frame_run(Shared::get().ctx(), &bad.frame, &bad.output), RRC_ERROR_MISSING_INPUT);
    EXPECT_NE(std::string(rrc_last_error()), "");
    uint64_t count = 0;
    EXPECT_EQ(rrc_context_validation_messages(Shared::get().ctx(), &count), RRC_SUCCESS);
    EXPECT_STREQ(rrc_last_error(), "");
    EXPECT_NE(std::string(rrc_context_last_error(Shared::get().ctx())).find("frame.depth"), std::string::npos);
    EXPECT_TRUE(Shared::get().good_frame_continues_history());
    done("ApiQuery.LastErrorIsClearedBySuccessAndKeptPerContext");
}

// ---- create ---------------------------------------------------------------

TEST(ApiCreate, NullDescLeavesOutputUntouched) {
    rrc_context* out = kSentinelContext;
    EXPECT_EQ(rrc_context_create(nullptr, &out), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("desc"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(out, kSentinelContext);
    done("ApiCreate.NullDescLeavesOutputUntouched");
}

// The largest valid extent with the widest inputs: needs far more than the
// device can allocate (a 16384x16384 RGBA32F image is 4 GiB): OUT_OF_MEMORY
// with a message, quickly, nothing left behind.
TEST(ApiCreate, LargestExtentBeyondTheDeviceFailsCleanly) {
    rrc_context_desc d = largest_extent_desc();
    ASSERT_EQ(rrc_validate_context_desc(&d), RRC_SUCCESS) << rrc_last_error();
    rrc_context* out = kSentinelContext;
    EXPECT_EQ(rrc_context_create(&d, &out), RRC_ERROR_OUT_OF_MEMORY) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find("memory"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(out, kSentinelContext);
    done("ApiCreate.LargestExtentBeyondTheDeviceFailsCleanly");
}

// A singular view-projection cannot be inverted: CAMERA frames refuse it by name.
TEST(ApiCamera, SingularViewProjection) {
    Context ctx(one_channel_desc(4, 4));
    ASSERT_TRUE(ctx);
    StaticFrame f(4, 4);
    rrc_frame_desc& d = f.desc;
    std::memset(d.view_proj, 0, sizeof d.view_proj);  // all zero
    std::vector<uint8_t> mask(16, 0xEE);
    rrc_frame_output o = mask_output(mask);
    EXPECT_EQ(rrc_frame_run(ctx.get(), &d, &o), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("frame.view_proj"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(mask, std::vector<uint8_t>(16, 0xEE));
    d.view_proj[0] = d.view_proj[5] = d.view_proj[10] = 1.0;  // rank 3: still singular
    EXPECT_EQ(rrc_frame_run(ctx.get(), &d, &o), RRC_ERROR_INVALID_ARGUMENT);
    d.view_proj[15] = 1.0;
    EXPECT_EQ(rrc_frame_run(ctx.get(), &d, &o), RRC_SUCCESS) << rrc_last_error();
    done("ApiCamera.SingularViewProjection");
}

TEST(ApiCamera, NonFiniteMatrices) {
    Context ctx(one_channel_desc(4, 4));
    ASSERT_TRUE(ctx);
    StaticFrame f(4, 4);
    f.desc.prev_view_proj[7] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f.desc, nullptr), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("view_proj"), std::string::npos) << rrc_last_error();
    done("ApiCamera.NonFiniteMatrices");
}

// rrc.h, "Thread safety": a call that finds another in progress on its
// context (here, deterministically, from inside the first call's log
// callback) is refused without touching the context, which keeps working.
TEST(ApiThreadSafety, ACallInsideAnotherOnTheSameContextIsRefused) {
    struct Probe {
        rrc_context* ctx = nullptr;
        const rrc_frame_desc* frame = nullptr;
        int calls = 0;
        rrc_result inner = RRC_SUCCESS;
        std::string message;
    } probe;
    rrc_context_desc d = one_channel_desc(4, 4);
    d.log = [](void* user, rrc_log_level level, const char*) {
        Probe& p = *static_cast<Probe*>(user);
        if (level != RRC_LOG_ERROR || p.calls++) return;  // once: the inner refusal logs too
        p.inner = rrc_frame_run(p.ctx, p.frame, nullptr);
        p.message = rrc_last_error();
    };
    d.log_user = &probe;
    rrc_context* raw = nullptr;  // not rrc_test::Context: it puts its own log callback in the descriptor
    ASSERT_EQ(rrc_context_create(&d, &raw), RRC_SUCCESS) << rrc_last_error();
    std::unique_ptr<rrc_context, void (*)(rrc_context*)> ctx(raw, rrc_context_destroy);
    StaticFrame f(4, 4);
    probe.ctx = ctx.get();
    probe.frame = &f.desc;
    EXPECT_EQ(rrc_frame_run(ctx.get(), nullptr, nullptr), RRC_ERROR_INVALID_ARGUMENT);  // its error is logged while it holds the context
    EXPECT_EQ(probe.inner, RRC_ERROR_UNSUPPORTED);
    EXPECT_NE(probe.message.find("another call on this context is in progress"), std::string::npos) << probe.message;
    EXPECT_NE(std::string(rrc_context_last_error(ctx.get())).find("frame"), std::string::npos) << "the refused call wrote the context's error";
    std::vector<uint8_t> mask(16, 0xEE);
    rrc_frame_output o = mask_output(mask);
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f.desc, &o), RRC_SUCCESS) << rrc_last_error();
    EXPECT_NE(mask, std::vector<uint8_t>(16, 0xEE)) << "the context works after the refusal";
    done("ApiThreadSafety.ACallInsideAnotherOnTheSameContextIsRefused");
}

}  // namespace
