#include "validation.h"
#include "vk_requirements.h"

#include "error.h"
#include "struct_reader.h"
#include "vk_formats.h"
#include "vk_names.h"

#include <rrc/rrc_vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rrc {
namespace {

bool finite(float x) { return std::isfinite(x); }

// Determinant of a column-major 4x4 matrix (Laplace expansion by 2x2 minors).
double determinant4(const double m[16]) {
    auto a = [&](int row, int col) { return m[col * 4 + row]; };
    const double s0 = a(0, 0) * a(1, 1) - a(1, 0) * a(0, 1), s1 = a(0, 0) * a(1, 2) - a(1, 0) * a(0, 2);
    const double s2 = a(0, 0) * a(1, 3) - a(1, 0) * a(0, 3), s3 = a(0, 1) * a(1, 2) - a(1, 1) * a(0, 2);
    const double s4 = a(0, 1) * a(1, 3) - a(1, 1) * a(0, 3), s5 = a(0, 2) * a(1, 3) - a(1, 2) * a(0, 3);
    const double c5 = a(2, 2) * a(3, 3) - a(3, 2) * a(2, 3), c4 = a(2, 1) * a(3, 3) - a(3, 1) * a(2, 3);
    const double c3 = a(2, 1) * a(3, 2) - a(3, 1) * a(2, 2), c2 = a(2, 0) * a(3, 3) - a(3, 0) * a(2, 3);
    const double c1 = a(2, 0) * a(3, 2) - a(3, 0) * a(2, 2), c0 = a(2, 0) * a(3, 1) - a(3, 0) * a(2, 1);
    return s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0;
}

// The largest lambda_eff of docs/CONVENTIONS.md's blends, ages capped at age_cap.
double max_lambda_eff(const ChannelConfig& c) {
    const double capped_mean = c.age_cap / (c.age_cap + 1.0);
    if (c.blend == RRC_BLEND_RUNNING_MEAN) return capped_mean;
    if (c.blend == RRC_BLEND_AGE_AWARE) return std::min<double>(c.lambda, capped_mean);
    if (c.blend == RRC_BLEND_REUSE) return 0.0;  // never blends: fp16 cannot stall
    return c.lambda;
}

// One row of compute/rrc_channel_options.def, checked: the caller's value
// `raw` is in the row's range (the message names the member and the range),
// non-zero only where the row's `needs` holds and, for a row REFUSED to
// REUSE, only on an accumulating channel.  The caller then resolves it
// (0 becomes the row's default).  Rows checked NONE are checked by hand.
enum class Check { Bool, Uint, Float, Below };
enum class Reuse { ALLOWED, REFUSED };
template <typename T>
void check_option(const char* what, const char* member, T raw, Check check, double high, bool zero_default, bool needs,
                  const char* needs_text, Reuse reuse, bool reuse_blend) {
    const double v = (double)raw;
    const char* zero = zero_default ? " (0 = default)" : "";
    if (check == Check::Uint && v > high) fail(RRC_ERROR_INVALID_ARGUMENT, "%s.%s is %.0f, at most %.0f%s", what, member, v, high, zero);
    if ((check == Check::Float && !(v >= 0.0 && v <= high)) || (check == Check::Below && !(v >= 0.0 && v < high)))
        fail(RRC_ERROR_INVALID_ARGUMENT, "%s.%s is %g, must be in [0, %g%c%s", what, member, v, high, check == Check::Below ? ')' : ']',
             zero);
    if (raw != T{} && !needs) fail(RRC_ERROR_INVALID_ARGUMENT, "%s.%s is set but needs %s", what, member, needs_text);
    if (raw != T{} && reuse == Reuse::REFUSED && reuse_blend)
        fail(RRC_ERROR_INVALID_ARGUMENT,
             "%s has blend REUSE and %s: a shading cache keeps its values, it neither blends nor takes a sample on a hit", what,
             member);
}

// c: the caller's channel as read by read_array (struct rules already applied).
ChannelConfig resolve_channel(const rrc_channel_desc& c, uint32_t index) {
    char what[48];
    std::snprintf(what, sizeof what, "channels[%u]", index);
    ChannelConfig out;
    size_t len = strnlen(c.name, RRC_MAX_NAME);
    if (len == 0) fail(RRC_ERROR_INVALID_ARGUMENT, "%s.name is empty", what);
    if (len == RRC_MAX_NAME) fail(RRC_ERROR_INVALID_ARGUMENT, "%s.name is not NUL-terminated within %d bytes", what, RRC_MAX_NAME);
    out.name.assign(c.name, len);
    // The rows checked by hand (check NONE): sets and enumerations.
    if (c.components != 1 && c.components != 4) fail(RRC_ERROR_INVALID_ARGUMENT, "%s.components is %u, must be 1 or 4", what, c.components);
    out.components = c.components;
    if (c.precision != RRC_HISTORY_FP16 && c.precision != RRC_HISTORY_FP32)
        fail(RRC_ERROR_INVALID_ARGUMENT, "%s.precision is %u, not an rrc_history_precision", what, c.precision);
    out.precision = c.precision;
    if (c.blend > uint32_t{RRC_BLEND_REUSE}) fail(RRC_ERROR_INVALID_ARGUMENT, "%s.blend is %u, not an rrc_blend", what, c.blend);
    out.blend = c.blend;
    if (c.filter > uint32_t{RRC_HISTORY_FILTER_GAUSSIAN})
        fail(RRC_ERROR_INVALID_ARGUMENT, "%s.filter is %u, not an rrc_history_filter", what, c.filter);
    out.filter = c.filter;
    // Every other row, in row order: a row's range and needs may read the rows before it (`out`).
#define RRC_CHECK_NONE(member, ctype, dflt, high, needs, needs_text, rule)
#define RRC_CHECK_ROW(member, ctype, check, dflt, high, needs, needs_text, rule)                                                   \
    check_option(what, #member, c.member, Check::check, (double)(high), (double)(dflt) != 0.0, needs, needs_text, Reuse::rule, \
                 out.reuse());                                                                                                  \
    out.member = c.member == 0 ? dflt : (ctype)c.member;
#define RRC_CHECK_BOOL(member, ctype, dflt, high, needs, needs_text, rule) RRC_CHECK_ROW(member, ctype, Bool, dflt, high, needs, needs_text, rule)
#define RRC_CHECK_UINT(member, ctype, dflt, high, needs, needs_text, rule) RRC_CHECK_ROW(member, ctype, Uint, dflt, high, needs, needs_text, rule)
#define RRC_CHECK_FLOAT(member, ctype, dflt, high, needs, needs_text, rule) RRC_CHECK_ROW(member, ctype, Float, dflt, high, needs, needs_text, rule)
#define RRC_CHECK_BELOW(member, ctype, dflt, high, needs, needs_text, rule) RRC_CHECK_ROW(member, ctype, Below, dflt, high, needs, needs_text, rule)
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, rule, ...) \
    RRC_CHECK_##check(member, ctype, dflt, high, needs, needs_text, rule)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_CHECK_BELOW
#undef RRC_CHECK_FLOAT
#undef RRC_CHECK_UINT
#undef RRC_CHECK_BOOL
#undef RRC_CHECK_ROW
#undef RRC_CHECK_NONE
    // An fp16 history rounded to nearest stops moving once (1 - lambda)|s - H|
    // falls under half an ulp of H, and stalls up to 2^-11/(1 - lambda) of H
    // away from the signal: keep fp16 only while the largest lambda_eff the
    // channel can reach is at most RRC_FP16_MAX_LAMBDA (docs/CONVENTIONS.md).
    out.fp16 = out.precision == RRC_HISTORY_FP16 && max_lambda_eff(out) <= RRC_FP16_MAX_LAMBDA;
    return out;
}

