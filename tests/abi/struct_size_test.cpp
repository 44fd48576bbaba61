// The 0.2 struct rules (include/rrc/rrc.h, Versioning) on every tagged struct
// of both headers, against the sizes a 0.1 caller's compiler gave them
// (abi_0_1_layout.c, compiled against the verbatim 0.1 headers):
//   rule 1: size < 0.1 size -> INVALID_STRUCT; the 0.1 size is accepted and
//           gives the same outputs as the full size (members beyond it read
//           as zero); larger with a zero tail -> accepted, the same outputs;
//           larger with any non-zero tail byte -> UNSUPPORTED;
//   rule 2: channel arrays strided by the elements' size (sizeof + 16, zero
//           tail: bit-identical outputs); mixed element sizes -> INVALID_STRUCT;
//   rule 3: outputs written only up to the caller's size (guard bytes);
//   rule 4: `next` chains: an unknown type -> UNSUPPORTED, a base struct's tag
//           -> INVALID_STRUCT, a cycle or more than RRC_MAX_CHAIN nodes ->
//           INVALID_STRUCT, messages naming "<field>.next[0]...".
// Every refused call leaves outputs untouched and history intact (the frame
// after it matches the reference frame for frame).  Contexts run under the
// validation layer; the Vulkan host's messages must be zero.
#include "abi/struct_support.h"
#include "abi/vulkan_path.h"
#include "abi_0_1_layout.h"
#include "support/rrc_test_context.h"

#include <rrc/rrc_vulkan.h>

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

using namespace rrc_abi;
using rrc_test::VulkanHost;
using rrc_test::vkpath::VkFrame;
using rrc_test::vkpath::VulkanRig;

namespace {

// The option rows of rrc_channel_desc in member order, with where each sits.
struct ChannelRow {
    const char* member;
    size_t offset, size;
    uint32_t version;
};
std::vector<ChannelRow> channel_rows() {
    return {
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, version, anchor) \
    {#member, offsetof(rrc_channel_desc, member), sizeof(rrc_channel_desc::member), version},
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    };
}

TEST(AbiChannelDesc, TheOptionTableIsTheStructAfterItsName) {
    // Every member after `name` is a row, in member order, with no gap; versions only grow.
    size_t at = offsetof(rrc_channel_desc, name) + sizeof(rrc_channel_desc::name);
    uint32_t version = 0;
    for (const ChannelRow& r : channel_rows()) {
        EXPECT_EQ(r.offset, at) << r.member << ": the table's rows follow the struct's members";
        EXPECT_GE(r.version, version) << r.member << ": an option of an earlier version after a later one";
        at = r.offset + r.size;
        version = r.version;
    }
    const size_t align = alignof(rrc_channel_desc);
    EXPECT_EQ((at + align - 1) / align * align, sizeof(rrc_channel_desc)) << "a member after the table's last row";
}


// ---- layout: every 0.1 member where a 0.1 caller put it ---------------------

const rrc_abi_entry kLayout02[] = {
#include "abi_0_1_entries.inc"
};

TEST(AbiLayout, HeaderVersions) {
    EXPECT_EQ(rrc_abi_0_1_header_version, RRC_MAKE_VERSION(0, 1, 0)) << "abi_0_1_layout.c must see tests/abi/rrc_0_1";
    EXPECT_EQ((uint32_t)RRC_API_VERSION, RRC_MAKE_VERSION(0, 13, 0)) << "rule 6: the current header is 0.13.0";
    EXPECT_EQ(RRC_VERSION_MAJOR(rrc_get_version()), 0u);
    EXPECT_GE(RRC_VERSION_MINOR(rrc_get_version()), 4u) << "the library must be at least as new as its header";
}

TEST(AbiLayout, Every01MemberKeepsItsOffsetSizeAndTag) {
    size_t n = 0;
    for (const rrc_abi_entry* e = rrc_abi_0_1_layout; e->struct_name; ++e, ++n) {
        const rrc_abi_entry& now = kLayout02[n];
        ASSERT_NE(now.struct_name, nullptr);
        SCOPED_TRACE(std::string(e->struct_name) + "." + (e->member ? e->member : "(struct)"));
        EXPECT_EQ(e->tag, now.tag) << "a struct's tag changed";
        if (e->member) {
            EXPECT_EQ(e->offset, now.offset) << "a 0.1 member moved";
            EXPECT_EQ(e->member_size, now.member_size) << "a 0.1 member changed size";
        }
    }
    EXPECT_EQ(kLayout02[n].struct_name, nullptr);
    EXPECT_GE(n, 100u);
}

// Rule 2: only the structs 0.2, 0.3 and 0.4 append to grew, and their new members
// start at or after the 0.1 size: rrc_vulkan_channel_images (age),
// rrc_vulkan_frame_desc (stats_buffer, stats_offset, object_id, storage_inputs),
// rrc_context_desc (depth_test, use_object_id; 0.3: refresh_policy,
// refresh_period, refresh_tiles, max_lifetime), rrc_frame_desc (object_id),
// rrc_frame_output (0.3: refreshed), rrc_channel_desc and rrc_channel_input (0.4: the finishing steps),
// rrc_vulkan_device_desc (0.11: enabled_features).
TEST(AbiLayout, OnlyTheAppendedStructsGrew) {
    const char* const appended[] = {"rrc_vulkan_channel_images", "rrc_vulkan_frame_desc", "rrc_context_desc",
                                    "rrc_frame_desc",            "rrc_frame_output",      "rrc_channel_desc",
                                    "rrc_channel_input",         "rrc_vulkan_device_desc"};
    for (const rrc_abi_entry* e = rrc_abi_0_1_layout; e->struct_name; ++e) {
        if (e->member) continue;
        size_t now = 0;
        for (const rrc_abi_entry* f = kLayout02; f->struct_name; ++f)
            if (!f->member && std::strcmp(f->struct_name, e->struct_name) == 0) now = f->offset;
        bool grows = false;
        for (const char* a : appended) grows = grows || std::strcmp(e->struct_name, a) == 0;
        if (grows)
            EXPECT_LT(e->offset, now) << e->struct_name << ": 0.2, 0.3 or 0.4 appends members";
        else
            EXPECT_EQ(e->offset, now) << e->struct_name << ": its 0.1 size must equal its 0.2 size";
    }
    EXPECT_GE(offsetof(rrc_vulkan_channel_images, age), size01("rrc_vulkan_channel_images"));
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, stats_buffer), size01("rrc_vulkan_frame_desc"));
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, stats_offset), size01("rrc_vulkan_frame_desc"));
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, object_id), size01("rrc_vulkan_frame_desc"));
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, storage_inputs), size01("rrc_vulkan_frame_desc"));
    EXPECT_GE(offsetof(rrc_context_desc, depth_test), size01("rrc_context_desc"));
    EXPECT_GE(offsetof(rrc_context_desc, use_object_id), size01("rrc_context_desc"));
    EXPECT_GE(offsetof(rrc_frame_desc, object_id), size01("rrc_frame_desc"));
    EXPECT_GE(offsetof(rrc_context_desc, refresh_policy), size01("rrc_context_desc"));
    EXPECT_GE(offsetof(rrc_context_desc, max_lifetime), size01("rrc_context_desc"));
    EXPECT_GE(offsetof(rrc_frame_output, refreshed), size01("rrc_frame_output"));
    // rrc_channel_desc's options (compute/rrc_channel_options.def): after the 0.1
    // size only the rows of later versions, each version's after the last.
    for (const ChannelRow& r : channel_rows()) {
        if (r.version > RRC_MAKE_VERSION(0, 1, 0)) EXPECT_GE(r.offset, size01("rrc_channel_desc")) << r.member;
        else EXPECT_LT(r.offset, size01("rrc_channel_desc")) << r.member << ": a 0.1 member";
    }
    EXPECT_GE(offsetof(rrc_frame_desc, camera_position), offsetof(rrc_frame_desc, reproject_from) + sizeof(uint32_t));  // 0.7 after 0.3
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, camera_position), offsetof(rrc_vulkan_frame_desc, split_outputs) + sizeof(uint32_t));
    EXPECT_GE(offsetof(rrc_frame_desc, lighting_turn), offsetof(rrc_frame_desc, prev_camera_position) + 3 * sizeof(double));  // 0.8
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, lighting_turn), offsetof(rrc_vulkan_frame_desc, prev_camera_position) + 3 * sizeof(double));
    EXPECT_GE(offsetof(rrc_channel_input, fallback), size01("rrc_channel_input"));
    EXPECT_GE(offsetof(rrc_vulkan_channel_images, fallback), size01("rrc_vulkan_channel_images"));
    EXPECT_EQ(sizeof(rrc_vulkan_frame_stats), 32u);
    // 0.10: the host's buffer sizes, after 0.8's last member and the quad list's 0.3 size.
    EXPECT_GE(offsetof(rrc_vulkan_frame_desc, stats_buffer_size), offsetof(rrc_vulkan_frame_desc, lighting_turn) + sizeof(float));
    EXPECT_EQ(offsetof(rrc_vulkan_quad_list, buffer_size), offsetof(rrc_vulkan_quad_list, offset) + sizeof(VkDeviceSize));
    // 0.11: the host's declared features, after the device description's 0.1 size.
    EXPECT_GE(offsetof(rrc_vulkan_device_desc, enabled_features), size01("rrc_vulkan_device_desc"));
}

