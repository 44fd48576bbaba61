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
    const size_t fill_words = RRC_FILL_LIST_FIRST + (config_.fill_mask() ? (size_t)config_.width * config_.height : 1);
    fill_list_ = HostBuffer(*dev_, fill_words * sizeof(uint32_t),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            /*device_local=*/true);
    view_buffer_ = HostBuffer(*dev_, RRC_VIEW_BUFFER_FLOATS * sizeof(float),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, /*device_local=*/true);
    // The pipelines of the context's plainest frame now, so that a broken device fails at
    // creation, not mid-frame, and that frame compiles nothing more: a frame of the whole
    // pass (a shading cache's classify) with no optional output, sampled inputs.  A frame
    // that asks for more makes its own variants then (accumulate_pipeline.h, KernelVariant).
    PlanRequest plain;
    plain.call = all_reuse(config_) ? PlanCall::Classify : PlanCall::Run;
    plain.interop = interop;
    prepare(make_plan(config_, plain), KernelVariant{});
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
    v.fill_list = fill_list_.buffer;
    v.view_buffer = view_buffer_.buffer;
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
    // The indirect read too: resolve dispatches from classify's list.
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    dev_->vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | extra_src_stages,
                                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void AccumulatorCore::prepare(const FramePlan& plan, const KernelVariant& base) {
    for (const PlanStep& step : plan.steps) {
        if (step.op != PlanStep::Op::Dispatch) continue;
        KernelVariant v = step.variant;
        v.storage_inputs = base.storage_inputs;
        pipeline_.pipeline(v);
    }
}

void AccumulatorCore::record_plan(VkCommandBuffer cmd, const FramePlan& plan, const PlanBindings& sets, const KernelVariant& base,
                                  const Frame& frame, bool prev_valid) {
    auto& vk = dev_->vk;
    const FramePushConstants pc = make_frame_constants(config_, frame, prev_valid);
    for (const PlanStep& step : plan.steps) {
        switch (step.op) {
            case PlanStep::Op::ClearFillList: {
                // The previous frame's fill (its indirect read and its loads)
                // finishes before the list starts again empty.
                VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
                b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                b.buffer = fill_list_.buffer;
                b.size = RRC_FILL_LIST_FIRST * sizeof(uint32_t);
                b.srcAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
                b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                                        VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1, &b, 0, nullptr);
                const uint32_t start[RRC_FILL_LIST_FIRST] = {0, 0, 1, 1};
                vk.vkCmdUpdateBuffer(cmd, fill_list_.buffer, 0, sizeof start, start);
                b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 1, &b, 0,
                                        nullptr);
                break;
            }
            case PlanStep::Op::WriteView: {
                // The previous frame's passes finish reading the camera before it changes.
                VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
                b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
                b.buffer = view_buffer_.buffer;
                b.size = VK_WHOLE_SIZE;
                b.srcAccessMask = VK_ACCESS_SHADER_READ_BIT;
                b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1, &b, 0,
                                        nullptr);
                const ViewBuffer view = make_view_buffer(frame);
                vk.vkCmdUpdateBuffer(cmd, view_buffer_.buffer, 0, sizeof view, &view);
                b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 1, &b, 0,
                                        nullptr);
                break;
            }
            case PlanStep::Op::Barrier: {
                VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
                b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
                b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                  (step.to_indirect ? VK_ACCESS_INDIRECT_COMMAND_READ_BIT : 0);
                const VkPipelineStageFlags dst =
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | (step.to_indirect ? VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT : 0);
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
                break;
            }
            case PlanStep::Op::Dispatch: {
                KernelVariant v = step.variant;
                v.storage_inputs = base.storage_inputs;
                const DescriptorSets& set = step.set == PlanSet::Frame ? sets.frame : sets.next;
                if (step.grid == PlanGrid::QuadList)
                    pipeline_.record_indirect(cmd, set, pc, v, sets.quad_list, sets.quad_list_offset + 4 * RRC_QUAD_LIST_DISPATCH);
                else if (step.grid == PlanGrid::FillList)
                    pipeline_.record_indirect(cmd, set, pc, v, fill_list_.buffer, 4 * RRC_FILL_LIST_DISPATCH);
                else
                    pipeline_.record(cmd, set, pc, config_.width, config_.height, v);
                break;
            }
        }
    }
}

void AccumulatorCore::advance(ViewState& view, uint32_t count, uint64_t last_frame_index) {
    view.parity ^= count & 1u;
    view.have_previous = true;
    view.frame_index = last_frame_index;
}

size_t AccumulatorCore::memory_bytes() const {
    size_t bytes = mask_.bytes() + (config_.fill_mask() ? fill_list_.size : 0)  // the fill list (a placeholder without a fill)
                   + (config_.view_lobe() ? view_buffer_.size : 0);
    for (const ViewState& v : views_) {
        bytes += v.depth[0].bytes() + v.depth[1].bytes() + v.object_id[0].bytes() + v.object_id[1].bytes();
        for (const auto& c : v.channels) bytes += c->bytes();
    }
    return bytes;
}

}  // namespace rrc