// The shading cache's members (0.3; docs/CONVENTIONS.md, "Refresh policies").
void resolve_refresh(const rrc_context_desc& d, ContextConfig& c) {
    const bool reuse = c.reuse_mask() != 0;
    if (d.refresh_policy > uint32_t{RRC_REFRESH_RANDOM})
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_policy is %u, not an rrc_refresh_policy", d.refresh_policy);
    c.refresh_policy = d.refresh_policy;
    if (c.refresh_policy == RRC_REFRESH_NONE) {
        if (d.refresh_period != 0 || d.refresh_tiles[0] != 0 || d.refresh_tiles[1] != 0)
            fail(RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_period/refresh_tiles are set but refresh_policy is NONE");
    } else {
        if (!reuse) fail(RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_policy is set but no channel has blend REUSE: only REUSE channels refresh");
        if (d.refresh_period == 0 || d.refresh_period > RRC_MAX_REFRESH_PERIOD)
            fail(RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_period is %u, must be 1..%u with a refresh policy", d.refresh_period,
                 RRC_MAX_REFRESH_PERIOD);
        c.refresh_period = d.refresh_period;
        if (c.refresh_policy == RRC_REFRESH_TILED) {
            uint32_t gx = d.refresh_tiles[0], gy = d.refresh_tiles[1];
            if (gx == 0 && gy == 0) gx = c.refresh_period, gy = 1;
            if (gx == 0 || gy == 0 || gx > RRC_MAX_REFRESH_TILES || gy > RRC_MAX_REFRESH_TILES || (uint64_t)gx * gy != c.refresh_period)
                fail(RRC_ERROR_INVALID_ARGUMENT,
                     "desc.refresh_tiles is {%u, %u}: TILED needs gx * gy = refresh_period (%u), each 1..%u ({0, 0} = {n, 1})",
                     d.refresh_tiles[0], d.refresh_tiles[1], c.refresh_period, RRC_MAX_REFRESH_TILES);
            c.refresh_tiles[0] = gx;
            c.refresh_tiles[1] = gy;
        } else if (d.refresh_tiles[0] != 0 || d.refresh_tiles[1] != 0) {
            fail(RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_tiles is set but refresh_policy is not TILED");
        }
    }
    if (d.max_lifetime != 0) {
        if (!reuse) fail(RRC_ERROR_INVALID_ARGUMENT, "desc.max_lifetime is set but no channel has blend REUSE");
        for (size_t i = 0; i < c.channels.size(); ++i)
            if (c.channels[i].reuse() && d.max_lifetime > c.channels[i].age_cap)
                fail(RRC_ERROR_INVALID_ARGUMENT, "desc.max_lifetime is %u, above channels[%zu].age_cap %u: the age saturates there",
                     d.max_lifetime, i, c.channels[i].age_cap);
        c.max_lifetime = d.max_lifetime;
    }
}

}  // namespace

ContextConfig resolve_context_desc(const rrc_context_desc* caller) {
    const rrc_context_desc desc = read_struct<rrc_context_desc>(caller, "desc");
    const rrc_context_desc* d = &desc;
    if (RRC_VERSION_MAJOR(d->api_version) != RRC_VERSION_MAJOR(RRC_API_VERSION))
        fail(RRC_ERROR_INCOMPATIBLE_VERSION, "desc.api_version is %u.%u.%u, this library is %u.%u.%u (major versions must match)",
             RRC_VERSION_MAJOR(d->api_version), RRC_VERSION_MINOR(d->api_version), RRC_VERSION_PATCH(d->api_version),
             RRC_VERSION_MAJOR(RRC_API_VERSION), RRC_VERSION_MINOR(RRC_API_VERSION), RRC_VERSION_PATCH(RRC_API_VERSION));
    ContextConfig c;
    if (d->width == 0 || d->width > RRC_MAX_EXTENT)
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.width is %u, must be 1..%u", d->width, RRC_MAX_EXTENT);
    if (d->height == 0 || d->height > RRC_MAX_EXTENT)
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.height is %u, must be 1..%u", d->height, RRC_MAX_EXTENT);
    c.width = d->width;
    c.height = d->height;

    if (d->depth_mode > uint32_t{RRC_DEPTH_MODE_LINEAR})
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.depth_mode is %u, not an rrc_depth_mode", d->depth_mode);
    c.depth_mode = d->depth_mode;
    if (d->reprojection > uint32_t{RRC_REPROJECTION_CAMERA})
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.reprojection is %u, not an rrc_reprojection", d->reprojection);
    c.reprojection = d->reprojection;
    if (d->depth_format > uint32_t{RRC_DEPTH_FORMAT_UNORM24})
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.depth_format is %u, not an rrc_depth_format", d->depth_format);
    c.depth_format = d->depth_format;

    if (!(d->background_threshold >= 0.0f) || std::isinf(d->background_threshold))
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.background_threshold is %g, must be finite and >= 0 (0 = default 1e10)",
             (double)d->background_threshold);
    c.background_threshold = d->background_threshold == 0.0f ? RRC_DEFAULT_BACKGROUND_THRESHOLD : d->background_threshold;

    // Linearising NDC depth (plain MOTION) needs the planes.
    c.near_plane = d->near_plane;
    c.far_plane = d->far_plane;
    bool linearise = d->reprojection == RRC_REPROJECTION_MOTION && d->depth_mode != RRC_DEPTH_MODE_LINEAR;
    if (linearise) {
        if (!(finite(d->near_plane) && d->near_plane > 0.0f))
            fail(RRC_ERROR_INVALID_ARGUMENT, "desc.near_plane is %g: MOTION without a depth channel on NDC depth needs near > 0",
                 (double)d->near_plane);
        bool far_ok = d->far_plane > d->near_plane && (finite(d->far_plane) || d->depth_mode == RRC_DEPTH_MODE_REVERSED);
        if (!far_ok)
            fail(RRC_ERROR_INVALID_ARGUMENT, "desc.far_plane is %g: must exceed near_plane (+inf only with REVERSED depth)",
                 (double)d->far_plane);
    } else if (std::isnan(d->near_plane) || std::isnan(d->far_plane)) {
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.near_plane/far_plane is NaN");
    }

    if (!(d->epsilon_scale >= 0.0f) || std::isinf(d->epsilon_scale))
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.epsilon_scale is %g, must be finite and >= 0", (double)d->epsilon_scale);
    if (!(d->epsilon >= 0.0f) || std::isinf(d->epsilon))
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.epsilon is %g, must be finite and >= 0", (double)d->epsilon);
    if (!(d->tau >= 0.0f) || std::isinf(d->tau))
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.tau is %g, must be finite and >= 0", (double)d->tau);
    // docs/CONVENTIONS.md, "Which test": zero is ADAPTIVE for 0.2 callers that
    // set no tolerance, FIXED for 0.1 callers (their zero meant the paper's test).
    const bool tolerance_set = d->epsilon_scale != 0.0f || d->epsilon != 0.0f || d->tau != 0.0f;
    if (d->depth_test > uint32_t{RRC_DEPTH_TEST_FIXED})
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.depth_test is %u, not an rrc_depth_test", d->depth_test);
    if (d->depth_test == RRC_DEPTH_TEST_ADAPTIVE && tolerance_set)
        fail(RRC_ERROR_INVALID_ARGUMENT,
             "desc.depth_test is ADAPTIVE but epsilon_scale/epsilon/tau is set: a host tolerance selects the FIXED test");
    if (d->depth_test == RRC_DEPTH_TEST_DEFAULT)
        c.depth_test = d->api_version >= RRC_MAKE_VERSION(0, 2, 0) && !tolerance_set ? RRC_DEPTH_TEST_ADAPTIVE : RRC_DEPTH_TEST_FIXED;
    else
        c.depth_test = d->depth_test;
    if (d->depth_mode == RRC_DEPTH_MODE_LINEAR || linearise) {
        c.epsilon_kind = EpsilonKind::Relative;
        c.epsilon_value = d->tau == 0.0f ? RRC_DEFAULT_TAU : d->tau;
    } else if (d->epsilon > 0.0f) {
        c.epsilon_kind = EpsilonKind::Absolute;
        c.epsilon_value = d->epsilon;
    } else if (d->depth_format == RRC_DEPTH_FORMAT_FLOAT32) {
        c.epsilon_kind = EpsilonKind::Ulp;
        c.epsilon_value = d->epsilon_scale == 0.0f ? RRC_DEFAULT_EPSILON_SCALE_FLOAT32 : d->epsilon_scale;
    } else {
        double step = d->depth_format == RRC_DEPTH_FORMAT_UNORM16 ? 1.0 / 65535.0 : 1.0 / 16777215.0;
        c.epsilon_kind = EpsilonKind::Absolute;
        c.epsilon_value = (float)((double)(d->epsilon_scale == 0.0f ? RRC_DEFAULT_EPSILON_SCALE_UNORM : d->epsilon_scale) * step);
    }

    if (d->motion_scale[0] == 0.0f && d->motion_scale[1] == 0.0f) {
        c.motion_scale = {1.0f, 1.0f};
    } else {
        if (!finite(d->motion_scale[0]) || !finite(d->motion_scale[1])) fail(RRC_ERROR_INVALID_ARGUMENT, "desc.motion_scale is not finite");
        c.motion_scale = {d->motion_scale[0], d->motion_scale[1]};
    }

    if (d->channel_count == 0 || d->channel_count > RRC_MAX_CHANNELS)
        fail(RRC_ERROR_INVALID_ARGUMENT, "desc.channel_count is %u, must be 1..%d", d->channel_count, RRC_MAX_CHANNELS);
    if (!d->channels) fail(RRC_ERROR_INVALID_ARGUMENT, "desc.channels is NULL");
    const std::vector<rrc_channel_desc> channels = read_array<rrc_channel_desc>(d->channels, d->channel_count, "channels");
    for (uint32_t i = 0; i < d->channel_count; ++i) {
        c.channels.push_back(resolve_channel(channels[i], i));
        for (uint32_t k = 0; k < i; ++k)
            if (c.channels[k].name == c.channels[i].name)
                fail(RRC_ERROR_INVALID_ARGUMENT, "channels[%u].name \"%s\" repeats channels[%u].name", i, c.channels[i].name.c_str(), k);
    }
    c.use_nocache = d->use_nocache_mask != 0;
    c.use_object_id = d->use_object_id != 0;
    c.adaptive =
        c.depth_test == RRC_DEPTH_TEST_ADAPTIVE && c.reprojection != RRC_REPROJECTION_MOTION;  // plain MOTION: no exact expected depth
    resolve_refresh(*d, c);
    if (d->view_count > RRC_MAX_VIEWS) fail(RRC_ERROR_INVALID_ARGUMENT, "desc.view_count is %u, at most %u", d->view_count, RRC_MAX_VIEWS);
    c.view_count = d->view_count == 0 ? 1 : d->view_count;
    if (d->device_name) c.device_name = d->device_name;
    c.validation = d->enable_validation != 0;
    c.log = d->log;
    c.log_user = d->log_user;
    return c;
}

namespace {

const char* source_name(rrc_reprojection r) {
    return r == RRC_REPROJECTION_PREV_CLIP ? "PREV_CLIP" : r == RRC_REPROJECTION_MOTION ? "MOTION" : "MOTION_DEPTH";
}

// The depth-format rule of docs/guide/integration.md: a depth/stencil image holds
// NDC depth in exactly the encoding the context's epsilon is built for; a
// colour image carries depth in .r and its precision is the host's choice.
void check_depth_image_format(const ContextConfig& c, VkFormat f) {
    if (!is_depth_format(f)) {
        // Depth in a colour image: its .r, read through a float sampler.
        if (f == VK_FORMAT_UNDEFINED || is_integer_format(f))
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.depth.format is %s: depth is a depth format or a float or normalised colour format",
                 format_name(f).c_str());
        return;
    }
    if (c.depth_mode == RRC_DEPTH_MODE_LINEAR)
        fail(RRC_ERROR_INVALID_ARGUMENT,
             "frame.depth.format is %s, a depth/stencil format, but LINEAR depth is view depth in a colour image", format_name(f).c_str());
    const bool is_float = f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
    const bool is_unorm16 = f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D16_UNORM_S8_UINT;
    const rrc_depth_format expected = is_float     ? RRC_DEPTH_FORMAT_FLOAT32
                                      : is_unorm16 ? RRC_DEPTH_FORMAT_UNORM16
                                                   : RRC_DEPTH_FORMAT_UNORM24;
    if (c.depth_format != expected)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.depth.format is %s (%s) but the context's depth_format is %u: epsilon would be wrong",
             format_name(f).c_str(),
             is_float     ? "FLOAT32"
             : is_unorm16 ? "UNORM16"
                          : "UNORM24",
             (unsigned)c.depth_format);
}