// ---- the scene: 8x4, PREV_CLIP at each pixel's own clip position, column 0
// background, a do-not-cache pixel on odd frames, samples varying per frame
// and pixel; channel "a" 1 component fp32 FIXED 0.5 with confidence, "b" 4
// components fp16 AGE_AWARE 0.8 NEAREST.

constexpr uint32_t W = 8, H = 4, N = W * H;
constexpr int kFrames = 10;

std::vector<rrc_channel_desc> scene_channels() {
    return {rrc_test::channel("a", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1),
            rrc_test::channel("b", 4, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_NEAREST)};
}

rrc_context_desc scene_desc(const std::vector<rrc_channel_desc>& channels) {
    rrc_context_desc d = rrc_test::context_desc(W, H, channels);
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    d.use_nocache_mask = 1;
    return d;
}

struct SceneFrame {
    std::vector<float> depth = std::vector<float>(N), clip = std::vector<float>(4 * N), a = std::vector<float>(N),
                       conf = std::vector<float>(N), b = std::vector<float>(4 * N);
    std::vector<uint8_t> nocache = std::vector<uint8_t>(N, 0);
};

SceneFrame scene_frame(int t) {
    SceneFrame f;
    for (uint32_t j = 0; j < H; ++j)
        for (uint32_t i = 0; i < W; ++i) {
            const uint32_t p = j * W + i;
            f.depth[p] = i == 0 ? 1.0f : 0.5f;
            f.clip[4 * p + 0] = 2.0f * (i + 0.5f) / W - 1.0f;
            f.clip[4 * p + 1] = 2.0f * (j + 0.5f) / H - 1.0f;
            f.clip[4 * p + 2] = f.depth[p];
            f.clip[4 * p + 3] = 1.0f;
            f.a[p] = 1.0f + (float)((p * 5 + t * 3) % 7) * 0.25f;
            f.conf[p] = (p + t) % 2 ? 1.0f : 0.5f;
            for (int k = 0; k < 4; ++k) f.b[4 * p + k] = f.a[p] + (float)k;
        }
    if (t % 2) f.nocache[2 * W + 3] = 1;
    return f;
}

// ---- the standalone path ---------------------------------------------------

struct Result {
    std::vector<uint8_t> mask = std::vector<uint8_t>(N, 0xEE);
    std::vector<float> a = std::vector<float>(N, -7.0f), b = std::vector<float>(4 * N, -7.0f), weight = std::vector<float>(N, -7.0f);
    std::vector<uint16_t> age_a = std::vector<uint16_t>(N, 777), age_b = std::vector<uint16_t>(N, 777);
    rrc_frame_stats stats{};
    bool operator==(const Result& o) const {
        return mask == o.mask && a == o.a && b == o.b && weight == o.weight && age_a == o.age_a && age_b == o.age_b &&
               std::memcmp(&stats, &o.stats, sizeof stats) == 0;
    }
    bool untouched() const { return *this == Result(); }
};

