#include "accumulator_core.h"

#include "frame_constants.h"

namespace rrc {

AccumulatorCore::AccumulatorCore(std::unique_ptr<VulkanDevice> device, const ContextConfig& config, bool interop, uint32_t sets,
                                 VkPipelineCache cache)
    : config_(config),
      dev_(std::move(device)),
      inputs_(live_inputs(config)),
      pipeline_(*dev_, config_, interop, sets, cache),
      placeholders_(*dev_),
      views_(config.view_count) {
    for (ViewState& v : views_) {
        for (auto& img : v.depth) img = GpuImage(*dev_, VK_FORMAT_R32_SFLOAT, config_.width, config_.height);
        if (config_.use_object_id)
            for (auto& img : v.object_id) img = GpuImage(*dev_, VK_FORMAT_R32_UINT, config_.width, config_.height);
        for (const ChannelConfig& c : config_.channels)
            v.channels.emplace_back(new ChannelHistory(*dev_, c, config_.width, config_.height));
    }
    mask_ = GpuImage(*dev_, VK_FORMAT_R8_UINT, config_.width, config_.height);
    stats_placeholder_ = HostBuffer(*dev_, RRC_STAT_COUNT * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    quads_placeholder_ = HostBuffer(*dev_, (RRC_QUAD_LIST_FIRST_QUAD + 1) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

AccumulatorCore::~AccumulatorCore() = default;  // members in reverse order: the device wrapper last

DescriptorViews AccumulatorCore::library_views(const ViewState& view, uint32_t p, const ViewState& source, uint32_t sp) const {
    DescriptorViews v = placeholders_.views();
    v.view[RRC_BINDING_PREV_DEPTH][0] = source.depth[sp].view;
    if (config_.use_object_id) v.view[RRC_BINDING_PREV_OBJECT_ID][0] = source.object_id[sp].view;
    v.view[RRC_BINDING_MASK][0] = mask_.view;
    v.view[RRC_BINDING_CLASSIFIED][0] = mask_.view;  // resolve reads what classify wrote there
    v.stats = stats_placeholder_.buffer;
    v.quads = quads_placeholder_.buffer;
    for (uint32_t s = 0; s < view.channels.size(); ++s) bind_history(v, s, *source.channels[s], sp, *view.channels[s], p);
    return v;
}

void AccumulatorCore::collect_images(std::vector<GpuImage*>& out) {
    for (ViewState& v : views_) {
        out.insert(out.end(), {&v.depth[0], &v.depth[1]});
        for (auto& img : v.object_id)
            if (img.image) out.push_back(&img);
        for (auto& c : v.channels) c->collect(out);
    }
    out.push_back(&mask_);
    placeholders_.collect(out);
}

void AccumulatorCore::record_history_barrier(VkCommandBuffer cmd, VkPipelineStageFlags extra_src_stages,
                                             VkAccessFlags extra_src_access) const {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | extra_src_access;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    dev_->vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | extra_src_stages, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                                  &b, 0, nullptr, 0, nullptr);
}

void AccumulatorCore::record_dispatch(VkCommandBuffer cmd, VkDescriptorSet set, const Frame& frame, bool prev_valid,
                                      const KernelVariant& variant) {
    const FramePushConstants pc = make_frame_constants(config_, frame, prev_valid);
    pipeline_.record(cmd, set, pc, config_.width, config_.height, variant);
    if (variant.phase != RRC_PHASE_CLASSIFY) return;
    // Classify's second dispatch lists the quads from the mask the first wrote.
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    dev_->vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0, nullptr, 0,
                                  nullptr);
    KernelVariant list = variant;
    list.phase = RRC_PHASE_LIST;
    pipeline_.record(cmd, set, pc, config_.width, config_.height, list);
}

void AccumulatorCore::advance(ViewState& view, uint32_t count, uint64_t last_frame_index) {
    view.parity ^= count & 1u;
    view.have_previous = true;
    view.frame_index = last_frame_index;
}

size_t AccumulatorCore::memory_bytes() const {
    size_t bytes = mask_.bytes();
    for (const ViewState& v : views_) {
        bytes += v.depth[0].bytes() + v.depth[1].bytes() + v.object_id[0].bytes() + v.object_id[1].bytes();
        for (const auto& c : v.channels) bytes += c->bytes();
    }
    return bytes;
}

}  // namespace rrc