// storage_inputs: each input image in the one format the kernel's storage
// binding for it declares (rrc_vulkan.h).  Checked after every input is known present.
void check_storage_format(const rrc_vulkan_image& img, VkFormat want, const std::string& what) {
    if (img.image && img.format != want)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.format is %s; with storage_inputs it must be %s", what.c_str(),
             format_name(img.format).c_str(), format_name(want).c_str());
}
void check_storage_input_formats(const ContextConfig& c, const Frame& f) {
    check_storage_format(f.depth_image, VK_FORMAT_R32_SFLOAT, "depth");
    if (c.reprojection != RRC_REPROJECTION_CAMERA) check_storage_format(f.reprojection_image, VK_FORMAT_R32G32B32A32_SFLOAT, "reprojection");
    if (c.use_nocache) check_storage_format(f.nocache_image, VK_FORMAT_R8_UINT, "nocache");
    for (uint32_t i = 0; i < f.channel_count && i < c.channels.size(); ++i) {
        const std::string what = "channels[" + std::to_string(i) + "]";
        check_storage_format(f.channels[i].samples_image, c.channels[i].components == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT,
                             what + ".samples");
        if (c.channels[i].confidence) check_storage_format(f.channels[i].confidence_image, VK_FORMAT_R32_SFLOAT, what + ".confidence");
    }
}