// The plain structs of one frame call; Hooks turn them into the bytes passed.
struct Plain {
    rrc_frame_desc frame;
    std::vector<rrc_channel_input> inputs;
    rrc_frame_output output;
    std::vector<rrc_channel_output> outputs;
};

struct Hooks {
    std::function<void(Plain&)> edit;  // e.g. set a next chain
    std::function<Blob(const rrc_frame_desc&)> frame;
    std::function<Blob(const std::vector<rrc_channel_input>&)> inputs;
    std::function<Blob(const rrc_frame_output&)> output;
    std::function<Blob(const std::vector<rrc_channel_output>&)> outputs;
};

struct Outcome {
    rrc_result code = RRC_SUCCESS;
    std::string message;
    Result result;
    bool guards_untouched = true;  // rule 3: nothing written beyond the caller's size or the library's sizeof
};

template <typename T>
bool beyond_known_untouched(const Blob& b, size_t count) {
    if (!b.size()) return true;
    uint32_t stride;
    std::memcpy(&stride, b.data() + 16, 4);  // size of element 0
    for (size_t i = 0; i < count; ++i) {
        const size_t start = i * stride;
        if (!b.untouched(start + std::min<size_t>(stride, sizeof(T)), start + stride)) return false;
    }
    return b.untouched(count * stride, b.size());
}

Outcome run_frame(rrc_context* ctx, int t, const Hooks& h = Hooks()) {
    SceneFrame s = scene_frame(t);
    Outcome o;
    Plain p;
    p.inputs = {rrc_test::channel_input(s.a.data(), s.conf.data()), rrc_test::channel_input(s.b.data())};
    p.frame = rrc_test::frame_desc();
    p.frame.frame_index = (uint64_t)t;
    p.frame.depth = s.depth.data();
    p.frame.reprojection = s.clip.data();
    p.frame.nocache = s.nocache.data();
    p.frame.channel_count = 2;
    p.outputs.resize(2);
    for (auto& c : p.outputs) {
        std::memset(&c, 0, sizeof c);
        c.type = RRC_STRUCT_TYPE_CHANNEL_OUTPUT;
        c.size = sizeof c;
    }
    p.outputs[0].values = o.result.a.data();
    p.outputs[0].age = o.result.age_a.data();
    p.outputs[0].weight = o.result.weight.data();
    p.outputs[1].values = o.result.b.data();
    p.outputs[1].age = o.result.age_b.data();
    std::memset(&p.output, 0, sizeof p.output);
    p.output.type = RRC_STRUCT_TYPE_FRAME_OUTPUT;
    p.output.size = sizeof p.output;
    p.output.mask = o.result.mask.data();
    p.output.channel_count = 2;
    if (h.edit) h.edit(p);

    Blob inputs = h.inputs ? h.inputs(p.inputs) : pack_array(p.inputs, sizeof(rrc_channel_input), {}, 0);
    p.frame.channels = inputs.as<rrc_channel_input>();
    Blob outputs = h.outputs ? h.outputs(p.outputs) : pack_array(p.outputs, sizeof(rrc_channel_output), {}, 0);
    p.output.channels = outputs.as<rrc_channel_output>();
    Blob frame = h.frame ? h.frame(p.frame) : pack(p.frame, Shape());
    Blob output = h.output ? h.output(p.output) : pack(p.output, Shape());
    // rrc_frame_output.stats as sentinel, as far as the caller's buffer holds
    // it (a case may pass an exactly-sized buffer smaller than the struct).
    const size_t stats_at = offsetof(rrc_frame_output, stats);
    const size_t stats_bytes = output.size() > stats_at ? std::min(sizeof(rrc_frame_stats), output.size() - stats_at) : 0;
    std::memset(output.data() + stats_at, 0xEE, stats_bytes);
    output.snapshot();
    o.code = rrc_frame_run(ctx, frame.as<rrc_frame_desc>(), output.as<rrc_frame_output>());
    o.message = rrc_last_error();
    std::memset(&o.result.stats, 0xEE, sizeof o.result.stats);
    std::memcpy(&o.result.stats, output.data() + stats_at, stats_bytes);
    if (o.code != RRC_SUCCESS && output.untouched(stats_at, stats_at + stats_bytes))
        o.result.stats = rrc_frame_stats{};  // untouched sentinel: report as the default Result's
    o.guards_untouched = beyond_known_untouched<rrc_frame_output>(output, 1) && beyond_known_untouched<rrc_channel_output>(outputs, 2);
    return o;
}

// The reference: kFrames plain frames on a plain context.
const std::vector<Result>& reference() {
    static std::vector<Result> ref;
    if (ref.empty()) {
        std::vector<rrc_channel_desc> channels = scene_channels();
        rrc_test::Context ctx(scene_desc(channels));
        for (int t = 0; t < kFrames; ++t) {
            Outcome o = run_frame(ctx.get(), t);
            EXPECT_EQ(o.code, RRC_SUCCESS) << o.message;
            ref.push_back(o.result);
        }
        EXPECT_GT(ref[2].stats.hits, 20u);
    }
    return ref;
}

// A refused call: code, field named, outputs and guards untouched.
#define EXPECT_REFUSED(outcome, want_code, field)                                                                      \
    do {                                                                                                               \
        const Outcome& o_ = (outcome);                                                                                 \
        EXPECT_EQ(o_.code, want_code) << rrc_result_to_string(o_.code) << ": " << o_.message;                          \
        EXPECT_NE(o_.message.find(field), std::string::npos) << "message must name " << (field) << ": " << o_.message; \
        EXPECT_TRUE(o_.result.untouched()) << "a refused call wrote outputs";                                          \
        EXPECT_TRUE(o_.guards_untouched);                                                                              \
    } while (0)

// Rule 4 on one `next` member: set(next) puts a chain there, call() runs.
struct ChainCase {
    const char* name;
    rrc_result code;
    const char* field_suffix;  // after "<prefix>.next"
    std::function<const void*(std::vector<ChainNode>&)> make;
};

