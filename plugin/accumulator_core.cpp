#include "accumulator_core.h"

#include "frame_constants.h"
#include "plan_observer.h"

#include <atomic>

namespace rrc {
namespace {

std::atomic<PlanObserver*> g_observer{nullptr};

}  // namespace

void set_plan_observer(PlanObserver* observer) { g_observer = observer; }
PlanObserver* plan_observer() { return g_observer.load(); }

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
    const size_t fill_words =
        RRC_FILL_LIST_FIRST + (config_.fill_mask() ? (size_t)RRC_FILL_LISTS * RRC_FILL_LIST_CAPACITY(config_.width, config_.height) : 1);
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

void AccumulatorCore::prepare(const FramePlan& plan, const KernelVariant& base) {
    for (const PlanStep& step : plan.steps) {
        if (step.kind != PlanStep::Kind::Dispatch) continue;
        KernelVariant v = step.variant;
        v.storage_inputs = base.storage_inputs;
        pipeline_.pipeline(v);
    }
}

void AccumulatorCore::record_call(VkCommandBuffer cmd, const PlanRequest& request, const KernelVariant& base, const Frame* frame,
                                  bool prev_valid, const MapResources& map) {
    const FramePlan plan = make_plan(config_, request);
    prepare(plan, base);  // every pipeline before anything is recorded: a failure records nothing
    PlanResources res = map(plan);
    res.fill_list = {fill_list_.buffer, 0, RRC_FILL_LIST_FIRST * sizeof(uint32_t)};
    res.view_buffer = {view_buffer_.buffer, 0, VK_WHOLE_SIZE};
    if (PlanObserver* observer = plan_observer()) observer->recording(plan, res, config_, *dev_);
    record_steps(cmd, plan, res, base, frame, prev_valid);
}

void AccumulatorCore::record_barrier(VkCommandBuffer cmd, const PlanStep& step, const PlanResources& res) const {
    auto& vk = dev_->vk;
    const VkPipelineStageFlags src = step.src_stages, dst = step.dst_stages;
    auto buffer_barrier = [&](const PlanBuffer& buf) {
        VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.buffer = buf.buffer;
        b.offset = buf.offset;
        b.size = buf.size;
        b.srcAccessMask = step.src_access;
        b.dstAccessMask = step.dst_access;
        vk.vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 1, &b, 0, nullptr);
    };
    auto image_barriers = [&](const std::vector<PlanCopy>& images) {
        std::vector<VkImageMemoryBarrier> barriers;
        for (const PlanCopy& c : images) {
            VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
            b.srcAccessMask = step.src_access;
            b.dstAccessMask = step.dst_access;
            b.oldLayout = step.old_layout;
            b.newLayout = step.new_layout;
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = c.image->image;
            b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            barriers.push_back(b);
        }
        if (!barriers.empty())
            vk.vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, (uint32_t)barriers.size(), barriers.data());
    };
    switch (step.resource) {
        case PlanResource::Memory: {
            VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            b.srcAccessMask = step.src_access;
            b.dstAccessMask = step.dst_access;
            vk.vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
            break;
        }
        case PlanResource::FillList: buffer_barrier(res.fill_list); break;
        case PlanResource::ViewBuffer: buffer_barrier(res.view_buffer); break;
        case PlanResource::QuadList: buffer_barrier(res.quad_list); break;
        case PlanResource::Stats: buffer_barrier(res.stats); break;
        case PlanResource::HostImagesIn:
        case PlanResource::HostImagesOut: {
            // Each host image carries its own layouts and accesses; the barrier
            // is recorded without any, too (an execution dependency).
            const auto& b = step.resource == PlanResource::HostImagesIn ? res.host_in : res.host_out;
            vk.vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, (uint32_t)b.size(), b.data());
            break;
        }
        case PlanResource::Inputs: image_barriers(res.inputs); break;
        case PlanResource::Outputs: image_barriers(res.outputs); break;
        case PlanResource::LibraryImages: break;  // initialised with their own barriers (record_initialise)
    }
}

void AccumulatorCore::record_steps(VkCommandBuffer cmd, const FramePlan& plan, const PlanResources& res, const KernelVariant& base,
                                   const Frame* frame, bool prev_valid) {
    auto& vk = dev_->vk;
    const FramePushConstants pc = frame ? make_frame_constants(config_, *frame, prev_valid) : FramePushConstants{};
    const VkImageSubresourceLayers colour{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    for (const PlanStep& step : plan.steps) {
        switch (step.kind) {
            case PlanStep::Kind::BeginLabel:
                if (dev_->fi.CmdBeginDebugUtilsLabelEXT) {
                    VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
                    label.pLabelName = step.label;
                    dev_->fi.CmdBeginDebugUtilsLabelEXT(cmd, &label);
                }
                break;
            case PlanStep::Kind::EndLabel:
                if (dev_->fi.CmdEndDebugUtilsLabelEXT) dev_->fi.CmdEndDebugUtilsLabelEXT(cmd);
                break;
            case PlanStep::Kind::Initialise: {
                std::vector<GpuImage*> all = res.initialise;
                for (ViewState& v : views_) {
                    all.insert(all.end(), {&v.depth[0], &v.depth[1]});
                    for (auto& img : v.object_id)
                        if (img.image) all.push_back(&img);
                    for (auto& c : v.channels) c->collect(all);
                }
                all.push_back(&mask_);
                placeholders_.collect(all);
                record_initialise(*dev_, cmd, all);
                break;
            }
            case PlanStep::Kind::Barrier: record_barrier(cmd, step, res); break;
            case PlanStep::Kind::Clear: {
                const PlanBuffer& b = step.resource == PlanResource::FillList ? res.fill_list
                                      : step.resource == PlanResource::Stats  ? res.stats
                                                                              : res.quad_list;
                vk.vkCmdUpdateBuffer(cmd, b.buffer, b.offset, step.words.size() * sizeof(uint32_t), step.words.data());
                break;
            }
            case PlanStep::Kind::WriteView: {
                const ViewBuffer view = make_view_buffer(*frame);
                vk.vkCmdUpdateBuffer(cmd, res.view_buffer.buffer, 0, sizeof view, &view);
                break;
            }
            case PlanStep::Kind::Upload:
            case PlanStep::Kind::Readback: {
                const bool up = step.kind == PlanStep::Kind::Upload;
                for (const PlanCopy& c : up ? res.inputs : res.outputs) {
                    VkBufferImageCopy r{};
                    r.bufferOffset = c.offset;
                    r.imageSubresource = colour;
                    r.imageExtent = {c.image->width, c.image->height, 1};
                    if (up)
                        vk.vkCmdCopyBufferToImage(cmd, res.staging_in, c.image->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
                    else
                        vk.vkCmdCopyImageToBuffer(cmd, c.image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, res.staging_out, 1, &r);
                }
                break;
            }
            case PlanStep::Kind::Dispatch: {
                KernelVariant v = step.variant;
                v.storage_inputs = base.storage_inputs;
                const DescriptorSets& set = step.set == PlanSet::Frame ? res.frame : res.next;
                if (step.grid == PlanGrid::QuadList)
                    pipeline_.record_indirect(cmd, set, pc, v, res.quad_list.buffer, res.quad_list.offset + 4 * RRC_QUAD_LIST_DISPATCH);
                else if (step.grid == PlanGrid::FillList)
                    pipeline_.record_indirect(cmd, set, pc, v, res.fill_list.buffer, 4 * RRC_FILL_LIST_DISPATCH);
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