// One input is present: a CPU array, or a host image with image and view.
template <typename P>
void need(const Frame& f, const P* array, const rrc_vulkan_image& image, rrc_result code, const std::string& what, const std::string& why) {
    if (f.path == FramePath::Standalone) {
        if (!array) fail(code, "frame.%s is NULL%s", what.c_str(), why.c_str());
    } else if (!image.image || !image.view) {
        fail(code, "frame.%s.image/view is VK_NULL_HANDLE%s", what.c_str(), why.c_str());
    }
}

// The images a Vulkan frame names, by member: what rrc reads, what it writes.
// Images not given are VK_NULL_HANDLE.
struct NamedImage {
    VkImage image;
    std::string what;
};
struct FrameImages {
    std::vector<NamedImage> reads, writes;
};
FrameImages frame_images(const Frame& f) {
    FrameImages m;
    m.reads = {{f.depth_image.image, "depth"}, {f.reprojection_image.image, "reprojection"}, {f.nocache_image.image, "nocache"},
               {f.object_id_image.image, "object_id"}};
    m.writes = {{f.mask_image.image, "mask"}};
    for (uint32_t i = 0; i < RRC_MAX_CHANNELS; ++i) {
        const FrameChannel& ch = f.channels[i];
        const std::string c = "channels[" + std::to_string(i) + "].";
        m.reads.push_back({ch.samples_image.image, c + "samples"});
        m.reads.push_back({ch.confidence_image.image, c + "confidence"});
        m.reads.push_back({ch.fallback_image.image, c + "fallback"});
        m.writes.push_back({ch.output_image.image, c + "output"});
        m.writes.push_back({ch.age_image.image, c + "age"});
    }
    return m;
}