// Nodes of `types` into `n`, each pointing at the next; the last points back
// at node `cycle_to` when that is not negative.  Returns the chain's head.
const void* linked(std::vector<ChainNode>& n, const std::vector<rrc_struct_type>& types, int cycle_to = -1) {
    n.clear();
    for (rrc_struct_type t : types) n.push_back(node(t));
    for (size_t i = 0; i + 1 < n.size(); ++i) n[i].next = &n[i + 1];
    if (cycle_to >= 0) n.back().next = &n[(size_t)cycle_to];
    return &n[0];
}

// `count` distinct unknown extension types.
std::vector<rrc_struct_type> unknown_types(uint32_t count) {
    std::vector<rrc_struct_type> t;
    for (uint32_t i = 0; i < count; ++i) t.push_back(0x7A000000u + i);
    return t;
}

std::vector<ChainCase> chain_cases() {
    using Nodes = std::vector<ChainNode>;
    return {
        {"unknown_extension_type", RRC_ERROR_UNSUPPORTED, "[0].type", [](Nodes& n) { return linked(n, {kUnknownExtension}); }},
        {"unknown_foreign_type", RRC_ERROR_UNSUPPORTED, "[0].type", [](Nodes& n) { return linked(n, {0x12345678u}); }},
        {"base_struct_tag", RRC_ERROR_INVALID_STRUCT, "[0].type", [](Nodes& n) { return linked(n, {RRC_STRUCT_TYPE_FRAME_DESC}); }},
        // After an unknown extension: the walk checks the shape first.
        {"base_struct_tag_second", RRC_ERROR_INVALID_STRUCT, "[1].type",
         [](Nodes& n) {
             return linked(n, {kUnknownExtension, RRC_STRUCT_TYPE_CONTEXT_DESC});
         }},
        {"self_cycle", RRC_ERROR_INVALID_STRUCT, "", [](Nodes& n) { return linked(n, {kUnknownExtension}, 0); }},
        {"two_node_cycle", RRC_ERROR_INVALID_STRUCT, "",
         [](Nodes& n) {
             return linked(n, {kUnknownExtension, kUnknownExtension - 1}, 0);
         }},
        {"chain_of_65", RRC_ERROR_INVALID_STRUCT, "", [](Nodes& n) { return linked(n, unknown_types(65)); }},
        {"chain_of_64_unknown", RRC_ERROR_UNSUPPORTED, "[0].type", [](Nodes& n) { return linked(n, unknown_types(64)); }},
    };
}

// ---- frame-level structs (frame desc, channel input, frame output, channel output)

struct FrameStruct {
    const char* name;         // test name
    const char* struct_name;  // for size01
    const char* prefix;       // the field in messages
    size_t full;              // sizeof in 0.2
    bool array;
    // Hooks passing this struct with `shape` (arrays: stride = shape.size, sizes per element).
    std::function<Hooks(const Shape& shape, const std::vector<uint32_t>& sizes, long nonzero_at)> hooks;
    std::function<void(Plain&, const void* next)> set_next;  // on the struct (arrays: element 1)
};

// An array struct's entry: the elements strided by shape.size with per-element
// sizes, `guard` bytes of `guard_fill` after the array; the chain goes on element 1.
template <typename T>
FrameStruct array_struct(const char* name, const char* struct_name, const char* prefix,
                         std::function<Blob(const std::vector<T>&)> Hooks::*hook, std::vector<T> Plain::*elements,
                         size_t guard, unsigned char guard_fill) {
    return {name, struct_name, prefix, sizeof(T), true,
            [=](const Shape& s, const std::vector<uint32_t>& sizes, long nz) {
                Hooks h;
                h.*hook = [=](const std::vector<T>& v) { return pack_array(v, s.size, sizes, guard, guard_fill, nz); };
                return h;
            },
            [=](Plain& p, const void* next) { (p.*elements)[1].next = next; }};
}

std::vector<FrameStruct> frame_structs() {
    return {
        {"frame_desc", "rrc_frame_desc", "frame", sizeof(rrc_frame_desc), false,
         [](const Shape& s, const std::vector<uint32_t>&, long nz) {
             Hooks h;
             Shape sh = s;
             sh.nonzero_at = nz;
             h.frame = [sh](const rrc_frame_desc& f) { return pack(f, sh); };
             return h;
         },
         [](Plain& p, const void* next) { p.frame.next = next; }},
        {"frame_output", "rrc_frame_output", "output", sizeof(rrc_frame_output), false,
         [](const Shape& s, const std::vector<uint32_t>&, long nz) {
             Hooks h;
             Shape sh = s;
             sh.nonzero_at = nz;
             if (!sh.alloc) sh.alloc = std::max<size_t>(sh.size ? sh.size : sizeof(rrc_frame_output), sizeof(rrc_frame_output)) + 32;
             sh.beyond = 0xCD;  // guard bytes after the caller's size
             h.output = [sh](const rrc_frame_output& f) { return pack(f, sh); };
             return h;
         },
         [](Plain& p, const void* next) { p.output.next = next; }},
        // Inputs are only read: no guard bytes.  Outputs get 0xCD guards after the caller's array.
        array_struct("channel_input", "rrc_channel_input", "frame.channels", &Hooks::inputs, &Plain::inputs, 0, 0),
        array_struct("channel_output", "rrc_channel_output", "output.channels", &Hooks::outputs, &Plain::outputs, 32, 0xCD),
    };
}

void PrintTo(const FrameStruct& s, std::ostream* os) { *os << s.name; }

class FrameLevelStruct : public ::testing::TestWithParam<FrameStruct> {};

