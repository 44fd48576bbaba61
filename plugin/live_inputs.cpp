#include "live_inputs.h"

namespace rrc {

std::vector<LiveInput> live_inputs(const ContextConfig& c) {
    std::vector<LiveInput> in;
    in.push_back({InputRole::Depth, 0, RRC_BINDING_DEPTH, RRC_BINDING_HOST_DEPTH, VK_FORMAT_R32_SFLOAT, 1, 4});
    switch (c.reprojection) {
        case RRC_REPROJECTION_PREV_CLIP:
            in.push_back({InputRole::Reprojection, 0, RRC_BINDING_REPROJ, RRC_BINDING_HOST_REPROJ, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4});
            break;
        case RRC_REPROJECTION_MOTION:
            // kept as RGBA like the others: one binding serves every source
            in.push_back({InputRole::Reprojection, 0, RRC_BINDING_REPROJ, RRC_BINDING_HOST_REPROJ, VK_FORMAT_R32G32B32A32_SFLOAT, 2, 4});
            break;
        case RRC_REPROJECTION_MOTION_DEPTH:  // 3 floats a pixel, kept as RGBA (no RGB32F storage images)
            in.push_back({InputRole::Reprojection, 0, RRC_BINDING_REPROJ, RRC_BINDING_HOST_REPROJ, VK_FORMAT_R32G32B32A32_SFLOAT, 3, 4});
            break;
        default: break;  // CAMERA: matrices only
    }
    if (c.use_nocache) in.push_back({InputRole::Nocache, 0, RRC_BINDING_NOCACHE, RRC_BINDING_HOST_NOCACHE, VK_FORMAT_R8_UINT, 1, 1});
    if (c.use_object_id)
        // Both paths read this frame's ids through the sampler binding: the
        // standalone upload, or the host's image (which the kernel copies to RRC_BINDING_OBJECT_ID).
        in.push_back({InputRole::ObjectId, 0, RRC_BINDING_HOST_OBJECT_ID, RRC_BINDING_HOST_OBJECT_ID, VK_FORMAT_R32_UINT, 1, 4});
    for (uint32_t s = 0; s < c.channels.size(); ++s) {
        const bool one = c.channels[s].components == 1;
        in.push_back({InputRole::Samples, s, uint32_t(one ? RRC_BINDING_SAMPLE1 : RRC_BINDING_SAMPLE4), RRC_BINDING_HOST_SAMPLES,
                      one ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT, c.channels[s].components, 4});
        if (c.channels[s].confidence)
            in.push_back({InputRole::Confidence, s, RRC_BINDING_CONFIDENCE, RRC_BINDING_HOST_CONFIDENCE, VK_FORMAT_R32_SFLOAT, 1, 4});
        if (c.channels[s].fallback())
            // Read by the fill only, through a sampler on both paths (as object ids).
            in.push_back({InputRole::Fallback, s, RRC_BINDING_FALLBACK, RRC_BINDING_FALLBACK,
                          one ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT, c.channels[s].components, 4});
    }
    return in;
}

// Where input `in` of frame f lives on either path: one table.
struct HostSource {
    const void* array;
    const rrc_vulkan_image* image;
};
static HostSource host_source(const Frame& f, const LiveInput& in) {
    const FrameChannel& c = f.channels[in.slot];
    switch (in.role) {
        case InputRole::Depth: return {f.depth, &f.depth_image};
        case InputRole::Reprojection: return {f.reprojection, &f.reprojection_image};
        case InputRole::Nocache: return {f.nocache, &f.nocache_image};
        case InputRole::ObjectId: return {f.object_id, &f.object_id_image};
        case InputRole::Samples: return {c.samples, &c.samples_image};
        case InputRole::Confidence: return {c.confidence, &c.confidence_image};
        case InputRole::Fallback: break;
    }
    return {c.fallback, &c.fallback_image};
}

const void* host_array(const Frame& f, const LiveInput& in) { return host_source(f, in).array; }
const rrc_vulkan_image& host_image(const Frame& f, const LiveInput& in) { return *host_source(f, in).image; }

}  // namespace rrc
