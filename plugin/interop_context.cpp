#include "interop_context.h"

#include "error.h"
#include "frame_constants.h"

#include <cmath>
#include <cstring>

namespace rrc {
namespace {

bool is_depth_format(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D32_SFLOAT ||
           f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}
bool has_stencil(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}
VkImageAspectFlags aspects(VkFormat f) {
    if (!is_depth_format(f)) return VK_IMAGE_ASPECT_COLOR_BIT;
    return VK_IMAGE_ASPECT_DEPTH_BIT | (has_stencil(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}
// The layout the kernel reads a host input in: valid for every sampled
// image, depth included (DEPTH_STENCIL_READ_ONLY_OPTIMAL would also demand
// attachment usage).
VkImageLayout read_layout(VkFormat) { return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL; }

struct HostBarriers {
    std::vector<VkImageMemoryBarrier> before, after;
    // `write`: the kernel stores to it (GENERAL); else it samples it.
    void add(const rrc_vulkan_image& img, bool write) {
        VkImageLayout use = write ? VK_IMAGE_LAYOUT_GENERAL : read_layout(img.format);
        VkImageLayout final_layout = img.final_layout ? img.final_layout : img.layout;
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img.image;
        b.subresourceRange = {aspects(img.format), 0, 1, 0, 1};
        // Whatever the host did before (any stage) is made visible to the kernel...
        b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
        b.dstAccessMask = write ? VK_ACCESS_SHADER_WRITE_BIT : VK_ACCESS_SHADER_READ_BIT;
        b.oldLayout = img.layout;  // UNDEFINED from the host discards, as it would for any pass
        b.newLayout = use;
        before.push_back(b);
        // ...and the kernel's writes to whatever the host does next.
        b.srcAccessMask = write ? VK_ACCESS_SHADER_WRITE_BIT : 0;
        b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        b.oldLayout = use;
        b.newLayout = final_layout;
        after.push_back(b);
    }
};

}  // namespace

InteropContext::InteropContext(const ContextConfig& config, const rrc_vulkan_device_desc& d) : config_(config) {
    HostDevice host;
    host.instance = d.instance;
    host.physical = d.physical_device;
    host.device = d.device;
    host.queue_family = d.queue_family_index;
    host.get_instance_proc_addr = d.get_instance_proc_addr;
    host.get_device_proc_addr = d.get_device_proc_addr;
    host.allocator = d.allocator;
    host.debug_utils = d.debug_utils_enabled != 0;
    dev_.reset(new VulkanDevice(host, Log{config.log, config.log_user}));
    const uint32_t in_flight = d.max_frames_in_flight ? d.max_frames_in_flight : 2;
    pipeline_.reset(new AccumulatePipeline(*dev_, config_, /*interop=*/true, in_flight + 1, d.pipeline_cache));
    placeholders_.reset(new Placeholders(*dev_));
    for (auto& img : depth_) img = GpuImage(*dev_, VK_FORMAT_R32_SFLOAT, config.width, config.height);
    mask_ = GpuImage(*dev_, VK_FORMAT_R8_UINT, config.width, config.height);
    for (const ChannelConfig& c : config_.channels) channels_.emplace_back(new ChannelHistory(*dev_, c, config.width, config.height));
    for (uint32_t i = 0; i < in_flight + 1; ++i) ring_.push_back(pipeline_->allocate_set());
}

InteropContext::~InteropContext() {
    // The host has waited for its device (documented); release before the
    // device wrapper, which destroys nothing of the host's.
    channels_.clear();
    depth_[0] = GpuImage();
    depth_[1] = GpuImage();
    mask_ = GpuImage();
    placeholders_.reset();
    pipeline_.reset();
    dev_.reset();
}

size_t InteropContext::memory_bytes() const {
    size_t bytes = depth_[0].bytes() * 2 + mask_.bytes();
    for (const auto& c : channels_) bytes += c->bytes();
    return bytes;
}

void InteropContext::validate(const rrc_vulkan_frame_desc& f) const {
    auto need = [](const rrc_vulkan_image& img, const char* what) {
        if (!img.image || !img.view) fail(RRC_ERROR_MISSING_INPUT, "frame.%s.image/view is VK_NULL_HANDLE", what);
    };
    if (f.type != RRC_STRUCT_TYPE_VULKAN_FRAME_DESC)
        fail(RRC_ERROR_INVALID_STRUCT, "frame.type is 0x%08x, expected RRC_STRUCT_TYPE_VULKAN_FRAME_DESC", (unsigned)f.type);
    if (f.size < sizeof(rrc_vulkan_frame_desc)) fail(RRC_ERROR_INVALID_STRUCT, "frame.size is %u, too small", (unsigned)f.size);
    if (f.next) fail(RRC_ERROR_INVALID_STRUCT, "frame.next must be NULL");
    if (!f.command_buffer) fail(RRC_ERROR_INVALID_ARGUMENT, "frame.command_buffer is VK_NULL_HANDLE");
    need(f.depth, "depth");
    if (config_.reprojection != RRC_REPROJECTION_CAMERA) need(f.reprojection, "reprojection");
    if (config_.use_nocache) need(f.nocache, "nocache");
    if (config_.reprojection == RRC_REPROJECTION_CAMERA)
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(f.view_proj[i]) || !std::isfinite(f.prev_view_proj[i]))
                fail(RRC_ERROR_INVALID_ARGUMENT, "frame.view_proj/prev_view_proj[%d] is not finite", i);
    for (int i = 0; i < 2; ++i)
        if (!std::isfinite(f.jitter[i]) || !std::isfinite(f.prev_jitter[i]) || std::fabs(f.jitter[i]) > 1.0f ||
            std::fabs(f.prev_jitter[i]) > 1.0f)
            fail(RRC_ERROR_INVALID_ARGUMENT, "frame.jitter/prev_jitter[%d] must be finite and within [-1, 1] pixels", i);
    if (f.channel_count != config_.channels.size())
        fail(RRC_ERROR_SIZE_MISMATCH, "frame.channel_count is %u, the context has %zu channels", f.channel_count, config_.channels.size());
    if (!f.channels) fail(RRC_ERROR_MISSING_INPUT, "frame.channels is NULL");
    for (uint32_t i = 0; i < f.channel_count; ++i) {
        const rrc_vulkan_channel_images& c = f.channels[i];
        if (c.type != RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES || c.size < sizeof c || c.next)
            fail(RRC_ERROR_INVALID_STRUCT, "frame.channels[%u] has a wrong type, size or next", i);
        char what[64];
        std::snprintf(what, sizeof what, "channels[%u].samples", i);
        need(c.samples, what);
        std::snprintf(what, sizeof what, "channels[%u].output", i);
        need(c.output, what);
        if (config_.channels[i].confidence) {
            std::snprintf(what, sizeof what, "channels[%u].confidence", i);
            need(c.confidence, what);
        }
    }
}

// The library's images start UNDEFINED: to GENERAL, cleared, once, inside
// the host's first command buffer.
void InteropContext::record_initialisation(VkCommandBuffer cmd) {
    std::vector<GpuImage*> all = {&depth_[0], &depth_[1], &mask_};
    for (auto& c : channels_) c->collect(all);
    placeholders_->collect(all);
    record_initialise(*dev_, cmd, all);
}

void InteropContext::record_frame(const rrc_vulkan_frame_desc& f) {
    validate(f);
    auto& vk = dev_->vk;
    VkCommandBuffer cmd = f.command_buffer;
    const uint32_t p = parity_;

    // Descriptors: the host's images of this frame, the library's ping-pong.
    DescriptorViews v = placeholders_->views();
    auto host_read = [&](Binding b, uint32_t slot, const rrc_vulkan_image& img) {
        v.view[b][slot] = img.view;
        v.layout[b][slot] = read_layout(img.format);
    };
    host_read(kHostDepth, 0, f.depth);
    if (config_.reprojection != RRC_REPROJECTION_CAMERA) host_read(kHostReproj, 0, f.reprojection);
    if (config_.use_nocache) host_read(kHostNocache, 0, f.nocache);
    v.view[kPrevDepth][0] = depth_[1 - p].view;
    v.view[kDepthOut][0] = depth_[p].view;
    v.view[kMask][0] = f.mask.image ? f.mask.view : mask_.view;
    for (uint32_t s = 0; s < channels_.size(); ++s) {
        host_read(kHostSamples, s, f.channels[s].samples);
        if (config_.channels[s].confidence) host_read(kHostConfidence, s, f.channels[s].confidence);
        v.view[kHostOut][s] = f.channels[s].output.view;
        bind_history(v, s, *channels_[s], p);
    }
    VkDescriptorSet set = ring_[next_set_];
    pipeline_->write_set(set, v);

    if (dev_->fi.CmdBeginDebugUtilsLabelEXT) {
        VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
        label.pLabelName = "rrc: reproject + accumulate";
        dev_->fi.CmdBeginDebugUtilsLabelEXT(cmd, &label);
    }
    if (!initialised_) record_initialisation(cmd);

    // The previous frame's kernel wrote what this one reads (history, depth)
    // and read what this one overwrites.
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    HostBarriers hb;
    hb.add(f.depth, false);
    if (config_.reprojection != RRC_REPROJECTION_CAMERA) hb.add(f.reprojection, false);
    if (config_.use_nocache) hb.add(f.nocache, false);
    if (f.mask.image) hb.add(f.mask, true);
    for (uint32_t s = 0; s < channels_.size(); ++s) {
        hb.add(f.channels[s].samples, false);
        if (config_.channels[s].confidence) hb.add(f.channels[s].confidence, false);
        hb.add(f.channels[s].output, true);
    }
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &mb, 0, nullptr,
                            (uint32_t)hb.before.size(), hb.before.data());
    rrc_frame_desc core{};
    std::memcpy(core.view_proj, f.view_proj, sizeof core.view_proj);
    std::memcpy(core.prev_view_proj, f.prev_view_proj, sizeof core.prev_view_proj);
    std::memcpy(core.jitter, f.jitter, sizeof core.jitter);
    std::memcpy(core.prev_jitter, f.prev_jitter, sizeof core.prev_jitter);
    core.reset = f.reset;
    pipeline_->record(cmd, set, make_frame_constants(config_, core, have_previous_), config_.width, config_.height);
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr,
                            (uint32_t)hb.after.size(), hb.after.data());
    if (dev_->fi.CmdEndDebugUtilsLabelEXT) dev_->fi.CmdEndDebugUtilsLabelEXT(cmd);

    initialised_ = true;
    next_set_ = (next_set_ + 1) % (uint32_t)ring_.size();
    parity_ = 1 - parity_;
    have_previous_ = true;
}

}  // namespace rrc