TEST_P(FrameLevelStruct, RulesOneToFour) {
    const FrameStruct& fs = GetParam();
    const std::vector<Result>& ref = reference();
    std::vector<rrc_channel_desc> channels = scene_channels();
    rrc_test::Context ctx(scene_desc(channels));
    ASSERT_TRUE(ctx);
    const uint32_t s01 = (uint32_t)size01(fs.struct_name), full = (uint32_t)fs.full, big = full + 16;
    auto shape = [&](uint32_t size, size_t alloc = 0) {
        Shape s;
        s.size = size;
        s.alloc = alloc;
        return s;
    };
    int t = 0;
    auto expect_accepted = [&](const Hooks& h, const char* what) {
        Outcome o = run_frame(ctx.get(), t, h);
        EXPECT_EQ(o.code, RRC_SUCCESS) << what << ": " << o.message;
        EXPECT_TRUE(o.result == ref[t]) << what << ": outputs differ from the plain frame " << t;
        EXPECT_TRUE(o.guards_untouched) << what << ": bytes beyond the caller's size or the library's struct were written";
        ++t;
    };
    expect_accepted(Hooks(), "plain frame 0");
    // Rule 1: the 0.1 size, in a buffer of exactly that many bytes (ASan: no over-read).
    expect_accepted(fs.hooks(shape(s01, fs.array ? 0 : s01), {}, -1), "0.1 size");
    // Rule 1 / 2: larger with a zero tail (arrays: strided by sizeof + 16).
    expect_accepted(fs.hooks(shape(big), {}, -1), "sizeof + 16, zero tail");
    // A 0.7 caller's frame ends before the lighting's turn (0.8), in a buffer of exactly that size.
    if (fs.name == std::string("frame_desc")) {
        const uint32_t s07 = (uint32_t)offsetof(rrc_frame_desc, lighting_turn);
        expect_accepted(fs.hooks(shape(s07, s07), {}, -1), "0.7 size");
    }
    // Garbage right after the struct (arrays: after the last element) is never read.
    if (!fs.array) {
        Shape g = shape(full, full + 64);
        g.beyond = 0xA5;
        if (fs.prefix == std::string("output")) g.beyond = 0xCD;
        expect_accepted(fs.hooks(g, {}, -1), "garbage after the struct");
    }

    // Refusals: nothing written, history intact.
    const std::string p = fs.prefix, elem = fs.array ? p + "[0]" : p, elem1 = fs.array ? p + "[1]" : p;
    {
        SCOPED_TRACE("0.1 size - 1");
        EXPECT_REFUSED(run_frame(ctx.get(), t, fs.hooks(shape(s01 - 1), {}, -1)), RRC_ERROR_INVALID_STRUCT, elem + ".size");
    }
    {
        SCOPED_TRACE("size 0 (arrays) or 1");
        EXPECT_REFUSED(run_frame(ctx.get(), t, fs.array ? fs.hooks(shape(full), {0, 0}, -1) : fs.hooks(shape(1, 24), {}, -1)),
                       RRC_ERROR_INVALID_STRUCT, elem + ".size");
    }
    // A non-zero byte in the extension tail: a newer header's member this library does not know.
    const long first_tail = fs.array ? (long)big + full : (long)full;       // element 1's first tail byte
    const long last_tail = fs.array ? (long)big + big - 1 : (long)big - 1;  // element 1's last tail byte
    for (long nz : {first_tail, last_tail}) {
        SCOPED_TRACE("non-zero tail byte " + std::to_string(nz));
        EXPECT_REFUSED(run_frame(ctx.get(), t, fs.hooks(shape(big), {}, nz)), RRC_ERROR_UNSUPPORTED, elem1);
    }
    if (fs.array) {
        SCOPED_TRACE("mixed element sizes");
        EXPECT_REFUSED(run_frame(ctx.get(), t, fs.hooks(shape(big), {big, full}, -1)), RRC_ERROR_INVALID_STRUCT, p + "[1].size");
        EXPECT_REFUSED(run_frame(ctx.get(), t, fs.hooks(shape(full), {full, big}, -1)), RRC_ERROR_INVALID_STRUCT, p + "[1].size");
    }
    for (const ChainCase& cc : chain_cases()) {
        SCOPED_TRACE(std::string("next chain: ") + cc.name);
        std::vector<ChainNode> nodes;
        const void* head = cc.make(nodes);
        Hooks h;
        h.edit = [&](Plain& pl) { fs.set_next(pl, head); };
        EXPECT_REFUSED(run_frame(ctx.get(), t, h), cc.code, elem1 + ".next" + cc.field_suffix);
    }
    // History intact: the remaining frames match the reference.
    for (; t < kFrames; ++t) {
        Outcome o = run_frame(ctx.get(), t);
        EXPECT_EQ(o.code, RRC_SUCCESS) << o.message;
        EXPECT_TRUE(o.result == ref[t]) << "frame " << t << " after the refused calls differs: history was touched";
    }
}

INSTANTIATE_TEST_SUITE_P(Abi, FrameLevelStruct, ::testing::ValuesIn(frame_structs()),
                         [](const ::testing::TestParamInfo<FrameStruct>& i) { return std::string(i.param.name); });

// ---- context-level structs (context desc, channel desc) ----------------------

// Creates a context from the given desc bytes; runs the whole sequence and
// compares it to the reference.
void expect_same_sequence(const rrc_context_desc* desc, const char* what) {
    SCOPED_TRACE(what);
    rrc_context* ctx = nullptr;
    ASSERT_EQ(rrc_validate_context_desc(desc), RRC_SUCCESS) << rrc_last_error();
    ASSERT_EQ(rrc_context_create(desc, &ctx), RRC_SUCCESS) << rrc_last_error();
    for (int t = 0; t < kFrames; ++t) {
        Outcome o = run_frame(ctx, t);
        EXPECT_EQ(o.code, RRC_SUCCESS) << o.message;
        EXPECT_TRUE(o.result == reference()[t]) << "frame " << t;
    }
    uint64_t messages = 1;
    EXPECT_EQ(rrc_context_validation_messages(ctx, &messages), RRC_SUCCESS);
    EXPECT_EQ(messages, 0u);
    rrc_context_destroy(ctx);
}

// A refused descriptor: validate and create both give `code` naming `field`; *out untouched.
void expect_desc_refused(const rrc_context_desc* desc, rrc_result code, const std::string& field, bool also_create = true) {
    EXPECT_EQ(rrc_validate_context_desc(desc), code) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find(field), std::string::npos) << "must name " << field << ": " << rrc_last_error();
    if (!also_create) return;
    rrc_context* sentinel = reinterpret_cast<rrc_context*>(0x1234);
    rrc_context* out = sentinel;
    EXPECT_EQ(rrc_context_create(desc, &out), code) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find(field), std::string::npos) << rrc_last_error();
    EXPECT_EQ(out, sentinel);
}

