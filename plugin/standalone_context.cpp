#include "standalone_context.h"

#include "error.h"
#include "struct_reader.h"

#include <glm/gtc/packing.hpp>

#include <cstring>

namespace rrc {
namespace {

size_t align16(size_t x) { return (x + 15) & ~size_t(15); }

VkImageSubresourceLayers color_layers() { return {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}; }

}  // namespace

StandaloneContext::StandaloneContext(const ContextConfig& config) {
    Log log{config.log, config.log_user};
    std::unique_ptr<VulkanDevice> dev(new VulkanDevice(config.device_name, config.validation, log));
    // Sets by (view, parity, source, source parity): 2 with one view; the
    // fill's by (view, parity): 2 a view.
    const uint32_t views = config.view_count, sets = (views == 1 ? 2 : 4 * views * views) + (config.fill_mask() ? 2 * views : 0);
    core_.reset(new AccumulatorCore(std::move(dev), config, /*interop=*/false, sets));
    VulkanDevice& d = core_->device();
    auto& vk = d.vk;
    try {
        const uint32_t w = config.width, h = config.height;
        for (const ChannelConfig& c : config.channels)
            display_.emplace_back(c.displayed() ? GpuImage(d, c.components == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT, w, h)
                                           : GpuImage());
        for (const LiveInput& in : core_->inputs()) {
            inputs_.emplace_back(kept_as_history(in.role) ? GpuImage() : GpuImage(d, in.own_format, w, h));
            upload_bytes_ += align16((size_t)w * h * texel_bytes(in.own_format));
        }
        readback_bytes_ = readback_bytes();
        reserve_batch(1);
        quads_ = HostBuffer(d, RRC_QUAD_LIST_BYTES(w, h),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pci.queueFamilyIndex = d.queue_family;
        VulkanDevice::check(vk.vkCreateCommandPool(d.device, &pci, nullptr, &pool_), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool_;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        VulkanDevice::check(vk.vkAllocateCommandBuffers(d.device, &cai, &cmd_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VulkanDevice::check(vk.vkCreateFence(d.device, &fci, nullptr, &fence_), "vkCreateFence");
        initialise_images();
        log(RRC_LOG_INFO, "rrc: context " + std::to_string(w) + "x" + std::to_string(h) + " on " + d.name);
    } catch (...) {
        if (fence_) vk.vkDestroyFence(d.device, fence_, nullptr);
        if (pool_) vk.vkDestroyCommandPool(d.device, pool_, nullptr);
        inputs_.clear();
        display_.clear();
        upload_ = HostBuffer();
        readback_ = HostBuffer();
        quads_ = HostBuffer();
        throw;
    }
}

StandaloneContext::~StandaloneContext() {
    VulkanDevice& d = core_->device();
    if (d.device) {
        d.vk.vkDeviceWaitIdle(d.device);
        if (fence_) d.vk.vkDestroyFence(d.device, fence_, nullptr);
        if (pool_) d.vk.vkDestroyCommandPool(d.device, pool_, nullptr);
    }
    // This path's resources go before the core, which destroys the device last.
    inputs_.clear();
    display_.clear();
    upload_ = HostBuffer();
    readback_ = HostBuffer();
    quads_ = HostBuffer();
    core_.reset();
}

// Fixed offsets in a slot's region of the readback buffer: the mask, then
// per channel history, age and weight; only requested images are copied.
std::vector<StandaloneContext::Readback> StandaloneContext::readbacks(const FrameOutputs& out, const ViewState& v, uint32_t parity) const {
    std::vector<Readback> r;
    r.push_back({&core_->own_mask(), out.caller ? (void*)out.mask : nullptr});
    for (size_t i = 0; i < v.channels.size(); ++i) {
        const ChannelHistory& h = *v.channels[i];
        const FrameOutputs::Channel* co = out.channel_count ? &out.channels[i] : nullptr;
        if (display_[i].image) {
            // A fill or a residual: values are the displayed ones, ages the history's (docs/CONVENTIONS.md,
            // "The spatial fill", "The residual").
            r.push_back({&display_[i], co ? (void*)co->values : nullptr});
            uint16_t* ages = co ? co->age : nullptr;
            if (h.packed())
                r.push_back({&h.history[parity], ages, ages});
            else
                r.push_back({&h.age[parity], ages});
        } else if (h.packed()) {
            // values and ages from one image: copied when either is asked for
            void* values = co ? (void*)co->values : nullptr;
            uint16_t* ages = co ? co->age : nullptr;
            r.push_back({&h.history[parity], values ? values : ages ? (void*)ages : nullptr, ages});
        } else {
            r.push_back({&h.history[parity], co ? (void*)co->values : nullptr});
            r.push_back({&h.age[parity], co ? (void*)co->age : nullptr});
        }
        r.push_back({&h.weight[parity], co ? (void*)co->weight : nullptr});
    }
    return r;
}

size_t StandaloneContext::readback_bytes() const {
    size_t bytes = 0;
    for (const Readback& r : readbacks(FrameOutputs{}, core_->view(), 0)) bytes += align16(r.image->bytes());
    return bytes;
}

// Staging holds one region per frame of a batch; it grows to the largest batch.
void StandaloneContext::reserve_batch(uint32_t frames) {
    if (frames <= batch_capacity_) return;
    upload_ = HostBuffer(core_->device(), upload_bytes_ * frames, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    readback_ = HostBuffer(core_->device(), readback_bytes_ * frames, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    batch_capacity_ = frames;
}

const GpuImage& StandaloneContext::own_input(const ViewState& view, size_t input, uint32_t parity) const {
    switch (core_->inputs()[input].role) {
        case InputRole::Depth: return view.depth[parity];
        case InputRole::ObjectId: return view.object_id[parity];
        default: return inputs_[input];
    }
}

DescriptorSets StandaloneContext::set_for(uint32_t view, uint32_t p, uint32_t source, uint32_t sp) {
    const uint32_t key = ((view * RRC_MAX_VIEWS + source) * 2 + p) * 2 + sp;
    auto found = sets_.find(key);
    if (found != sets_.end()) return found->second;
    const ViewState& v = core_->view(view);
    DescriptorViews d = core_->library_views(v, p, core_->view(source), sp);
    d.quads = quads_.buffer;
    for (size_t i = 0; i < core_->inputs().size(); ++i) {
        const LiveInput& in = core_->inputs()[i];
        d.view[in.own_binding][in.slot] = own_input(v, i, p).view;
    }
    // A fill's or a residual's displayed values: the frame's passes write them where the
    // fill does not run, the fill where it does (docs/design/frame-plan.md).
    for (uint32_t s = 0; s < display_.size(); ++s)
        if (display_[s].image) d.view[RRC_BINDING_HOST_OUT][s] = display_[s].view;
    DescriptorSets set = core_->pipeline().allocate_set();
    core_->pipeline().write_set(set, d);
    sets_[key] = set;
    return set;
}

// One submission at creation: every image to GENERAL, cleared (the plan of
// the Initialise call).
void StandaloneContext::initialise_images() {
    begin();
    PlanRequest request;
    request.call = PlanCall::Initialise;
    core_->record_call(cmd_, request, KernelVariant{}, nullptr, false, [&](const FramePlan&) {
        PlanResources res;
        for (GpuImage& img : inputs_) res.initialise.push_back(&img);
        for (GpuImage& img : display_)
            if (img.image) res.initialise.push_back(&img);
        return res;
    });
    VulkanDevice::check(core_->device().vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    submit_and_wait();
}

// The host's arrays into the slot's staging region, in the table's order;
// arrays with fewer components than their image (MOTION_DEPTH's 3 floats)
// are padded with zeros.
bool StandaloneContext::uploads(const LiveInput& in, PlanCall call) const {
    const bool channel = is_channel_input(in.role);
    return call == PlanCall::Run || (call == PlanCall::Resolve) == channel;
}

void StandaloneContext::upload(const Frame& f, uint32_t slot, PlanCall call) {
    const size_t n = (size_t)config().width * config().height;
    unsigned char* dst = upload_.data + slot * upload_bytes_;
    for (const LiveInput& in : core_->inputs()) {
        if (!uploads(in, call)) {
            dst += align16(n * texel_bytes(in.own_format));
            continue;
        }
        const size_t texel = texel_bytes(in.own_format), element = (size_t)in.host_components * in.host_element_bytes;
        const unsigned char* src = static_cast<const unsigned char*>(host_array(f, in));
        if (element == texel) {
            std::memcpy(dst, src, n * texel);
        } else {
            for (size_t i = 0; i < n; ++i) {
                std::memcpy(dst + i * texel, src + i * element, element);
                std::memset(dst + i * texel + element, 0, texel - element);
            }
        }
        dst += align16(n * texel);
    }
}

void StandaloneContext::record(const Frame& f, const FrameOutputs& out, uint32_t slot, uint32_t parity, uint32_t source_parity,
                               bool prev_valid, PlanCall call) {
    const ViewState& view = core_->view(f.view);
    PlanRequest request;
    request.call = call;
    // The plan's ids to this context's own images: its sets bind everything
    // (a fill's or a residual's displayed values are its host outputs), its
    // inputs come from the slot's staging region, its outputs go to the slot's readback region.
    core_->record_call(cmd_, request, KernelVariant{}, &f, prev_valid, [&](const FramePlan& plan) {
        PlanResources res;
        res.frame = set_for(f.view, parity, f.source(), source_parity);
        if (plan.uses(PlanSet::Next)) res.next = set_for(f.view, 1 - parity, f.view, parity);  // this frame's results as history inputs
        res.quad_list = {quads_.buffer, 0, quads_.size};
        res.staging_in = upload_.buffer;
        res.staging_out = readback_.buffer;
        VkDeviceSize offset = slot * upload_bytes_;
        for (size_t i = 0; i < core_->inputs().size(); ++i) {
            const LiveInput& in = core_->inputs()[i];
            if (uploads(in, call)) res.inputs.push_back({&own_input(view, i, parity), offset});
            offset += align16((size_t)config().width * config().height * texel_bytes(in.own_format));
        }
        offset = slot * readback_bytes_;
        for (const Readback& r : readbacks(out, view, parity)) {
            // What the host asked for, and the mask always (the statistics).
            if (r.image->image && (r.destination || r.image == &core_->own_mask())) res.outputs.push_back({r.image, offset});
            offset += align16(r.image->bytes());
        }
        return res;
    });
}

void StandaloneContext::submit_and_wait() {
    VulkanDevice& d = core_->device();
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    VulkanDevice::check(d.vk.vkQueueSubmit(d.queue, 1, &si, fence_), "vkQueueSubmit");
    VkResult r = d.vk.vkWaitForFences(d.device, 1, &fence_, VK_TRUE, 120ull * 1000 * 1000 * 1000);
    if (r == VK_TIMEOUT) fail(RRC_ERROR_DEVICE_LOST, "the frame did not finish within 120 s");
    VulkanDevice::check(r, "vkWaitForFences");
    VulkanDevice::check(d.vk.vkResetFences(d.device, 1, &fence_), "vkResetFences");
}

// docs/CONVENTIONS.md: misses are the pixels neither HIT, REFRESHED nor BACKGROUND.
StandaloneContext::Stats StandaloneContext::count_stats(const uint8_t* mask) const {
    const size_t n = (size_t)config().width * config().height;
    rrc_frame_stats stats{};
    uint64_t refreshed = 0;
    for (size_t i = 0; i < n; ++i) {
        const uint8_t m = mask[i];
        stats.hits += (m & RRC_MASK_HIT) ? 1 : 0;
        refreshed += (m & RRC_MASK_REFRESHED) ? 1 : 0;
        stats.background += (m & RRC_MASK_BACKGROUND) ? 1 : 0;
        stats.invalid_samples += (m & RRC_MASK_INVALID_SAMPLE) ? 1 : 0;
        stats.invalid_geometry += (m & RRC_MASK_INVALID_GEOMETRY) ? 1 : 0;
    }
    stats.misses = n - stats.background - stats.hits - refreshed;
    return {stats, refreshed};
}

void StandaloneContext::read_back(const FrameOutputs& out, uint32_t slot, const ViewState& view, uint32_t parity) {
    if (!out.caller) return;
    const size_t n = (size_t)config().width * config().height;
    const Stats stats = count_stats(readback_.data + slot * readback_bytes_);
    size_t offset = slot * readback_bytes_;
    for (const Readback& r : readbacks(out, view, parity)) {
        const GpuImage& img = *r.image;
        const unsigned char* src = readback_.data + offset;
        offset += align16(img.bytes());
        if (!img.image || !r.destination) continue;
        if (img.format == kPackedHistoryFormat) {
            const uint32_t* words = reinterpret_cast<const uint32_t*>(src);
            float* values = r.destination == r.age_destination ? nullptr : static_cast<float*>(r.destination);
            for (size_t i = 0; i < n; ++i) {
                if (values) values[i] = glm::unpackHalf1x16((uint16_t)(words[i] & 0xFFFFu));
                if (r.age_destination) r.age_destination[i] = (uint16_t)(words[i] >> 16);
            }
        } else if (img.format == VK_FORMAT_R16G16B16A16_SFLOAT) {
            const uint16_t* h = reinterpret_cast<const uint16_t*>(src);
            float* d = static_cast<float*>(r.destination);
            const size_t count = 4 * n;
            for (size_t i = 0; i < count; ++i) d[i] = glm::unpackHalf1x16(h[i]);
        } else {
            std::memcpy(r.destination, src, img.bytes());
        }
    }
    write_member(out.caller, offsetof(rrc_frame_output, stats), stats.counts);
    write_member(out.caller, offsetof(rrc_frame_output, refreshed), stats.refreshed);
}

size_t StandaloneContext::memory_bytes() const {
    size_t bytes = core_->memory_bytes() + upload_.size + readback_.size;
    for (const GpuImage& img : inputs_) bytes += img.bytes();
    return bytes;
}

void StandaloneContext::begin() {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VulkanDevice::check(core_->device().vk.vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
}

// Classify of frame f, its geometry already in staging slot 0: the list
// (from empty), the mask and the HITs' channels of a shading cache.
void StandaloneContext::run_classify(const Frame& f) {
    auto& vk = core_->device().vk;
    ViewState& view = core_->view(f.view);
    const ViewState& source = core_->view(f.source());
    begin();
    record(f, FrameOutputs{}, 0, view.parity, AccumulatorCore::latest(source), source.have_previous,
           PlanCall::Classify);  // copies the mask back, as always, and the list to the host
    VulkanDevice::check(vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    submit_and_wait();
}

void StandaloneContext::classify(const Frame& f, const Classified& out) {
    // A classification still pending is kept if this one fails: its staged
    // geometry, to classify it again (the GPU state resolve reads: the mask,
    // the list, the uploaded inputs and the HITs' channels).
    std::vector<unsigned char> pending_geometry;
    if (pending_) pending_geometry.assign(upload_.data, upload_.data + upload_bytes_);
    upload(f, 0, PlanCall::Classify);
    run_classify(f);

    const uint32_t* words = reinterpret_cast<const uint32_t*>(quads_.data);
    const uint32_t count = words[RRC_QUAD_LIST_COUNT];
    const uint8_t* mask = readback_.data;  // slot 0 starts with the mask
    if (out.caller && out.quads && count > out.quad_capacity) {
        if (pending_) {
            std::memcpy(upload_.data, pending_geometry.data(), pending_geometry.size());
            run_classify(classified_);
        }
        fail(RRC_ERROR_SIZE_MISMATCH, "output.quad_capacity is %u but %u quads are listed (RRC_QUAD_LIST_BYTES sizes a full list)",
             out.quad_capacity, count);
    }
    if (out.caller) {
        if (out.mask) std::memcpy(out.mask, mask, (size_t)config().width * config().height);
        if (out.quads) std::memcpy(out.quads, words + RRC_QUAD_LIST_FIRST_QUAD, (size_t)count * sizeof(uint32_t));
        write_member(out.caller, offsetof(rrc_classify_output, quad_count), count);
        const Stats stats = count_stats(mask);
        write_member(out.caller, offsetof(rrc_classify_output, stats), stats.counts);
        write_member(out.caller, offsetof(rrc_classify_output, refreshed), stats.refreshed);
    }
    classified_ = f;  // a classification not resolved is dropped
    pending_ = true;
}

void StandaloneContext::resolve(const Frame& channels, const FrameOutputs& out) {
    if (!classified()) fail(RRC_ERROR_INVALID_ARGUMENT, "no classified frame to resolve: call rrc_frame_classify first");
    Frame f = classified_;
    ViewState& view = core_->view(f.view);
    const ViewState& source = core_->view(f.source());
    f.channel_count = channels.channel_count;
    f.channels = channels.channels;
    f.channels_given = channels.channels_given;
    upload(f, 0, PlanCall::Resolve);
    begin();
    record(f, out, 0, view.parity, AccumulatorCore::latest(source), source.have_previous, PlanCall::Resolve);
    VulkanDevice::check(core_->device().vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    submit_and_wait();
    read_back(out, 0, view, view.parity);
    pending_ = false;
    core_->advance(view, 1, f.frame_index);
}

void StandaloneContext::run_frames(const std::vector<Frame>& frames, const std::vector<FrameOutputs>& outputs) {
    const uint32_t count = (uint32_t)frames.size();
    reserve_batch(count);
    for (uint32_t i = 0; i < count; ++i) upload(frames[i], i);
    auto& vk = core_->device().vk;
    // Each view's parity and history as the batch's frames will leave them:
    // a frame writes its view's next set and reads its source's latest.
    const uint32_t views = core_->view_count();
    std::vector<uint32_t> parity(views), written(count);
    std::vector<bool> have(views);
    for (uint32_t v = 0; v < views; ++v) parity[v] = core_->view(v).parity, have[v] = core_->view(v).have_previous;
    begin();
    for (uint32_t i = 0; i < count; ++i) {
        const Frame& f = frames[i];
        const uint32_t v = f.view, s = f.source();
        written[i] = parity[v];
        record(f, outputs[i], i, parity[v], 1 - parity[s], have[s] && !f.reset);
        parity[v] ^= 1u;
        have[v] = true;
    }
    VulkanDevice::check(vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    submit_and_wait();
    for (uint32_t i = 0; i < count; ++i) read_back(outputs[i], i, core_->view(frames[i].view), written[i]);
    // Only now do the frames become history.
    for (uint32_t i = 0; i < count; ++i) core_->advance(core_->view(frames[i].view), 1, frames[i].frame_index);
    pending_ = false;
}

}  // namespace rrc