// Every image rrc writes (the outputs, ages and the mask) is none of the
// images it reads and no other it writes: a shared VkImage would be
// overwritten while it is read, or written twice (docs/guide/integration.md, "What
// rrc checks and what it cannot").
void check_distinct_images(const FrameImages& m) {
    const std::vector<NamedImage>&reads = m.reads, &writes = m.writes;
    for (size_t w = 0; w < writes.size(); ++w) {
        if (!writes[w].image) continue;
        for (const NamedImage& r : reads)
            if (r.image == writes[w].image)
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.image is frame.%s.image: rrc would overwrite an input it reads",
                     writes[w].what.c_str(), r.what.c_str());
        for (size_t o = 0; o < w; ++o)
            if (writes[o].image == writes[w].image)
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.image is frame.%s.image: two outputs in one image", writes[w].what.c_str(),
                     writes[o].what.c_str());
    }
}

// The host's stated extents (rrc_vulkan_image_extents, rrc_vulkan.h): every
// image the frame binds is listed once (or twice alike) and is the context's size.
void check_extents(const ContextConfig& c, const Frame& f, const FrameImages& m) {
    if (!f.extents_given) return;
    for (const std::vector<NamedImage>* list : {&m.reads, &m.writes})
        for (const NamedImage& n : *list) {
            if (!n.image) continue;
            const rrc_vulkan_image_extent* found = nullptr;
            for (const rrc_vulkan_image_extent& e : f.extents) {
                if (e.image != n.image) continue;
                if (found && (found->width != e.width || found->height != e.height))
                    fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.image is listed twice in rrc_vulkan_image_extents, as %ux%u and %ux%u",
                         n.what.c_str(), found->width, found->height, e.width, e.height);
                found = &e;
            }
            if (!found)
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.image is not listed in the frame's rrc_vulkan_image_extents (frame.next)",
                     n.what.c_str());
            if (found->width != c.width || found->height != c.height)
                fail(RRC_ERROR_SIZE_MISMATCH, "frame.%s.image is %ux%u (rrc_vulkan_image_extents), the context is %ux%u", n.what.c_str(),
                     found->width, found->height, c.width, c.height);
        }
}

}  // namespace