rrc_context_desc validated_desc(const std::vector<rrc_channel_desc>& channels) {
    rrc_context_desc d = scene_desc(channels);
    d.enable_validation = 1;
    return d;
}

TEST(AbiContextDesc, RulesOneAndFour) {
    std::vector<rrc_channel_desc> channels = scene_channels();
    const rrc_context_desc d = validated_desc(channels);
    const uint32_t s01 = (uint32_t)size01("rrc_context_desc"), full = sizeof(rrc_context_desc), big = full + 16;
    Shape s;
    s.size = s01;
    s.alloc = s01;
    expect_same_sequence(pack(d, s).as<rrc_context_desc>(), "0.1 size, exact buffer");
    s = Shape();
    s.size = big;
    expect_same_sequence(pack(d, s).as<rrc_context_desc>(), "sizeof + 16, zero tail");
    s = Shape();
    s.size = s01 - 1;
    expect_desc_refused(pack(d, s).as<rrc_context_desc>(), RRC_ERROR_INVALID_STRUCT, "desc.size");
    for (long nz : {(long)full, (long)big - 1}) {
        SCOPED_TRACE(nz);
        s = Shape();
        s.size = big;
        s.nonzero_at = nz;
        expect_desc_refused(pack(d, s).as<rrc_context_desc>(), RRC_ERROR_UNSUPPORTED, "desc", nz == full);
    }
    for (const ChainCase& cc : chain_cases()) {
        SCOPED_TRACE(cc.name);
        std::vector<ChainNode> nodes;
        rrc_context_desc e = d;
        e.next = cc.make(nodes);
        expect_desc_refused(&e, cc.code, std::string("desc.next") + cc.field_suffix, cc.code == RRC_ERROR_UNSUPPORTED);
    }
}

TEST(AbiChannelDesc, RulesOneToFour) {
    std::vector<rrc_channel_desc> channels = scene_channels();
    rrc_context_desc d = validated_desc(channels);
    const uint32_t s01 = (uint32_t)size01("rrc_channel_desc"), full = sizeof(rrc_channel_desc), big = full + 16;
    {
        Blob a = pack_array(channels, s01, {}, 0);
        d.channels = a.as<rrc_channel_desc>();
        expect_same_sequence(&d, "0.1 size, exact buffer");
    }
    {
        Blob a = pack_array(channels, big, {}, 0);
        d.channels = a.as<rrc_channel_desc>();
        expect_same_sequence(&d, "strided by sizeof + 16, zero tails");
    }
    // A caller of each earlier version: its channel descriptors end before the
    // first option of a later version (compute/rrc_channel_options.def), read as zero: off.
    const std::vector<ChannelRow> rows = channel_rows();
    for (size_t i = 1; i < rows.size(); ++i) {
        if (rows[i].version == rows[i - 1].version || rows[i - 1].version == RRC_MAKE_VERSION(0, 1, 0)) continue;
        Blob a = pack_array(channels, (uint32_t)rows[i].offset, {}, 0);
        d.channels = a.as<rrc_channel_desc>();
        const std::string what = std::string("a caller before ") + rows[i].member + ", exact buffer";
        expect_same_sequence(&d, what.c_str());
    }
    {
        Blob a = pack_array(channels, s01 - 1, {}, 0);
        d.channels = a.as<rrc_channel_desc>();
        expect_desc_refused(&d, RRC_ERROR_INVALID_STRUCT, "channels[0].size");
    }
    for (long nz : {(long)big + full, (long)2 * big - 1}) {
        SCOPED_TRACE(nz);
        Blob a = pack_array(channels, big, {}, 0, 0, nz);
        d.channels = a.as<rrc_channel_desc>();
        expect_desc_refused(&d, RRC_ERROR_UNSUPPORTED, "channels[1]", nz == (long)big + full);
    }
    {
        Blob a = pack_array(channels, big, {big, full}, 0);
        d.channels = a.as<rrc_channel_desc>();
        expect_desc_refused(&d, RRC_ERROR_INVALID_STRUCT, "channels[1].size");
        Blob b = pack_array(channels, full, {full, big}, 0);
        d.channels = b.as<rrc_channel_desc>();
        expect_desc_refused(&d, RRC_ERROR_INVALID_STRUCT, "channels[1].size", false);
    }
    for (const ChainCase& cc : chain_cases()) {
        SCOPED_TRACE(cc.name);
        std::vector<ChainNode> nodes;
        std::vector<rrc_channel_desc> c = channels;
        c[1].next = cc.make(nodes);
        d.channels = c.data();
        expect_desc_refused(&d, cc.code, std::string("channels[1].next") + cc.field_suffix, false);
    }
}

// ---- the Vulkan path ----------------------------------------------------------

struct VkResult {
    std::vector<float> a, b;
    std::vector<uint16_t> age_a, age_b;
    std::vector<uint8_t> mask;
    std::vector<unsigned char> stats;  // rrc_vulkan_frame_stats bytes
    bool stats_guard = true;
};

void upload_scene(VulkanRig& rig, int t) {
    SceneFrame s = scene_frame(t);
    rig.upload_depth(s.depth);
    rig.upload_reprojection(s.clip);
    rig.upload_nocache(s.nocache);
    rig.upload_samples(0, s.a);
    rig.upload_confidence(0, s.conf);
    rig.upload_samples(1, s.b);
    rig.fill_outputs();
}

VkResult read_back(VulkanRig& rig) {
    VkResult r;
    r.a = rig.values(0);
    r.b = rig.values(1);
    r.age_a = rig.age(0);
    r.age_b = rig.age(1);
    r.mask = rig.mask_bytes();
    rrc_vulkan_frame_stats st = rig.frame_stats();
    r.stats.assign((const unsigned char*)&st, (const unsigned char*)&st + sizeof st);
    r.stats_guard = rig.stats_guard_untouched();
    return r;
}

