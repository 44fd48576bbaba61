#include "standalone_context.h"

#include "error.h"
#include "frame_constants.h"
#include "validation.h"

#include <glm/gtc/packing.hpp>

#include <cstring>

namespace rrc {
namespace {

size_t align16(size_t x) { return (x + 15) & ~size_t(15); }

VkImageSubresourceLayers color_layers() { return {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}; }

void memory_barrier(const VolkDeviceTable& vk, VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    vk.vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace

StandaloneContext::StandaloneContext(const ContextConfig& config) : config_(config) {
    Log log{config.log, config.log_user};
    dev_.reset(new VulkanDevice(config.device_name, config.validation, log));
    try {
        pipeline_.reset(new AccumulatePipeline(*dev_, config_, /*interop=*/false, /*sets=*/2));
        create_images();
        auto& vk = dev_->vk;
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pci.queueFamilyIndex = dev_->queue_family;
        VulkanDevice::check(vk.vkCreateCommandPool(dev_->device, &pci, nullptr, &pool_), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool_;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        VulkanDevice::check(vk.vkAllocateCommandBuffers(dev_->device, &cai, &cmd_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VulkanDevice::check(vk.vkCreateFence(dev_->device, &fci, nullptr, &fence_), "vkCreateFence");
        sets_[0] = pipeline_->allocate_set();
        sets_[1] = pipeline_->allocate_set();
        write_descriptor_sets();
        initialise_images();
        log(RRC_LOG_INFO, "rrc: context " + std::to_string(config_.width) + "x" + std::to_string(config_.height) + " on " + dev_->name);
    } catch (...) {
        // Members are destroyed in reverse order; the device goes last.
        if (fence_) dev_->vk.vkDestroyFence(dev_->device, fence_, nullptr);
        if (pool_) dev_->vk.vkDestroyCommandPool(dev_->device, pool_, nullptr);
        throw;
    }
}

StandaloneContext::~StandaloneContext() {
    if (dev_ && dev_->device) {
        dev_->vk.vkDeviceWaitIdle(dev_->device);
        if (fence_) dev_->vk.vkDestroyFence(dev_->device, fence_, nullptr);
        if (pool_) dev_->vk.vkDestroyCommandPool(dev_->device, pool_, nullptr);
    }
    // Resources must go before the device: release them explicitly.
    placeholders_.reset();
    channels_.clear();
    depth_[0] = GpuImage();
    depth_[1] = GpuImage();
    reprojection_ = GpuImage();
    nocache_ = GpuImage();
    mask_ = GpuImage();
    upload_ = HostBuffer();
    readback_ = HostBuffer();
    pipeline_.reset();
    dev_.reset();
}

void StandaloneContext::create_images() {
    VulkanDevice& d = *dev_;
    const uint32_t w = config_.width, h = config_.height;
    size_t up = 0, down = 0;
    for (auto& img : depth_) img = GpuImage(d, VK_FORMAT_R32_SFLOAT, w, h);
    up += align16(depth_[0].bytes());
    if (config_.reprojection == RRC_REPROJECTION_MOTION) reprojection_ = GpuImage(d, VK_FORMAT_R32G32_SFLOAT, w, h);
    if (config_.reprojection == RRC_REPROJECTION_PREV_CLIP || config_.reprojection == RRC_REPROJECTION_MOTION_DEPTH)
        reprojection_ = GpuImage(d, VK_FORMAT_R32G32B32A32_SFLOAT, w, h);
    up += align16(reprojection_.bytes());
    if (config_.use_nocache) nocache_ = GpuImage(d, VK_FORMAT_R8_UINT, w, h);
    up += align16(nocache_.bytes());
    mask_ = GpuImage(d, VK_FORMAT_R8_UINT, w, h);
    down += align16(mask_.bytes());
    channels_.resize(config_.channels.size());
    for (size_t i = 0; i < channels_.size(); ++i) {
        const ChannelConfig& cc = config_.channels[i];
        Channel& ch = channels_[i];
        ch.samples = GpuImage(d, cc.components == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT, w, h);
        up += align16(ch.samples.bytes());
        if (cc.confidence) ch.confidence = GpuImage(d, VK_FORMAT_R32_SFLOAT, w, h);
        up += align16(ch.confidence.bytes());
        ch.state.reset(new ChannelHistory(d, cc, w, h));
        down += align16(ch.state->history[0].bytes()) + align16(ch.state->age[0].bytes()) + align16(ch.state->weight[0].bytes());
    }
    placeholders_.reset(new Placeholders(d));
    upload_bytes_ = up;
    readback_bytes_ = down;
    reserve_batch(1);
}

// Staging holds one region per frame of a batch; it grows to the largest batch.
void StandaloneContext::reserve_batch(uint32_t frames) {
    if (frames <= batch_capacity_) return;
    upload_ = HostBuffer(*dev_, upload_bytes_ * frames, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    readback_ = HostBuffer(*dev_, readback_bytes_ * frames, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    batch_capacity_ = frames;
}

void StandaloneContext::write_descriptor_sets() {
    for (uint32_t p = 0; p < 2; ++p) {
        DescriptorViews v = placeholders_->views();
        const uint32_t prev = 1 - p;
        v.view[kDepth][0] = depth_[p].view;
        v.view[kPrevDepth][0] = depth_[prev].view;
        if (reprojection_.format == VK_FORMAT_R32G32B32A32_SFLOAT) v.view[kReproj][0] = reprojection_.view;
        if (reprojection_.format == VK_FORMAT_R32G32_SFLOAT) v.view[kMotion][0] = reprojection_.view;
        if (nocache_.view) v.view[kNocache][0] = nocache_.view;
        v.view[kMask][0] = mask_.view;
        for (uint32_t s = 0; s < channels_.size(); ++s) {
            Channel& ch = channels_[s];
            v.view[ch.samples.format == VK_FORMAT_R32_SFLOAT ? kSample1 : kSample4][s] = ch.samples.view;
            if (ch.confidence.view) v.view[kConfidence][s] = ch.confidence.view;
            bind_history(v, s, *ch.state, p);
        }
        pipeline_->write_set(sets_[p], v);
    }
}

// One submission at creation: every image to GENERAL, cleared.
void StandaloneContext::initialise_images() {
    auto& vk = dev_->vk;
    std::vector<GpuImage*> all = {&depth_[0], &depth_[1], &reprojection_, &nocache_, &mask_};
    for (auto& ch : channels_) {
        all.insert(all.end(), {&ch.samples, &ch.confidence});
        ch.state->collect(all);
    }
    placeholders_->collect(all);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VulkanDevice::check(vk.vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    record_initialise(*dev_, cmd_, all);
    VulkanDevice::check(vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    submit_and_wait();
}

void StandaloneContext::upload(const rrc_frame_desc& f, uint32_t slot) {
    const size_t n = (size_t)config_.width * config_.height;
    unsigned char* dst = upload_.data + slot * upload_bytes_;
    auto put = [&](const void* src, size_t bytes) {
        std::memcpy(dst, src, bytes);
        dst += align16(bytes);
    };
    put(f.depth, n * sizeof(float));
    if (config_.reprojection == RRC_REPROJECTION_MOTION_DEPTH) {
        float* out = reinterpret_cast<float*>(dst);  // 3 floats a pixel to RGBA
        for (size_t i = 0; i < n; ++i) {
            std::memcpy(out + 4 * i, f.reprojection + 3 * i, 3 * sizeof(float));
            out[4 * i + 3] = 0.0f;
        }
        dst += align16(reprojection_.bytes());
    } else if (reprojection_.image) {
        put(f.reprojection, reprojection_.bytes());
    }
    if (nocache_.image) put(f.nocache, n);
    for (size_t i = 0; i < channels_.size(); ++i) {
        put(f.channels[i].samples, channels_[i].samples.bytes());
        if (channels_[i].confidence.image) put(f.channels[i].confidence, n * sizeof(float));
    }
}

template <typename F>
void StandaloneContext::for_each_readback(const rrc_frame_output* out, uint32_t parity, uint32_t slot, F&& f) {
    // Fixed offsets in the slot's region of the readback buffer, in creation
    // order; only the requested images are copied.
    size_t offset = slot * readback_bytes_;
    f(mask_, offset, true, nullptr, -1);
    offset += align16(mask_.bytes());
    for (size_t i = 0; i < channels_.size(); ++i) {
        const rrc_channel_output* co = out && out->channel_count ? &out->channels[i] : nullptr;
        Channel& ch = channels_[i];
        const ChannelHistory& h = *ch.state;
        f(h.history[parity], offset, co && co->values, co ? (void*)co->values : nullptr, (int)i);
        offset += align16(h.history[parity].bytes());
        f(h.age[parity], offset, co && co->age, co ? (void*)co->age : nullptr, (int)i);
        offset += align16(h.age[parity].bytes());
        f(h.weight[parity], offset, co && co->weight, co ? (void*)co->weight : nullptr, (int)i);
        offset += align16(h.weight[parity].bytes());
    }
}

void StandaloneContext::record(const rrc_frame_desc& f, const rrc_frame_output* out, uint32_t slot, uint32_t parity, bool prev_valid) {
    auto& vk = dev_->vk;
    std::vector<const GpuImage*> inputs = {&depth_[parity], &reprojection_, &nocache_};
    for (auto& ch : channels_) inputs.insert(inputs.end(), {&ch.samples, &ch.confidence});
    std::vector<const GpuImage*> outputs;
    for_each_readback(out, parity, slot, [&](const GpuImage& img, size_t, bool wanted, void*, int) {
        if (wanted) outputs.push_back(&img);
    });

    // 1. The previous frame's writes become visible to this dispatch, and its
    //    reads finish before this frame overwrites its inputs.  Inputs are
    //    fully overwritten: their old contents are discarded (UNDEFINED).
    memory_barrier(vk, cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    transition(inputs, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_ACCESS_TRANSFER_WRITE_BIT);
    size_t offset = slot * upload_bytes_;
    for (const GpuImage* img : inputs) {
        if (!img->image) continue;
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = color_layers();
        r.imageExtent = {img->width, img->height, 1};
        vk.vkCmdCopyBufferToImage(cmd_, upload_.buffer, img->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
        offset += align16(img->bytes());
    }
    // 2. Uploaded inputs to the kernel.
    transition(inputs, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    FramePushConstants pc = make_frame_constants(config_, f, prev_valid);
    pipeline_->record(cmd_, sets_[parity], pc, config_.width, config_.height);
    // 3. Requested outputs to the copy, then back to GENERAL: next frame's
    //    kernel reads them as history.
    transition(outputs, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    for_each_readback(out, parity, slot, [&](const GpuImage& img, size_t at, bool wanted, void*, int) {
        if (!img.image || !wanted) return;
        VkBufferImageCopy r{};
        r.bufferOffset = at;
        r.imageSubresource = color_layers();
        r.imageExtent = {img.width, img.height, 1};
        vk.vkCmdCopyImageToBuffer(cmd_, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer, 1, &r);
    });
    transition(outputs, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    memory_barrier(vk, cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                   VK_ACCESS_HOST_READ_BIT);
}

void StandaloneContext::transition(const std::vector<const GpuImage*>& images, VkImageLayout from, VkImageLayout to,
                                   VkPipelineStageFlags src_stage, VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                                   VkAccessFlags dst_access) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (const GpuImage* img : images) {
        if (!img->image) continue;
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = src_access;
        b.dstAccessMask = dst_access;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img->image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        barriers.push_back(b);
    }
    if (barriers.empty()) return;
    dev_->vk.vkCmdPipelineBarrier(cmd_, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, (uint32_t)barriers.size(), barriers.data());
}

void StandaloneContext::submit_and_wait() {
    auto& vk = dev_->vk;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    VulkanDevice::check(vk.vkQueueSubmit(dev_->queue, 1, &si, fence_), "vkQueueSubmit");
    VkResult r = vk.vkWaitForFences(dev_->device, 1, &fence_, VK_TRUE, 120ull * 1000 * 1000 * 1000);
    if (r == VK_TIMEOUT) fail(RRC_ERROR_DEVICE_LOST, "the frame did not finish within 120 s");
    VulkanDevice::check(r, "vkWaitForFences");
    VulkanDevice::check(vk.vkResetFences(dev_->device, 1, &fence_), "vkResetFences");
}

void StandaloneContext::read_back(rrc_frame_output* out, uint32_t slot, uint32_t parity) {
    const size_t n = (size_t)config_.width * config_.height;
    rrc_frame_stats stats{};
    const uint8_t* mask = readback_.data + slot * readback_bytes_;
    for (size_t i = 0; i < n; ++i) {
        uint8_t m = mask[i];
        stats.hits += (m & RRC_MASK_HIT) ? 1 : 0;
        stats.background += (m & RRC_MASK_BACKGROUND) ? 1 : 0;
        stats.invalid_samples += (m & RRC_MASK_INVALID_SAMPLE) ? 1 : 0;
        stats.invalid_geometry += (m & RRC_MASK_INVALID_GEOMETRY) ? 1 : 0;
    }
    stats.misses = n - stats.background - stats.hits;
    if (!out) return;
    for_each_readback(out, parity, slot, [&](const GpuImage& img, size_t at, bool wanted, void* dst, int channel) {
        if (!img.image || !wanted) return;
        const unsigned char* src = readback_.data + at;
        if (channel >= 0 && img.format == VK_FORMAT_R16_SFLOAT) {
            const uint16_t* h = reinterpret_cast<const uint16_t*>(src);
            float* d = static_cast<float*>(dst);
            for (size_t i = 0; i < n; ++i) d[i] = glm::unpackHalf1x16(h[i]);
        } else if (channel >= 0 && img.format == VK_FORMAT_R16G16B16A16_SFLOAT) {
            const uint16_t* h = reinterpret_cast<const uint16_t*>(src);
            float* d = static_cast<float*>(dst);
            for (size_t i = 0; i < 4 * n; ++i) d[i] = glm::unpackHalf1x16(h[i]);
        } else if (dst) {
            std::memcpy(dst, src, img.bytes());
        }
    });
    if (out->mask) std::memcpy(out->mask, mask, n);
    out->stats = stats;
}

size_t StandaloneContext::memory_bytes() const {
    size_t bytes = 2 * depth_[0].bytes() + reprojection_.bytes() + nocache_.bytes() + mask_.bytes() + upload_.size + readback_.size;
    for (const Channel& ch : channels_) bytes += ch.samples.bytes() + ch.confidence.bytes() + ch.state->bytes();
    return bytes;
}

void StandaloneContext::run_frames(uint32_t count, const rrc_frame_desc* frames, rrc_frame_output* outputs) {
    reserve_batch(count);
    for (uint32_t i = 0; i < count; ++i) upload(frames[i], i);
    auto& vk = dev_->vk;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VulkanDevice::check(vk.vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    // Frame i writes the image set of parity parity_ ^ (i & 1) and reads the other.
    for (uint32_t i = 0; i < count; ++i) record(frames[i], outputs ? &outputs[i] : nullptr, i, parity_ ^ (i & 1u), have_previous_ || i > 0);
    VulkanDevice::check(vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    submit_and_wait();
    for (uint32_t i = 0; i < count; ++i) read_back(outputs ? &outputs[i] : nullptr, i, parity_ ^ (i & 1u));
    // Only now do the frames become history.
    parity_ ^= count & 1u;
    have_previous_ = true;
}

}  // namespace rrc