// A host buffer's range: `bytes` written at `offset` lie within the size it states.
void check_range(const char* offset_name, uint64_t offset, uint64_t bytes, const char* size_name, uint64_t size, const char* what) {
    if (offset > size || size - offset < bytes)
        fail(RRC_ERROR_SIZE_MISMATCH, "%s is %llu and %s %llu: the %llu bytes of %s written there would end past the buffer", offset_name,
             (unsigned long long)offset, size_name, (unsigned long long)size, (unsigned long long)bytes, what);
}

void validate_geometry(const ContextConfig& c, const Frame& f, uint64_t stats_alignment) {
    const bool vulkan = f.path == FramePath::Vulkan;
    if (f.view >= c.view_count) fail(RRC_ERROR_INVALID_ARGUMENT, "frame.view is %u, the context has %u view(s)", f.view, c.view_count);
    if (f.reproject_from > c.view_count)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.reproject_from is %u: 0 (its own view) or 1..%u (view + 1)", f.reproject_from, c.view_count);
    if (vulkan && !f.command_buffer) fail(RRC_ERROR_INVALID_ARGUMENT, "frame.command_buffer is VK_NULL_HANDLE");
    need(f, f.depth, f.depth_image, RRC_ERROR_MISSING_INPUT, "depth", "");
    if (vulkan) check_depth_image_format(c, f.depth_image.format);
    if (c.reprojection != RRC_REPROJECTION_CAMERA)
        need(f, f.reprojection, f.reprojection_image, RRC_ERROR_MISSING_INPUT, "reprojection",
             std::string(" but the context reprojects from ") + source_name(c.reprojection));
    if (c.reprojection == RRC_REPROJECTION_CAMERA) {
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(f.view_proj[i]) || !std::isfinite(f.prev_view_proj[i]))
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.view_proj/prev_view_proj[%d] is not finite", i);
    }
    if (c.view_lobe()) {
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(f.view_proj[i]))
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.view_proj[%d] is not finite (a channel has a view_lobe)", i);
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(f.camera_position[i]) || !std::isfinite(f.prev_camera_position[i]))
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.camera_position/prev_camera_position[%d] is not finite (a channel has a view_lobe)", i);
    }
    // The lighting's turn (0.8) adds to every view lobe's view turn: an angle like the lobe.
    if (!(f.lighting_turn >= 0.0f && f.lighting_turn <= RRC_MAX_VIEW_LOBE))
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.lighting_turn %g is not in [0, RRC_MAX_VIEW_LOBE] radians", (double)f.lighting_turn);
    if (f.lighting_turn != 0.0f && !c.view_lobe())
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.lighting_turn is %g but no channel has a view_lobe to apply it to", (double)f.lighting_turn);
    if (c.reprojection == RRC_REPROJECTION_CAMERA || c.view_lobe()) {
        // The library inverts view_proj (frame_constants.cpp): a singular one
        // would turn every pixel into NaN silently.
        const double det = determinant4(f.view_proj);
        if (!(std::fabs(det) > 0.0) || !std::isfinite(det))
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.view_proj is singular (determinant %g): %s inverts it", det,
                 c.reprojection == RRC_REPROJECTION_CAMERA ? "CAMERA reprojection" : "the view lobe");
    }
    for (int i = 0; i < 2; ++i)
        if (!finite(f.jitter[i]) || !finite(f.prev_jitter[i]) || std::fabs(f.jitter[i]) > 1.0f || std::fabs(f.prev_jitter[i]) > 1.0f)
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.jitter/prev_jitter[%d] must be finite and within [-1, 1] pixels", i);
    if (c.use_nocache)
        need(f, f.nocache, f.nocache_image, RRC_ERROR_MISSING_INPUT, "nocache", " but the context was created with use_nocache_mask");
    if (c.use_object_id) {
        need(f, f.object_id, f.object_id_image, RRC_ERROR_MISSING_INPUT, "object_id", " but the context was created with use_object_id");
        const VkFormat idf = f.object_id_image.format;
        if (vulkan && idf != VK_FORMAT_R16_UINT && idf != VK_FORMAT_R32_UINT)
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.object_id.format is %s, must be %s or %s", format_name(idf).c_str(),
                 format_name(VK_FORMAT_R16_UINT).c_str(), format_name(VK_FORMAT_R32_UINT).c_str());
    }
    // The channels' storage formats too (classify takes resolve's descriptor), before their other checks.
    if (vulkan && f.storage_inputs) check_storage_input_formats(c, f);
    if (vulkan && f.mask_image.image && !f.mask_image.view)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.mask.view is VK_NULL_HANDLE with an image");
    if (vulkan && f.mask_image.image && f.mask_image.format != VK_FORMAT_R8_UINT)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.mask.format is %s, must be %s", format_name(f.mask_image.format).c_str(),
             format_name(VK_FORMAT_R8_UINT).c_str());
    if (vulkan && f.count_io && !f.stats_buffer)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.count_io is set but frame.stats_buffer is VK_NULL_HANDLE: the counts follow the statistics");
    if (vulkan && f.stats_buffer && f.stats_buffer_size)
        check_range("frame.stats_offset", f.stats_offset, sizeof(rrc_vulkan_frame_stats) + (f.count_io ? sizeof(rrc_vulkan_io_counts) : 0),
                    "frame.stats_buffer_size", f.stats_buffer_size,
                    f.count_io ? "rrc_vulkan_frame_stats and rrc_vulkan_io_counts" : "rrc_vulkan_frame_stats");
    if (vulkan) {
        const FrameImages images = frame_images(f);
        check_distinct_images(images);
        check_extents(c, f, images);
    }
    if (vulkan && f.stats_buffer && stats_alignment && f.stats_offset % stats_alignment != 0)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.stats_offset is %llu, not a multiple of the device's minStorageBufferOffsetAlignment %llu",
             (unsigned long long)f.stats_offset, (unsigned long long)stats_alignment);
}