// Frames through the Vulkan path; `pass` may change how frame t is passed.
struct VkOutcome {
    rrc_result code;
    std::string message;
    uint64_t recorded = 0;
    VkResult result;
};

VkOutcome vk_frame(VulkanRig& rig, int t, const std::function<void(VkFrame&)>& spoil = {}) {
    upload_scene(rig, t);
    VkFrame f = rig.frame((uint64_t)t);
    VkOutcome o;
    o.code = rig.record(f, spoil, &o.recorded);
    o.message = rrc_last_error();
    o.result = read_back(rig);
    return o;
}

const std::vector<VkResult>& vk_reference(VulkanHost& host) {
    static std::vector<VkResult> ref;
    if (ref.empty()) {
        std::vector<rrc_channel_desc> channels = scene_channels();
        VulkanRig rig(host, scene_desc(channels));
        EXPECT_EQ(rig.create_result, RRC_SUCCESS) << rrc_last_error();
        for (int t = 0; t < kFrames; ++t) {
            VkOutcome o = vk_frame(rig, t);
            EXPECT_EQ(o.code, RRC_SUCCESS) << o.message;
            ref.push_back(o.result);
        }
        // The same frames as the standalone path, bit for bit (values, mask, ages, stats).
        for (int t = 0; t < kFrames; ++t) {
            EXPECT_EQ(ref[t].a, reference()[t].a) << t;
            EXPECT_EQ(ref[t].b, reference()[t].b) << t;
            EXPECT_EQ(ref[t].mask, reference()[t].mask) << t;
            EXPECT_EQ(ref[t].age_a, reference()[t].age_a) << t;
            rrc_vulkan_frame_stats st;
            std::memcpy(&st, ref[t].stats.data(), sizeof st);
            EXPECT_EQ(st.hits, reference()[t].stats.hits) << t;
            EXPECT_EQ(st.misses, reference()[t].stats.misses) << t;
            EXPECT_EQ(st.background, reference()[t].stats.background) << t;
            EXPECT_EQ(st.pixels, N) << t;
        }
    }
    return ref;
}

void expect_host_clean(VulkanHost& host) {
    host.shutdown();
    EXPECT_EQ(host.message_count(), 0u) << (host.messages().empty() ? "" : host.messages().front());
}

TEST(AbiVulkanDeviceDesc, RulesOneAndFour) {
    VulkanHost host;
    std::vector<rrc_channel_desc> channels = scene_channels();
    const rrc_context_desc cd = scene_desc(channels);
    const rrc_vulkan_device_desc dd = rrc_test::vkpath::device_desc(host);
    const uint32_t s01 = (uint32_t)size01("rrc_vulkan_device_desc"), full = sizeof dd, big = full + 16;
    auto create = [&](const rrc_vulkan_device_desc* d, rrc_context** out) { return rrc_vulkan_context_create(&cd, d, out); };
    for (uint32_t size : {s01, big}) {
        SCOPED_TRACE(size);
        Shape s;
        s.size = size;
        s.alloc = size == s01 ? s01 : 0;
        Blob b = pack(dd, s);
        rrc_context* ctx = nullptr;
        EXPECT_EQ(create(b.as<rrc_vulkan_device_desc>(), &ctx), RRC_SUCCESS) << rrc_last_error();
        rrc_context_destroy(ctx);
    }
    auto refused = [&](const rrc_vulkan_device_desc* d, rrc_result code, const std::string& field) {
        rrc_context* sentinel = reinterpret_cast<rrc_context*>(0x1234);
        rrc_context* out = sentinel;
        EXPECT_EQ(create(d, &out), code) << rrc_last_error();
        EXPECT_NE(std::string(rrc_last_error()).find(field), std::string::npos) << "must name " << field << ": " << rrc_last_error();
        EXPECT_EQ(out, sentinel);
    };
    {
        Shape s;
        s.size = s01 - 1;
        refused(pack(dd, s).as<rrc_vulkan_device_desc>(), RRC_ERROR_INVALID_STRUCT, "device.size");
    }
    for (long nz : {(long)full, (long)big - 1}) {
        Shape s;
        s.size = big;
        s.nonzero_at = nz;
        refused(pack(dd, s).as<rrc_vulkan_device_desc>(), RRC_ERROR_UNSUPPORTED, "device");
    }
    for (const ChainCase& cc : chain_cases()) {
        SCOPED_TRACE(cc.name);
        std::vector<ChainNode> nodes;
        rrc_vulkan_device_desc e = dd;
        e.next = cc.make(nodes);
        refused(&e, cc.code, std::string("device.next") + cc.field_suffix);
    }
    expect_host_clean(host);
}

// rrc_vulkan_frame_desc and rrc_vulkan_channel_images on one rig: accepted
// shapes match the plain reference frame for frame; refused ones record
// nothing and write nothing.
struct VkStruct {
    const char* name;
    const char* struct_name;
    const char* prefix;
    size_t full;
    bool array;
};

void PrintTo(const VkStruct& s, std::ostream* os) { *os << s.name; }

class VulkanFrameLevelStruct : public ::testing::TestWithParam<VkStruct> {};

