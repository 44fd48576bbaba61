// libFuzzer target: the device-free argument validation of plugin/validation.cpp
// (what rrc_validate_context_desc, rrc_context_create and rrc_frame_run check
// before any Vulkan object exists).
//
// The bytes drive every field of a context descriptor and its channels, then
// (if the context is valid) of a frame and its output description and of a
// Vulkan frame and its channel images, then of an interop device descriptor.  Pointers are NULL or point at real memory sized
// exactly as the structs claim, so AddressSanitizer catches any read beyond
// what a count allows.  Validation must either accept or throw rrc::Error with
// a known code and a non-empty message; anything else aborts.
#include "config.h"
#include "error.h"
#include "frame.h"
#include "validation.h"

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace {

// Floats a validator must get right: specials, bounds, and anything at all.
float fuzz_float(FuzzedDataProvider& in) {
    static const float specials[] = {0.0f,
                                     -0.0f,
                                     1.0f,
                                     -1.0f,
                                     0.5f,
                                     0.999f,
                                     1e-7f,
                                     1e-40f,
                                     1e30f,
                                     65504.0f,
                                     std::numeric_limits<float>::max(),
                                     std::numeric_limits<float>::infinity(),
                                     -std::numeric_limits<float>::infinity(),
                                     std::numeric_limits<float>::quiet_NaN()};
    if (in.ConsumeBool()) return specials[in.ConsumeIntegralInRange<size_t>(0, sizeof specials / sizeof specials[0] - 1)];
    return in.ConsumeFloatingPoint<float>();
}

double fuzz_double(FuzzedDataProvider& in) {
    if (in.ConsumeBool()) return in.ConsumeBool() ? 0.0 : 1.0;
    return in.ConsumeFloatingPoint<double>();
}

// A struct tag: mostly the right one, sometimes anything.
uint32_t fuzz_tag(FuzzedDataProvider& in, uint32_t right) {
    return in.ConsumeIntegralInRange<int>(0, 7) ? right : in.ConsumeIntegral<uint32_t>();
}
// Never above `right` but for sizes above RRC_MAX_STRUCT_SIZE: under the
// struct rules (include/rrc/rrc.h, Versioning) a caller's size promises that
// many readable bytes, and these structs live in objects of exactly `right`
// bytes, so a size past the cap must be refused before anything past
// `right` is read (AddressSanitizer sees a read past it).  Larger sizes
// within the cap, with zero and non-zero tails, are tested by
// tests/abi/struct_size_test.cpp.
uint32_t fuzz_size(FuzzedDataProvider& in, uint32_t right) {
    if (in.ConsumeIntegralInRange<int>(0, 15) == 0) return in.ConsumeIntegralInRange<uint32_t>(RRC_MAX_STRUCT_SIZE + 1, 0xFFFFFFFFu);
    return in.ConsumeIntegralInRange<int>(0, 7) ? right - (in.ConsumeBool() ? 0u : in.ConsumeIntegralInRange<uint32_t>(0, 64) % (right + 1))
                                                : in.ConsumeIntegralInRange<uint32_t>(0, right);
}
// A small enum or count, now and then anything.
uint32_t fuzz_small(FuzzedDataProvider& in, uint32_t max) {
    return in.ConsumeIntegralInRange<int>(0, 7) ? in.ConsumeIntegralInRange<uint32_t>(0, max) : in.ConsumeIntegral<uint32_t>();
}

// `next` chains (rrc.h Versioning, rule 5): NULL mostly, else one of these
// extension headers: an unknown tag, a base struct's tag, a two-node cycle.
rrc_struct_header g_unknown{0x525243E7u, nullptr, sizeof(rrc_struct_header)};
rrc_struct_header g_base{RRC_STRUCT_TYPE_FRAME_DESC, nullptr, sizeof(rrc_struct_header)};
rrc_struct_header g_cycle_b{0x525243E1u, nullptr, sizeof(rrc_struct_header)};
rrc_struct_header g_cycle_a{0x525243E0u, &g_cycle_b, sizeof(rrc_struct_header)};
const void* fuzz_next(FuzzedDataProvider& in) {
    g_cycle_b.next = &g_cycle_a;
    const void* targets[] = {&g_unknown, &g_base, &g_cycle_a};
    return in.ConsumeIntegralInRange<int>(0, 15) ? nullptr : targets[in.ConsumeIntegralInRange<int>(0, 2)];
}

// s zeroed, then its header fuzzed: the tag (mostly `tag`), the size (mostly
// sizeof s) and the chain, in that order (the corpus's bytes depend on it).
template <typename T>
void fuzz_header(FuzzedDataProvider& in, T& s, uint32_t tag) {
    std::memset(&s, 0, sizeof s);
    s.type = fuzz_tag(in, tag);
    s.size = fuzz_size(in, sizeof s);
    s.next = fuzz_next(in);
}

// An array that holds exactly min(count, max) entries (plus one, so that an
// empty array is still memory), each with its header fuzzed, then `body(entry)`.
template <typename T, typename Body>
std::unique_ptr<T[]> fuzz_array(FuzzedDataProvider& in, uint32_t count, uint32_t max, uint32_t tag, Body body) {
    const uint32_t stored = std::min<uint32_t>(count, max);
    std::unique_ptr<T[]> a(new T[stored + 1]);
    for (uint32_t i = 0; i < stored; ++i) {
        fuzz_header(in, a[i], tag);
        body(a[i]);
    }
    return a;
}

void check_error(const rrc::Error& e) {
    const rrc_result known[] = {RRC_ERROR_INVALID_ARGUMENT, RRC_ERROR_INVALID_STRUCT, RRC_ERROR_INCOMPATIBLE_VERSION,
                                RRC_ERROR_UNSUPPORTED,      RRC_ERROR_MISSING_INPUT,  RRC_ERROR_SIZE_MISMATCH};
    bool ok = false;
    for (rrc_result r : known) ok |= e.code == r;
    if (!ok || std::strlen(e.what()) == 0) std::abort();
}

void fuzz_frame(FuzzedDataProvider& in, const rrc::ContextConfig& config) {
    const size_t n = 4;  // validation never reads pixel arrays: any real memory will do
    std::vector<float> depth(n), reprojection(4 * n), samples(4 * n), confidence(n), values(4 * n), weight(n);
    std::vector<uint8_t> nocache(n), mask(n);
    std::vector<uint16_t> age(n);

    rrc_frame_desc f;
    fuzz_header(in, f, RRC_STRUCT_TYPE_FRAME_DESC);
    f.frame_index = in.ConsumeIntegral<uint64_t>();
    f.reset = in.ConsumeIntegral<uint32_t>();
    f.depth = in.ConsumeIntegralInRange<int>(0, 7) ? depth.data() : nullptr;
    f.reprojection = in.ConsumeIntegralInRange<int>(0, 7) ? reprojection.data() : nullptr;
    for (int i = 0; i < 16; ++i) {
        f.view_proj[i] = i % 5 == 0 ? 1.0 : 0.0;  // identity unless the bytes say otherwise
        f.prev_view_proj[i] = i % 5 == 0 ? 1.0 : 0.0;
    }
    // A few entries changed (bounded: an exhausted provider returns the range's minimum forever).
    for (int k = 0, edits = in.ConsumeIntegralInRange<int>(0, 4); k < edits; ++k) {
        f.view_proj[in.ConsumeIntegralInRange<int>(0, 15)] = fuzz_double(in);
        f.prev_view_proj[in.ConsumeIntegralInRange<int>(0, 15)] = fuzz_double(in);
    }
    f.jitter[0] = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    f.jitter[1] = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    f.prev_jitter[0] = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    f.prev_jitter[1] = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    f.nocache = in.ConsumeBool() ? nocache.data() : nullptr;
    // channel_count may exceed the array: validation must compare it with the
    // context first.  The array holds min(count, 8) entries, exactly.
    f.channel_count = in.ConsumeBool() ? (uint32_t)config.channels.size() : fuzz_small(in, 8);
    auto inputs = fuzz_array<rrc_channel_input>(in, f.channel_count, 8, RRC_STRUCT_TYPE_CHANNEL_INPUT, [&](rrc_channel_input& c) {
        c.samples = in.ConsumeIntegralInRange<int>(0, 7) ? samples.data() : nullptr;
        c.confidence = in.ConsumeBool() ? confidence.data() : nullptr;
    });
    f.channels = f.channel_count && in.ConsumeIntegralInRange<int>(0, 7) ? inputs.get() : nullptr;

    rrc_frame_output o;
    fuzz_header(in, o, RRC_STRUCT_TYPE_FRAME_OUTPUT);
    o.mask = in.ConsumeBool() ? mask.data() : nullptr;
    o.channel_count = in.ConsumeBool() ? (uint32_t)config.channels.size() : fuzz_small(in, 8);
    auto outs = fuzz_array<rrc_channel_output>(in, o.channel_count, 8, RRC_STRUCT_TYPE_CHANNEL_OUTPUT, [&](rrc_channel_output& c) {
        c.values = in.ConsumeBool() ? values.data() : nullptr;
        c.age = in.ConsumeBool() ? age.data() : nullptr;
        c.weight = in.ConsumeBool() ? weight.data() : nullptr;
    });
    o.channels = o.channel_count && in.ConsumeIntegralInRange<int>(0, 7) ? outs.get() : nullptr;
    try {
        rrc::validate_frame(config, &f, in.ConsumeIntegralInRange<int>(0, 3) ? &o : nullptr);
    } catch (const rrc::Error& e) {
        check_error(e);
    }
}

// A Vulkan frame: handles from a pool of four (so that outputs meet inputs
// and each other), formats anything, the statistics' offset and stated size
// anything.  Validation reads no handle; it must refuse what would alias or
// write past the stated range, and accept nothing else it cannot check.
rrc_vulkan_image fuzz_image(FuzzedDataProvider& in) {
    rrc_vulkan_image img{};
    if (in.ConsumeIntegralInRange<int>(0, 3)) {
        img.image = reinterpret_cast<VkImage>(uintptr_t(0x1000 * in.ConsumeIntegralInRange<int>(1, 4)));
        img.view = reinterpret_cast<VkImageView>(uintptr_t(0x2000));
    }
    // Any value of the enumeration's range (0..VK_FORMAT_MAX_ENUM): outside it a C++ VkFormat does not exist.
    img.format = (VkFormat)(in.ConsumeBool() ? in.ConsumeIntegralInRange<int32_t>(0, 130) : in.ConsumeIntegralInRange<int32_t>(0, VK_FORMAT_MAX_ENUM));
    img.layout = (VkImageLayout)in.ConsumeIntegralInRange<int>(0, 8);
    return img;
}

void fuzz_vulkan_frame(FuzzedDataProvider& in, const rrc::ContextConfig& config) {
    rrc_vulkan_frame_desc f;
    fuzz_header(in, f, RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
    if (in.ConsumeIntegralInRange<int>(0, 7)) f.command_buffer = reinterpret_cast<VkCommandBuffer>(uintptr_t(0x3000));
    f.depth = fuzz_image(in);
    f.reprojection = fuzz_image(in);
    f.nocache = fuzz_image(in);
    f.mask = fuzz_image(in);
    f.object_id = fuzz_image(in);
    for (int i = 0; i < 16; ++i) f.view_proj[i] = f.prev_view_proj[i] = i % 5 == 0 ? 1.0 : 0.0;
    if (in.ConsumeBool()) f.stats_buffer = reinterpret_cast<VkBuffer>(uintptr_t(0x4000));
    f.stats_offset = in.ConsumeBool() ? 256 * in.ConsumeIntegralInRange<uint64_t>(0, 4) : in.ConsumeIntegral<uint64_t>();
    f.stats_buffer_size = in.ConsumeBool() ? 256 * in.ConsumeIntegralInRange<uint64_t>(0, 4) : in.ConsumeIntegral<uint64_t>();
    f.storage_inputs = in.ConsumeBool();
    f.split_outputs = in.ConsumeBool();
    f.channel_count = in.ConsumeBool() ? (uint32_t)config.channels.size() : fuzz_small(in, 8);
    auto images = fuzz_array<rrc_vulkan_channel_images>(in, f.channel_count, 8, RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES,
                                                        [&](rrc_vulkan_channel_images& c) {
                                                            c.samples = fuzz_image(in);
                                                            c.confidence = fuzz_image(in);
                                                            c.output = fuzz_image(in);
                                                            c.age = fuzz_image(in);
                                                            c.fallback = fuzz_image(in);
                                                        });
    f.channels = f.channel_count && in.ConsumeIntegralInRange<int>(0, 7) ? images.get() : nullptr;
    // Now and then the host's stated extents (rrc_vulkan_image_extents): pool images, mostly the context's size.
    rrc_vulkan_image_extents ext;
    std::vector<rrc_vulkan_image_extent> listed;
    if (!f.next && in.ConsumeIntegralInRange<int>(0, 3) == 0) {
        fuzz_header(in, ext, RRC_STRUCT_TYPE_EXT_VULKAN_IMAGE_EXTENTS);
        const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0, 6);
        for (uint32_t i = 0; i < n; ++i) {
            const VkImage image = reinterpret_cast<VkImage>(uintptr_t(0x1000 * in.ConsumeIntegralInRange<int>(1, 4)));
            const uint32_t w = in.ConsumeBool() ? config.width : fuzz_small(in, 64), h = in.ConsumeBool() ? config.height : fuzz_small(in, 64);
            listed.push_back({image, w, h});
        }
        ext.count = (uint32_t)listed.size();
        ext.images = listed.empty() ? nullptr : listed.data();
        f.next = &ext;
    }
    try {
        const rrc::Frame frame = rrc::read_frame(&f, config.channels.size());
        rrc::validate_frame(config, frame, nullptr, 256);
        // Accepted: what rrc writes lies within what the host stated, and no image it writes is one it reads.
        if (frame.stats_buffer && frame.stats_buffer_size &&
            (frame.stats_offset > frame.stats_buffer_size || frame.stats_buffer_size - frame.stats_offset < sizeof(rrc_vulkan_frame_stats)))
            std::abort();
        // Accepted with stated extents: the depth image (when bound) is listed, only at the context's size.
        if (frame.extents_given && frame.depth_image.image)
            for (const rrc_vulkan_image_extent& e : listed)
                if (e.image == frame.depth_image.image && (e.width != config.width || e.height != config.height)) std::abort();
        for (uint32_t i = 0; i < frame.channel_count; ++i) {
            const VkImage out = frame.channels[i].output_image.image;
            if (out && (out == frame.depth_image.image || out == frame.channels[i].samples_image.image || out == frame.mask_image.image))
                std::abort();
        }
    } catch (const rrc::Error& e) {
        check_error(e);
    }
}

void fuzz_vulkan_device(FuzzedDataProvider& in) {
    rrc_vulkan_device_desc d;
    fuzz_header(in, d, RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC);
    // Handles are opaque to validation: non-NULL values it must never use.
    if (in.ConsumeBool()) d.instance = reinterpret_cast<VkInstance>(uintptr_t(0x1000));
    if (in.ConsumeBool()) d.physical_device = reinterpret_cast<VkPhysicalDevice>(uintptr_t(0x2000));
    if (in.ConsumeBool()) d.device = reinterpret_cast<VkDevice>(uintptr_t(0x3000));
    if (in.ConsumeBool()) d.get_instance_proc_addr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(uintptr_t(0x4000));
    d.vulkan_api_version = in.ConsumeIntegral<uint32_t>();
    d.max_frames_in_flight = fuzz_small(in, 20);
    try {
        rrc::validate_vulkan_device_desc(&d);
    } catch (const rrc::Error& e) {
        check_error(e);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    rrc_context_desc d;
    fuzz_header(in, d, RRC_STRUCT_TYPE_CONTEXT_DESC);
    d.api_version = in.ConsumeIntegralInRange<int>(0, 7) ? RRC_API_VERSION : in.ConsumeIntegral<uint32_t>();
    d.width = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 64) : in.ConsumeIntegral<uint32_t>();
    d.height = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 64) : in.ConsumeIntegral<uint32_t>();
    d.depth_mode = fuzz_small(in, 3);
    d.near_plane = fuzz_float(in);
    d.far_plane = fuzz_float(in);
    d.background_threshold = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    d.depth_format = fuzz_small(in, 3);
    d.epsilon_scale = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    d.epsilon = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    d.tau = in.ConsumeBool() ? 0.0f : fuzz_float(in);
    d.reprojection = fuzz_small(in, 4);
    if (in.ConsumeBool()) {
        d.motion_scale[0] = fuzz_float(in);
        d.motion_scale[1] = fuzz_float(in);
    }
    // The channel array holds exactly min(count, RRC_MAX_CHANNELS + 2)
    // entries: a count beyond RRC_MAX_CHANNELS must be refused unread.
    d.channel_count = fuzz_small(in, RRC_MAX_CHANNELS + 2);
    auto channels = fuzz_array<rrc_channel_desc>(in, d.channel_count, RRC_MAX_CHANNELS + 2, RRC_STRUCT_TYPE_CHANNEL_DESC, [&](rrc_channel_desc& c) {
        if (in.ConsumeIntegralInRange<int>(0, 7)) {
            std::string name = in.ConsumeRandomLengthString(RRC_MAX_NAME - 1);
            std::memcpy(c.name, name.data(), name.size());  // NUL-terminated (zeroed), may hold NULs inside
        } else {
            for (char& ch : c.name) ch = (char)in.ConsumeIntegral<uint8_t>();  // possibly unterminated
        }
        c.components = fuzz_small(in, 5);
        c.precision = fuzz_small(in, 2);
        c.lambda = fuzz_float(in);
        c.blend = fuzz_small(in, 3);
        c.filter = fuzz_small(in, 3);
        c.age_cap = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 300) : in.ConsumeIntegral<uint32_t>();
        // Every other row of compute/rrc_channel_options.def, by its check: 0 often (off, or the default).
#define RRC_FUZZ_NONE(member)
#define RRC_FUZZ_BOOL(member) c.member = in.ConsumeIntegral<uint8_t>() % 3;
#define RRC_FUZZ_UINT(member) c.member = in.ConsumeBool() ? 0u : in.ConsumeBool() ? fuzz_small(in, 8) : in.ConsumeIntegral<uint32_t>();
#define RRC_FUZZ_FLOAT(member) c.member = in.ConsumeBool() ? 0.0f : fuzz_float(in);
#define RRC_FUZZ_BELOW(member) RRC_FUZZ_FLOAT(member)
#define RRC_CHANNEL_OPTION(member, ctype, check, ...) RRC_FUZZ_##check(member)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_FUZZ_BELOW
#undef RRC_FUZZ_FLOAT
#undef RRC_FUZZ_UINT
#undef RRC_FUZZ_BOOL
#undef RRC_FUZZ_NONE
    });
    d.channels = in.ConsumeIntegralInRange<int>(0, 15) ? channels.get() : nullptr;
    d.use_nocache_mask = in.ConsumeBool();
    std::string device = in.ConsumeRandomLengthString(32);
    d.device_name = in.ConsumeBool() ? device.c_str() : nullptr;
    d.enable_validation = in.ConsumeBool();

    rrc::ContextConfig config;
    bool valid = false;
    try {
        config = rrc::resolve_context_desc(&d);
        valid = true;
    } catch (const rrc::Error& e) {
        check_error(e);
    }
    if (valid) {
        // What was accepted must be within the documented limits.
        if (config.width == 0 || config.width > RRC_MAX_EXTENT || config.height == 0 || config.height > RRC_MAX_EXTENT ||
            config.channels.empty() || config.channels.size() > RRC_MAX_CHANNELS)
            std::abort();
        for (const rrc::ChannelConfig& c : config.channels)
            if (!(c.lambda >= 0.0f && c.lambda < 1.0f) || (c.components != 1 && c.components != 4) || c.age_cap == 0 ||
                c.age_cap > RRC_MAX_AGE_CAP || c.name.empty())
                std::abort();
        // Every checked row's resolved value is in its range (a finite, non-negative float).
#define RRC_FUZZ_CHECK_FLOAT(member) \
    for (const rrc::ChannelConfig& c : config.channels)                                         \
        if (!(std::isfinite(c.member) && c.member >= 0.0f)) std::abort();
#define RRC_FUZZ_CHECK_BELOW(member) RRC_FUZZ_CHECK_FLOAT(member)
#define RRC_FUZZ_CHECK_NONE(member)
#define RRC_FUZZ_CHECK_BOOL(member)
#define RRC_FUZZ_CHECK_UINT(member)
#define RRC_CHANNEL_OPTION(member, ctype, check, ...) RRC_FUZZ_CHECK_##check(member)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
        fuzz_frame(in, config);
        fuzz_vulkan_frame(in, config);
    }
    fuzz_vulkan_device(in);
    return 0;
}