void validate_channels(const ContextConfig& c, const Frame& f) {
    const bool vulkan = f.path == FramePath::Vulkan;
    if (f.channel_count != c.channels.size())
        fail(RRC_ERROR_SIZE_MISMATCH, "frame.channel_count is %u, the context has %zu channels", f.channel_count, c.channels.size());
    if (!f.channels_given) fail(RRC_ERROR_MISSING_INPUT, "frame.channels is NULL");
    for (uint32_t i = 0; i < f.channel_count; ++i) {
        const FrameChannel& ch = f.channels[i];
        const std::string what = "channels[" + std::to_string(i) + "]";
        const std::string name = " (channel \"" + c.channels[i].name + "\")";
        need(f, ch.samples, ch.samples_image, RRC_ERROR_MISSING_INPUT, what + ".samples", name);
        if (c.channels[i].confidence)
            need(f, ch.confidence, ch.confidence_image, RRC_ERROR_MISSING_INPUT, what + ".confidence",
                 " but channel \"" + c.channels[i].name + "\" has confidence");
        if (c.channels[i].fallback())
            need(f, ch.fallback, ch.fallback_image, RRC_ERROR_MISSING_INPUT, what + ".fallback",
                 " but channel \"" + c.channels[i].name + (c.channels[i].residual ? "\" has residual (the fallback is its base)" : "\" has fill_prior > 0"));
        if (vulkan) need(f, (const float*)nullptr, ch.output_image, RRC_ERROR_MISSING_INPUT, what + ".output", name);
        if (vulkan && !is_float_format(ch.output_image.format))
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.output.format is %s: the accumulated value needs a float format (rrc_vulkan.h)",
                 what.c_str(), format_name(ch.output_image.format).c_str());
        if (vulkan && ch.age_image.image && ch.age_image.format != VK_FORMAT_R16_UINT)
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.age.format is %s, must be %s", what.c_str(), format_name(ch.age_image.format).c_str(),
                 format_name(VK_FORMAT_R16_UINT).c_str());
        if (vulkan && ch.age_image.image && !ch.age_image.view)
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.%s.age.view is VK_NULL_HANDLE with an image", what.c_str());
    }
}

