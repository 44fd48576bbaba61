// The two public frame descriptors into one Frame record.  Only the struct
// rules are applied here (struct_reader.h); what the values mean is checked
// once, for both paths, by validate_frame (validation.cpp).
#include "frame.h"
#include "struct_reader.h"

namespace rrc {
namespace {

// Fields both descriptors share, by name.
template <typename D>
void read_common(Frame& f, const D& d) {
    f.frame_index = d.frame_index;
    f.reset = d.reset != 0;
    std::memcpy(f.view_proj, d.view_proj, sizeof f.view_proj);
    std::memcpy(f.prev_view_proj, d.prev_view_proj, sizeof f.prev_view_proj);
    std::memcpy(f.jitter, d.jitter, sizeof f.jitter);
    std::memcpy(f.prev_jitter, d.prev_jitter, sizeof f.prev_jitter);
    f.channel_count = d.channel_count;
    f.channels_given = d.channels != nullptr;
}

// The channel array is read only when its count is the context's (else
// validate_frame reports the mismatch) and it is given.
bool channels_readable(const Frame& f, size_t context_channels) {
    return f.channels_given && f.channel_count == context_channels && f.channel_count <= RRC_MAX_CHANNELS;
}

}  // namespace

Frame read_frame(const rrc_frame_desc* caller, size_t context_channels) {
    const rrc_frame_desc d = read_struct<rrc_frame_desc>(caller, "frame");
    Frame f;
    f.path = FramePath::Standalone;
    read_common(f, d);
    f.depth = d.depth;
    f.reprojection = d.reprojection;
    f.nocache = d.nocache;
    if (channels_readable(f, context_channels)) {
        const auto channels = read_array<rrc_channel_input>(d.channels, d.channel_count, "frame.channels");
        for (uint32_t i = 0; i < d.channel_count; ++i) {
            f.channels[i].samples = channels[i].samples;
            f.channels[i].confidence = channels[i].confidence;
        }
    }
    return f;
}

Frame read_frame(const rrc_vulkan_frame_desc* caller, size_t context_channels) {
    const rrc_vulkan_frame_desc d = read_struct<rrc_vulkan_frame_desc>(caller, "frame");
    Frame f;
    f.path = FramePath::Vulkan;
    read_common(f, d);
    f.command_buffer = d.command_buffer;
    f.depth_image = d.depth;
    f.reprojection_image = d.reprojection;
    f.nocache_image = d.nocache;
    f.mask_image = d.mask;
    f.stats_buffer = d.stats_buffer;
    f.stats_offset = d.stats_offset;
    if (channels_readable(f, context_channels)) {
        const auto channels = read_array<rrc_vulkan_channel_images>(d.channels, d.channel_count, "frame.channels");
        for (uint32_t i = 0; i < d.channel_count; ++i) {
            f.channels[i].samples_image = channels[i].samples;
            f.channels[i].confidence_image = channels[i].confidence;
            f.channels[i].output_image = channels[i].output;
            f.channels[i].age_image = channels[i].age;
        }
    }
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
