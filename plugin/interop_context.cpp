#include "interop_context.h"

#include "error.h"
#include "vk_formats.h"

namespace rrc {
namespace {

VkImageAspectFlags aspects(VkFormat f) {
    if (!is_depth_format(f)) return VK_IMAGE_ASPECT_COLOR_BIT;
    return VK_IMAGE_ASPECT_DEPTH_BIT | (has_stencil(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}
// The layout the kernel reads a host input in: valid for every sampled
// image, depth included (DEPTH_STENCIL_READ_ONLY_OPTIMAL would also demand
// attachment usage).
constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

struct HostBarriers {
    std::vector<VkImageMemoryBarrier> before, after;
    // `write`: the kernel stores to it (GENERAL); else it reads it, through
    // a sampler or (`storage`) as a storage image, which needs GENERAL.
    void add(const rrc_vulkan_image& img, bool write, bool storage = false) {
        VkImageLayout use = write || storage ? VK_IMAGE_LAYOUT_GENERAL : kReadLayout;
        VkImageLayout final_layout = img.final_layout ? img.final_layout : img.layout;
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img.image;
        b.subresourceRange = {aspects(img.format), 0, 1, 0, 1};
        // Whatever the host did before (any stage) is made visible to the kernel...
        b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
        // (an image the kernel writes may be read too: resolve reads the mask classify wrote in place)
        b.dstAccessMask = write ? VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT : VK_ACCESS_SHADER_READ_BIT;
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

HostDevice host_device(const rrc_vulkan_device_desc& d) {
    return HostDevice{d.instance,           d.physical_device,         d.device,
                      d.queue_family_index, d.get_instance_proc_addr,  d.get_device_proc_addr,
                      d.allocator,          d.debug_utils_enabled != 0};
}

}  // namespace

InteropContext::InteropContext(const ContextConfig& config, const rrc_vulkan_device_desc& d) {
    std::unique_ptr<VulkanDevice> dev(new VulkanDevice(host_device(d), Log{config.log, config.log_user}));
    const uint32_t in_flight = d.max_frames_in_flight ? d.max_frames_in_flight : 2;
    // A frame records one call (fused) or two (classify, resolve); a call
    // binds at most two sets (the frame's, and the one bound as the next frame).
    const uint32_t sets = 4 * (in_flight + 1);
    core_.reset(new AccumulatorCore(std::move(dev), config, /*interop=*/true, sets, d.pipeline_cache));
    for (uint32_t i = 0; i < sets; ++i) ring_.push_back(core_->pipeline().allocate_set());
    stats_alignment_ = core_->device().limits.minStorageBufferOffsetAlignment;
}

InteropContext::~InteropContext() {
    // The host has waited for its device (documented); the core releases
    // before the device wrapper, which destroys nothing of the host's.
    core_.reset();
}

VkBufferMemoryBarrier InteropContext::stats_barrier(const Frame& f, VkAccessFlags src, VkAccessFlags dst) const {
    VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    b.srcAccessMask = src;
    b.dstAccessMask = dst;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = f.stats_buffer;
    b.offset = f.stats_offset;
    b.size = sizeof(rrc_vulkan_frame_stats);
    return b;
}

// The frame's counters start at zero, `pixels` at the frame's size; the
// host's earlier use of those bytes (any stage) finishes first.
void InteropContext::record_stats_clear(VkCommandBuffer cmd, const Frame& f) {
    auto& vk = core_->device().vk;
    rrc_vulkan_frame_stats start{};
    start.pixels = config().width * config().height;
    VkBufferMemoryBarrier b = stats_barrier(f, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1, &b, 0, nullptr);
    vk.vkCmdUpdateBuffer(cmd, f.stats_buffer, f.stats_offset, sizeof start, &start);
    b = stats_barrier(f, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 1, &b, 0, nullptr);
}

// The library's images start UNDEFINED: to GENERAL, cleared, once, inside
// the host's first command buffer.
void InteropContext::record_initialisation(VkCommandBuffer cmd) {
    std::vector<GpuImage*> all;
    core_->collect_images(all);
    record_initialise(core_->device(), cmd, all);
}

// The list starts empty with a dispatch of {0, 1, 1}; the host's earlier
// use of those bytes (its indirect dispatch of a frame before) finishes first.
void InteropContext::record_list_clear(VkCommandBuffer cmd, VkBuffer list, VkDeviceSize offset) {
    auto& vk = core_->device().vk;
    const uint32_t start[RRC_QUAD_LIST_FIRST_QUAD] = {0, 0, 1, 1};
    VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = list;
    b.offset = offset;
    b.size = RRC_QUAD_LIST_BYTES(config().width, config().height);
    b.srcAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1, &b, 0, nullptr);
    vk.vkCmdUpdateBuffer(cmd, list, offset, sizeof start, start);
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 1, &b, 0, nullptr);
}

void InteropContext::record_frame(const Frame& f) {
    pending_.valid = false;  // a classification not resolved is dropped
    record_pass(f, PlanCall::Run);
    core_->advance(core_->view(f.view), 1, f.frame_index);
}

void InteropContext::record_classify(const Frame& f, VkBuffer list, VkDeviceSize list_offset) {
    pending_.valid = false;  // a classification not resolved is dropped
    record_pass(f, PlanCall::Classify, list, list_offset);
    pending_ = {true, f.frame_index, f.view, f.reproject_from, list, list_offset};
}

void InteropContext::record_resolve(const Frame& f) {
    if (!pending_.valid) fail(RRC_ERROR_INVALID_ARGUMENT, "no classified frame to resolve: record rrc_vulkan_record_classify first");
    if (pending_.frame_index != f.frame_index)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.frame_index is %llu but the classified frame's is %llu: resolve takes classify's frame",
             (unsigned long long)f.frame_index, (unsigned long long)pending_.frame_index);
    if (pending_.view != f.view || pending_.reproject_from != f.reproject_from)
        fail(RRC_ERROR_INVALID_ARGUMENT, "frame.view/reproject_from is %u/%u but the classified frame's is %u/%u", f.view, f.reproject_from,
             pending_.view, pending_.reproject_from);
    record_pass(f, PlanCall::Resolve, pending_.list, pending_.list_offset);  // a shading cache's resolve runs from classify's list
    pending_.valid = false;
    core_->advance(core_->view(f.view), 1, f.frame_index);
}

void InteropContext::record_pass(const Frame& f, PlanCall call, VkBuffer list, VkDeviceSize list_offset) {
    VulkanDevice& dev = core_->device();
    auto& vk = dev.vk;
    VkCommandBuffer cmd = f.command_buffer;
    ViewState& view = core_->view(f.view);
    const ViewState& source = core_->view(f.source());  // the frame reprojects into its latest
    const uint32_t p = view.parity;
    const bool classify = call == PlanCall::Classify;

    PlanRequest request;
    request.call = call;
    request.interop = true;
    request.split_outputs = f.split_outputs;
    request.host_mask = f.mask_image.image != VK_NULL_HANDLE;
    request.stats = f.stats_buffer != VK_NULL_HANDLE;
    for (uint32_t s = 0; s < f.channel_count; ++s)
        if (f.channels[s].age_image.image) request.host_age_mask |= 1u << s;
    const FramePlan plan = make_plan(config(), request);
    KernelVariant base;
    base.storage_inputs = f.storage_inputs;
    core_->prepare(plan, base);  // every pipeline before anything is recorded: a failure records nothing

    // Which host images each set needs: the outputs where a pass bound with
    // it writes them, the mask where the plan puts it.
    uint32_t outputs[2] = {}, ages[2] = {};
    bool copies_mask[2] = {};
    for (const PlanStep& s : plan.steps)
        if (s.op == PlanStep::Op::Dispatch) {
            const int i = (int)s.set;
            outputs[i] |= s.variant.host_out_mask | (s.variant.phase == RRC_PHASE_FILL ? config().fill_mask() : 0u);
            ages[i] |= s.variant.host_age_mask;
            copies_mask[i] = copies_mask[i] || s.variant.copy_mask;
        }
    HostBarriers hb;
    std::vector<VkImage> barriered;
    auto use = [&](const rrc_vulkan_image& img, bool write, bool storage) {
        for (VkImage i : barriered)
            if (i == img.image) return;
        barriered.push_back(img.image);
        hb.add(img, write, storage);
    };
    auto bind_outputs = [&](DescriptorViews& v, int set) {
        for (uint32_t s = 0; s < f.channel_count; ++s) {
            if (outputs[set] & (1u << s)) {
                v.view[RRC_BINDING_HOST_OUT][s] = f.channels[s].output_image.view;
                use(f.channels[s].output_image, true, false);
            }
            if ((ages[set] & (1u << s)) && f.channels[s].age_image.image) {
                v.view[RRC_BINDING_HOST_AGE_OUT][s] = f.channels[s].age_image.view;
                use(f.channels[s].age_image, true, false);
            }
        }
    };
    auto bind_mask = [&](DescriptorViews& v) {
        v.view[RRC_BINDING_MASK][0] = f.mask_image.view;
        use(f.mask_image, true, false);
    };

    // The frame's set: the host's images of this frame over the library's
    // own.  Classify reads the geometry only.
    DescriptorViews v = core_->library_views(view, p, source, AccumulatorCore::latest(source));
    for (const LiveInput& in : core_->inputs()) {
        if (classify && is_channel_input(in.role)) continue;
        // The fallback: the fill's (the next set), and a residual's base (this set too).
        if (in.role == InputRole::Fallback && !config().channels[in.slot].residual) continue;
        const rrc_vulkan_image& img = host_image(f, in);
        // storage_inputs: where the standalone path binds its own copy (ids and fallbacks are sampled either way)
        const bool storage = f.storage_inputs && in.role != InputRole::ObjectId && in.role != InputRole::Fallback;
        const Binding b = storage ? in.own_binding : in.host_binding;
        v.view[b][in.slot] = img.view;
        v.layout[b][in.slot] = storage ? VK_IMAGE_LAYOUT_GENERAL : kReadLayout;
        use(img, false, storage);
    }
    v.view[RRC_BINDING_DEPTH_OUT][0] = view.depth[p].view;
    if (core_->config().use_object_id) v.view[RRC_BINDING_OBJECT_ID][0] = view.object_id[p].view;
    if (plan.frame_set_host_mask) bind_mask(v);
    bind_outputs(v, (int)PlanSet::Frame);
    if (request.stats) {
        v.stats = f.stats_buffer;
        v.stats_offset = f.stats_offset;
    }
    if (list) {
        v.quads = list;
        v.quads_offset = list_offset;
        v.quads_range = RRC_QUAD_LIST_BYTES(config().width, config().height);
    }
    AccumulatorCore::PlanBindings sets;
    sets.quad_list = list;
    sets.quad_list_offset = list_offset;
    sets.frame = next_set();
    core_->pipeline().write_set(sets.frame, v);
    if (plan.uses(PlanSet::Next)) {
        // Bound as the next frame would be: this frame's results as history
        // inputs, its depth as the previous depth; the host's outputs.
        DescriptorViews nv = core_->library_views(view, 1 - p, view, p);
        for (const LiveInput& in : core_->inputs())
            if (in.role == InputRole::Fallback) {
                nv.view[RRC_BINDING_FALLBACK][in.slot] = host_image(f, in).view;
                nv.layout[RRC_BINDING_FALLBACK][in.slot] = kReadLayout;
                use(host_image(f, in), false, false);
            }
        if (copies_mask[(int)PlanSet::Next]) bind_mask(nv);
        bind_outputs(nv, (int)PlanSet::Next);
        sets.next = next_set();
        core_->pipeline().write_set(sets.next, nv);
    }

    if (dev.fi.CmdBeginDebugUtilsLabelEXT) {
        VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
        label.pLabelName = classify ? "rrc: classify" : call == PlanCall::Resolve ? "rrc: resolve" : "rrc: reproject + accumulate";
        dev.fi.CmdBeginDebugUtilsLabelEXT(cmd, &label);
    }
    if (!initialised_) record_initialisation(cmd);

    // The previous frame's kernel wrote what this one reads (history, depth)
    // and read what this one overwrites; the host's images come over.
    core_->record_history_barrier(cmd, 0, 0);
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr,
                            (uint32_t)hb.before.size(), hb.before.data());
    // Resolve adds its counts (invalid samples) to classify's.
    if (request.stats && call != PlanCall::Resolve) record_stats_clear(cmd, f);
    if (classify) record_list_clear(cmd, list, list_offset);
    core_->record_plan(cmd, plan, sets, base, f, source.have_previous);
    if (classify) {
        // The list to the host's indirect dispatch and its miss shader (rrc_vulkan.h).
        VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.buffer = list;
        b.offset = list_offset;
        b.size = v.quads_range;
        b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
        vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                0, 0, nullptr, 1, &b, 0, nullptr);
    }
    vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr,
                            (uint32_t)hb.after.size(), hb.after.data());
    if (request.stats) {
        // The counters to the host (after its fence) and to any later command.
        VkBufferMemoryBarrier b =
            stats_barrier(f, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT | VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
        vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                                0, 0, nullptr, 1, &b, 0, nullptr);
    }
    if (dev.fi.CmdEndDebugUtilsLabelEXT) dev.fi.CmdEndDebugUtilsLabelEXT(cmd);
    initialised_ = true;
}

DescriptorSets InteropContext::next_set() {
    DescriptorSets set = ring_[next_set_];
    next_set_ = (next_set_ + 1) % (uint32_t)ring_.size();
    return set;
}

}  // namespace rrc