void validate_outputs(const ContextConfig& c, const FrameOutputs* out) {
    if (!out || !out->caller) return;
    if (out->channel_count != 0 && out->channel_count != c.channels.size())
        fail(RRC_ERROR_SIZE_MISMATCH, "output.channel_count is %u, must be 0 or the context's %zu", out->channel_count, c.channels.size());
    for (uint32_t i = 0; i < out->channel_count; ++i)
        if (out->channels[i].weight && !c.channels[i].confidence)
            fail(RRC_ERROR_INVALID_ARGUMENT, "output.channels[%u].weight is set but channel \"%s\" has no confidence", i,
                 c.channels[i].name.c_str());
}

void validate_frame(const ContextConfig& c, const Frame& f, const FrameOutputs* out, uint64_t stats_alignment) {
    validate_geometry(c, f, stats_alignment);
    validate_channels(c, f);
    validate_outputs(c, out);
}

void validate_frame(const ContextConfig& c, const rrc_frame_desc* frame, rrc_frame_output* output) {
    const Frame f = read_frame(frame, c.channels.size());
    const FrameOutputs out = read_outputs(output, c.channels.size());
    validate_frame(c, f, &out, 0);
}

}  // namespace rrc

namespace rrc {

rrc_vulkan_device_desc validate_vulkan_device_desc(const rrc_vulkan_device_desc* caller) {
    const rrc_vulkan_device_desc desc = read_struct<rrc_vulkan_device_desc>(caller, "device");
    const rrc_vulkan_device_desc* d = &desc;
    if (!d->instance) fail(RRC_ERROR_INVALID_ARGUMENT, "device.instance is VK_NULL_HANDLE");
    if (!d->physical_device) fail(RRC_ERROR_INVALID_ARGUMENT, "device.physical_device is VK_NULL_HANDLE");
    if (!d->device) fail(RRC_ERROR_INVALID_ARGUMENT, "device.device is VK_NULL_HANDLE");
    if (!d->get_instance_proc_addr) fail(RRC_ERROR_INVALID_ARGUMENT, "device.get_instance_proc_addr is NULL");
    if (d->vulkan_api_version < VK_API_VERSION_1_1)
        fail(RRC_ERROR_UNSUPPORTED, "device.vulkan_api_version is %u.%u, rrc needs Vulkan 1.1", VK_API_VERSION_MAJOR(d->vulkan_api_version),
             VK_API_VERSION_MINOR(d->vulkan_api_version));
    if (d->max_frames_in_flight > 16)
        fail(RRC_ERROR_INVALID_ARGUMENT, "device.max_frames_in_flight is %u, at most 16", d->max_frames_in_flight);
    if (d->enabled_features) check_enabled_features(*d->enabled_features, "device.enabled_features");
    return desc;
}

}  // namespace rrc
