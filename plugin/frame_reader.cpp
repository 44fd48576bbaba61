// The two public frame descriptors into one Frame record.  Only the struct
// rules are applied here (struct_reader.h); what the values mean is checked
// once, for both paths, by validate_frame (validation.cpp).
#include "frame.h"
#include "struct_reader.h"

#include <tuple>

namespace rrc {
namespace {

// The descriptor by the struct rules, and the fields both descriptors
// share, by name.
template <typename D>
Frame read_common(const D* caller, FramePath path, D& d) {
    d = read_struct<D>(caller, "frame");
    Frame f;
    f.path = path;
    f.frame_index = d.frame_index;
    f.reset = d.reset != 0;
    std::memcpy(f.view_proj, d.view_proj, sizeof f.view_proj);
    std::memcpy(f.prev_view_proj, d.prev_view_proj, sizeof f.prev_view_proj);
    std::memcpy(f.camera_position, d.camera_position, sizeof f.camera_position);
    std::memcpy(f.prev_camera_position, d.prev_camera_position, sizeof f.prev_camera_position);
    f.lighting_turn = d.lighting_turn;
    std::memcpy(f.jitter, d.jitter, sizeof f.jitter);
    std::memcpy(f.prev_jitter, d.prev_jitter, sizeof f.prev_jitter);
    f.channel_count = d.channel_count;
    f.channels_given = d.channels != nullptr;
    f.view = d.view;
    f.reproject_from = d.reproject_from;
    return f;
}

// The channel array is read only when its count is the context's (else
// validate_frame reports the mismatch) and it is given.
bool channels_readable(const Frame& f, size_t context_channels) {
    return f.channels_given && f.channel_count == context_channels && f.channel_count <= RRC_MAX_CHANNELS;
}

// The channel array, element by element through `assign(FrameChannel&, const C&)`.
template <typename C, typename D, typename Assign>
void read_channels(Frame& f, const D& d, size_t context_channels, Assign assign) {
    if (!channels_readable(f, context_channels)) return;
    const std::vector<C> channels = read_array<C>(d.channels, d.channel_count, "frame.channels");
    for (uint32_t i = 0; i < d.channel_count; ++i) assign(f.channels[i], channels[i]);
}

}  // namespace

Frame read_frame(const rrc_frame_desc* caller, size_t context_channels) {
    rrc_frame_desc d;
    Frame f = read_common(caller, FramePath::Standalone, d);
    std::tie(f.depth, f.reprojection, f.nocache, f.object_id) = std::tie(d.depth, d.reprojection, d.nocache, d.object_id);
    read_channels<rrc_channel_input>(f, d, context_channels, [](FrameChannel& to, const rrc_channel_input& from) {
        to.samples = from.samples;
        to.confidence = from.confidence;
        to.fallback = from.fallback;
    });
    return f;
}

Frame read_frame(const rrc_vulkan_frame_desc* caller, size_t context_channels) {
    rrc_vulkan_frame_desc d;
    Frame f = read_common(caller, FramePath::Vulkan, d);
    std::tie(f.command_buffer, f.stats_buffer, f.stats_offset, f.stats_buffer_size) =
        std::tie(d.command_buffer, d.stats_buffer, d.stats_offset, d.stats_buffer_size);
    f.storage_inputs = d.storage_inputs != 0;
    f.split_outputs = d.split_outputs != 0;
    f.count_io = d.count_io != 0;
    rrc_vulkan_image_extents e;
    if ((f.extents_given = find_extension(d.next, "frame.next (rrc_vulkan_image_extents)", e))) {
        if (e.count == 0 || e.count > RRC_MAX_IMAGE_EXTENTS)
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.next (rrc_vulkan_image_extents).count is %u, must be 1..%u", e.count,
                 RRC_MAX_IMAGE_EXTENTS);
        if (!e.images) fail(RRC_ERROR_INVALID_ARGUMENT, "frame.next (rrc_vulkan_image_extents).images is NULL");
        f.extents.assign(e.images, e.images + e.count);
    }
    std::tie(f.depth_image, f.reprojection_image, f.nocache_image, f.mask_image, f.object_id_image) =
        std::tie(d.depth, d.reprojection, d.nocache, d.mask, d.object_id);
    read_channels<rrc_vulkan_channel_images>(f, d, context_channels, [](FrameChannel& to, const rrc_vulkan_channel_images& from) {
        to.samples_image = from.samples;
        to.confidence_image = from.confidence;
        to.output_image = from.output;
        to.age_image = from.age;
        to.fallback_image = from.fallback;
    });
    return f;
}

Frame read_resolve(const rrc_resolve_desc* caller, size_t context_channels) {
    const rrc_resolve_desc d = read_struct<rrc_resolve_desc>(caller, "resolve");
    Frame f;
    f.channel_count = d.channel_count;
    f.channels_given = d.channels != nullptr;
    read_channels<rrc_channel_input>(f, d, context_channels, [](FrameChannel& to, const rrc_channel_input& from) {
        to.samples = from.samples;
        to.confidence = from.confidence;
        to.fallback = from.fallback;
    });
    return f;
}

FrameOutputs read_outputs(rrc_frame_output* caller, size_t context_channels) {
    FrameOutputs out;
    if (!caller) return out;
    const rrc_frame_output o = read_struct<rrc_frame_output>(caller, "output");
    out.caller = caller;
    out.mask = o.mask;
    out.channel_count = o.channel_count;
    if (o.channel_count && !o.channels) fail(RRC_ERROR_INVALID_ARGUMENT, "output.channels is NULL with channel_count %u", o.channel_count);
    if (o.channel_count == context_channels && o.channel_count <= RRC_MAX_CHANNELS) {
        const auto channels = read_array<rrc_channel_output>(o.channels, o.channel_count, "output.channels");
        for (uint32_t i = 0; i < o.channel_count; ++i) out.channels[i] = {channels[i].values, channels[i].age, channels[i].weight};
    }
    return out;
}

}  // namespace rrc
