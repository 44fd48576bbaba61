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
    if (config.validation)
        Log{config.log, config.log_user}(RRC_LOG_WARNING,
                                          "rrc: validation (enable_validation or RRC_VALIDATION=1) has no effect on an interop context: "
                                          "rrc records into the host's device, so enable the Khronos validation layer with synchronization "
                                          "validation in the host's own instance");
}

InteropContext::~InteropContext() {
    // The host has waited for its device (documented); the core releases
    // before the device wrapper, which destroys nothing of the host's.
    core_.reset();
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
    ViewState& view = core_->view(f.view);
    const ViewState& source = core_->view(f.source());  // the frame reprojects into its latest
    const uint32_t p = view.parity;

    PlanRequest request;
    request.call = call;
    request.interop = true;
    request.first_use = !initialised_;
    request.split_outputs = f.split_outputs;
    request.host_mask = f.mask_image.image != VK_NULL_HANDLE;
    request.stats = f.stats_buffer != VK_NULL_HANDLE;
    request.count_io = f.count_io;
    for (uint32_t s = 0; s < f.channel_count; ++s)
        if (f.channels[s].age_image.image) request.host_age_mask |= 1u << s;
    KernelVariant base;
    base.storage_inputs = f.storage_inputs;

    // The plan's ids to this frame's images: the host's where the plan's sets
    // bind them, over the library's own.
    auto map = [&](const FramePlan& plan) {
        PlanResources res;
        HostBarriers hb;
        std::vector<VkImage> barriered;
        auto use = [&](const rrc_vulkan_image& img, bool write, bool storage) {
            for (VkImage i : barriered)
                if (i == img.image) return;
            barriered.push_back(img.image);
            hb.add(img, write, storage);
        };
        auto bind_host = [&](DescriptorViews& v, const PlanSetContents& set) {
            for (uint32_t s = 0; s < f.channel_count; ++s) {
                if (set.host_outputs & (1u << s)) {
                    v.view[RRC_BINDING_HOST_OUT][s] = f.channels[s].output_image.view;
                    use(f.channels[s].output_image, true, false);
                }
                if ((set.host_ages & (1u << s)) && f.channels[s].age_image.image) {
                    v.view[RRC_BINDING_HOST_AGE_OUT][s] = f.channels[s].age_image.view;
                    use(f.channels[s].age_image, true, false);
                }
            }
            if (set.host_mask) {
                v.view[RRC_BINDING_MASK][0] = f.mask_image.view;
                use(f.mask_image, true, false);
            }
        };
        const PlanSetContents& frame = plan.sets[(int)PlanSet::Frame];
        DescriptorViews v = core_->library_views(view, p, source, AccumulatorCore::latest(source));
        for (const LiveInput& in : core_->inputs()) {
            if (!frame.channel_inputs && is_channel_input(in.role)) continue;
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
        bind_host(v, frame);
        // The host's statistics buffer; with the I/O counts, its range holds them too (rrc_vulkan_frame_desc.count_io).
        const VkDeviceSize stats_range = sizeof(rrc_vulkan_frame_stats) + (plan.count_io ? sizeof(rrc_vulkan_io_counts) : 0);
        auto bind_stats = [&](DescriptorViews& set_views) {
            set_views.stats = f.stats_buffer;
            set_views.stats_offset = f.stats_offset;
            set_views.stats_range = stats_range;
        };
        if (frame.stats) {
            bind_stats(v);
            res.stats = {f.stats_buffer, f.stats_offset, stats_range};
        }
        if (list) {
            v.quads = list;
            v.quads_offset = list_offset;
            v.quads_range = RRC_QUAD_LIST_BYTES(config().width, config().height);
            res.quad_list = {list, list_offset, v.quads_range};
        }
        res.frame = next_set();
        core_->pipeline().write_set(res.frame, v);
        if (plan.uses(PlanSet::Next)) {
            // Bound as the next frame would be: this frame's results as history
            // inputs, its depth as the previous depth; the host's outputs.
            DescriptorViews nv = core_->library_views(view, 1 - p, view, p);
            if (plan.sets[(int)PlanSet::Next].stats) bind_stats(nv);
            for (const LiveInput& in : core_->inputs())
                if (in.role == InputRole::Fallback) {
                    nv.view[RRC_BINDING_FALLBACK][in.slot] = host_image(f, in).view;
                    nv.layout[RRC_BINDING_FALLBACK][in.slot] = kReadLayout;
                    use(host_image(f, in), false, false);
                }
            bind_host(nv, plan.sets[(int)PlanSet::Next]);
            res.next = next_set();
            core_->pipeline().write_set(res.next, nv);
        }
        res.host_in = std::move(hb.before);
        res.host_out = std::move(hb.after);
        return res;
    };
    core_->record_call(f.command_buffer, request, base, &f, source.have_previous, map);
    initialised_ = true;
}

DescriptorSets InteropContext::next_set() {
    DescriptorSets set = ring_[next_set_];
    next_set_ = (next_set_ + 1) % (uint32_t)ring_.size();
    return set;
}

}  // namespace rrc