TEST_P(VulkanFrameLevelStruct, RulesOneToFour) {
    const VkStruct& vs = GetParam();
    VulkanHost host;
    const std::vector<VkResult>& ref = vk_reference(host);
    std::vector<rrc_channel_desc> channels = scene_channels();
    std::vector<VkOutcome> outcomes;
    {
        VulkanRig rig(host, scene_desc(channels));
        ASSERT_EQ(rig.create_result, RRC_SUCCESS) << rrc_last_error();
        const uint32_t s01 = (uint32_t)size01(vs.struct_name), full = (uint32_t)vs.full, big = full + 16;
        std::vector<Blob> keep;  // the bytes passed, alive until the call
        // Passes the frame (or its channel array) with `shape`; for arrays
        // `sizes` overrides element sizes and nonzero_at is a byte of the array.
        auto passing = [&](Shape shape, std::vector<uint32_t> sizes = {}) {
            return [&, shape, sizes](VkFrame& f) {
                if (vs.array) {
                    keep.push_back(pack_array(f.channels, shape.size, sizes, 0, 0, shape.nonzero_at));
                    f.desc.channels = keep.back().as<rrc_vulkan_channel_images>();
                } else {
                    keep.push_back(pack(f.desc, shape));
                }
            };
        };
        // record() passes &f.desc: for the frame desc itself, a packed copy
        // replaces it through this wrapper.
        auto run = [&](int t, const std::function<void(VkFrame&)>& spoil) {
            upload_scene(rig, t);
            VkFrame f = rig.frame((uint64_t)t);
            VkOutcome o;
            VkCommandBuffer cmd = host.begin();
            f.desc.command_buffer = cmd;
            f.desc.channels = f.channels.data();
            keep.clear();
            if (spoil) spoil(f);
            const rrc_vulkan_frame_desc* passed = (!vs.array && !keep.empty()) ? keep.back().as<rrc_vulkan_frame_desc>() : &f.desc;
            const uint64_t before = rrc_test::vkpath::recorded_commands();
            o.code = rrc_vulkan_record_frame(rig.ctx, passed);
            o.message = rrc_last_error();
            o.recorded = rrc_test::vkpath::recorded_commands() - before;
            host.submit_and_wait(cmd);
            o.result = read_back(rig);
            return o;
        };
        int t = 0;
        auto accepted = [&](const std::function<void(VkFrame&)>& spoil, const char* what, bool no_age, bool no_stats) {
            SCOPED_TRACE(what);
            VkOutcome o = run(t, spoil);
            EXPECT_EQ(o.code, RRC_SUCCESS) << o.message;
            EXPECT_GT(o.recorded, 0u);
            EXPECT_EQ(o.result.a, ref[t].a);
            EXPECT_EQ(o.result.b, ref[t].b);
            EXPECT_EQ(o.result.mask, ref[t].mask);
            if (no_age) {  // a 0.1 caller's channel images have no age member: the age images stay as filled
                EXPECT_EQ(o.result.age_a, std::vector<uint16_t>(N, 777));
            } else {
                EXPECT_EQ(o.result.age_a, ref[t].age_a);
                EXPECT_EQ(o.result.age_b, ref[t].age_b);
            }
            if (no_stats)  // a 0.1 caller's frame has no stats_buffer: nothing written there
                EXPECT_EQ(o.result.stats, std::vector<unsigned char>(sizeof(rrc_vulkan_frame_stats), 0xEE));
            else
                EXPECT_EQ(o.result.stats, ref[t].stats);
            EXPECT_TRUE(o.result.stats_guard);
            ++t;
        };
        auto refused = [&](const std::function<void(VkFrame&)>& spoil, rrc_result code, const std::string& field) {
            VkOutcome o = run(t, spoil);
            EXPECT_EQ(o.code, code) << rrc_result_to_string(o.code) << ": " << o.message;
            EXPECT_NE(o.message.find(field), std::string::npos) << "must name " << field << ": " << o.message;
            EXPECT_EQ(o.recorded, 0u) << "a refused call recorded commands";
            EXPECT_EQ(o.result.a, std::vector<float>(N, -7.0f)) << "a refused call wrote outputs";
            EXPECT_EQ(o.result.mask, std::vector<uint8_t>(N, 0xEE));
            EXPECT_EQ(o.result.age_a, std::vector<uint16_t>(N, 777));
        };
        Shape s;
        accepted({}, "plain frame 0", false, false);
        s.size = s01;
        s.alloc = vs.array ? 0 : s01;
        accepted(passing(s), "0.1 size, exact buffer", vs.array, !vs.array);
        if (!vs.array) {  // 0.1 size with garbage where 0.2's members are: read as zero
            s.alloc = full;
            s.beyond = 0xA5;
            accepted(passing(s), "0.1 size, garbage beyond it", false, true);
        }
        s = Shape();
        s.size = big;
        accepted(passing(s), "sizeof + 16, zero tail", false, false);

        const std::string p = vs.prefix, elem = vs.array ? p + "[0]" : p, elem1 = vs.array ? p + "[1]" : p;
        s = Shape();
        s.size = s01 - 1;
        refused(passing(s), RRC_ERROR_INVALID_STRUCT, elem + ".size");
        for (long nz : {vs.array ? (long)big + full : (long)full, vs.array ? 2L * big - 1 : (long)big - 1}) {
            SCOPED_TRACE(nz);
            s = Shape();
            s.size = big;
            s.nonzero_at = nz;
            refused(passing(s), RRC_ERROR_UNSUPPORTED, elem1);
        }
        if (vs.array) {
            s = Shape();
            s.size = big;
            refused(passing(s, {big, full}), RRC_ERROR_INVALID_STRUCT, p + "[1].size");
        }
        for (const ChainCase& cc : chain_cases()) {
            SCOPED_TRACE(cc.name);
            std::vector<ChainNode> nodes;
            const void* head = cc.make(nodes);
            refused(
                [&](VkFrame& f) {
                    if (vs.array)
                        f.channels[1].next = head;
                    else
                        f.desc.next = head;
                },
                cc.code, elem1 + ".next" + cc.field_suffix);
        }
        for (; t < kFrames; ++t) {
            VkOutcome o = run(t, {});
            EXPECT_EQ(o.code, RRC_SUCCESS) << o.message;
            EXPECT_EQ(o.result.a, ref[t].a) << "frame " << t << " after the refused calls: history was touched";
            EXPECT_EQ(o.result.b, ref[t].b) << "frame " << t;
            EXPECT_EQ(o.result.age_a, ref[t].age_a) << "frame " << t;
        }
    }
    expect_host_clean(host);
}

INSTANTIATE_TEST_SUITE_P(Abi, VulkanFrameLevelStruct,
                         ::testing::Values(VkStruct{"vulkan_frame_desc", "rrc_vulkan_frame_desc", "frame", sizeof(rrc_vulkan_frame_desc),
                                                    false},
                                           VkStruct{"vulkan_channel_images", "rrc_vulkan_channel_images", "frame.channels",
                                                    sizeof(rrc_vulkan_channel_images), true}),
                         [](const ::testing::TestParamInfo<VkStruct>& i) { return std::string(i.param.name); });

}  // namespace
