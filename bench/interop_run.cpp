#include "interop_run.h"

#include "rrc_interop.h"
#include "stats.h"

#include <cstring>
#include <stdexcept>
#include <tuple>

namespace rrc_bench {

using rrc_host::vk_check;

// (Timer and Submitter are declared in interop_run.h, held by InteropBench.)
// Queries: 0-1 around the kernel's commands, 2-3 around the roof's.
class Timer {
public:
    explicit Timer(VulkanBootstrap& vk) : vk_(vk) {
        if (!vk.timestamps) return;
        VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = 4;
        vk_check(vkCreateQueryPool(vk.device, &qi, nullptr, &pool_), "vkCreateQueryPool");
    }
    ~Timer() {
        if (pool_) vkDestroyQueryPool(vk_.device, pool_, nullptr);
    }
    bool enabled() const { return pool_ != VK_NULL_HANDLE; }
    void reset(VkCommandBuffer cmd, uint32_t first) const {
        if (pool_) vkCmdResetQueryPool(cmd, pool_, first, 2);
    }
    void stamp(VkCommandBuffer cmd, uint32_t query, bool end) const {
        if (pool_) vkCmdWriteTimestamp(cmd, end ? VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT : VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_, query);
    }
    double elapsed_ms(uint32_t first) const {
        uint64_t t[2];
        vk_check(vkGetQueryPoolResults(vk_.device, pool_, first, 2, sizeof t, t, sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                 "vkGetQueryPoolResults");
        return (double)(t[1] - t[0]) * vk_.properties.limits.timestampPeriod * 1e-6;
    }

private:
    VulkanBootstrap& vk_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
};

// Every submission starts by waiting for all earlier work and its writes, so
// the kernel and the roof (which write the same outputs) never overlap.
static void full_barrier(VkCommandBuffer cmd) {
    rrc_host::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                             VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

class Submitter {
public:
    explicit Submitter(VulkanBootstrap& vk) : vk_(vk) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = vk.pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        vk_check(vkAllocateCommandBuffers(vk.device, &ai, &cmd_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vk_check(vkCreateFence(vk.device, &fi, nullptr, &fence_), "vkCreateFence");
    }
    ~Submitter() {
        vkDestroyFence(vk_.device, fence_, nullptr);
        vkFreeCommandBuffers(vk_.device, vk_.pool, 1, &cmd_);
    }
    VkCommandBuffer begin() {
        vk_check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vk_check(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
        return cmd_;
    }
    void submit_and_wait() {
        vk_check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd_;
        vk_check(vkQueueSubmit(vk_.queue, 1, &si, fence_), "vkQueueSubmit");
        vk_check(vkWaitForFences(vk_.device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vk_check(vkResetFences(vk_.device, 1, &fence_), "vkResetFences");
    }

private:
    VulkanBootstrap& vk_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

static rrc_vulkan_image general(const Image& img) { return rrc_host::vulkan_image(img, VK_IMAGE_LAYOUT_GENERAL); }

InteropBench::InteropBench(VulkanBootstrap& vk, const Config& c, const SceneInputs& scene, const BenchImages& img, LogCounter& log)
    : vk_(vk), config_(c), scene_(scene), img_(img) {
    ContextSetup setup(c, log);
    // One frame in flight: the bench waits for every submission.
    const rrc_vulkan_device_desc dd = rrc_host::vulkan_device_desc(vk, 1);
    if (rrc_vulkan_context_create(setup.desc(), &dd, &ctx_) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_vulkan_context_create: ") + rrc_last_error());
    rrc_context_memory_usage(ctx_, &res_.memory_bytes);
    try {
        stats_ = vk.create_buffer(256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "bench stats");
        if (c.shading_cache == Config::Cache::Split || c.shading_cache == Config::Cache::ClassifyFused)
            quads_ = vk.create_buffer(RRC_QUAD_LIST_BYTES(c.width, c.height),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      true, "bench quad list");
        roof_ = std::make_unique<Roof>(vk, c, img);
        res_.roof_bytes_bound = roof_->bound_bytes();
        timer_ = std::make_unique<Timer>(vk);
        sub_ = std::make_unique<Submitter>(vk);
        res_.timestamps = timer_->enabled();
    } catch (...) {
        release();
        throw;
    }
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        auto ci = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
        ci.samples = general(img.samples[ch]);
        if (c.channels[ch].confidence) ci.confidence = general(img.confidence[ch]);
        ci.output = general(img.values[ch]);
        ci.age = general(img.age_out[ch]);
        channels_.push_back(ci);
    }
}

InteropBench::~InteropBench() { release(); }

void InteropBench::release() {
    vkDeviceWaitIdle(vk_.device);
    sub_.reset();
    timer_.reset();
    roof_.reset();
    vk_.destroy(stats_);
    vk_.destroy(quads_);
    rrc_context_destroy(ctx_);
    ctx_ = nullptr;
}

// One kernel frame (pose = frame parity): {GPU ms, wall ms}.  Timed frames
// pass no statistics buffer (the library's default; counting costs the
// kernel time the roof does not spend); one untimed frame at the end does,
// for the hit/miss mix the report gives.
std::pair<double, double> InteropBench::kernel(bool with_stats) {
    const int pose = (int)(frame_ % 2);
    const PoseFrame& pf = scene_.poses[pose];
    auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
    f.frame_index = frame_;
    f.depth = general(img_.poses[pose].depth);
    if (img_.poses[pose].reprojection.image) f.reprojection = general(img_.poses[pose].reprojection);
    if (config_.nocache) f.nocache = general(img_.nocache);
    if (config_.object_id) f.object_id = general(img_.poses[pose].object_id);
    f.mask = general(img_.mask);
    // MOTION's RG32F vectors have no storage binding in the kernel (storage_inputs asks RGBA32F): sampled.
    f.storage_inputs = config_.sampled_inputs || config_.source == RRC_REPROJECTION_MOTION ? 0u : 1u;
    for (int i = 0; i < 16; ++i) {
        f.view_proj[i] = pf.view_proj[i / 4][i % 4];  // column-major, as GLM stores it
        f.prev_view_proj[i] = pf.prev_view_proj[i / 4][i % 4];
    }
    f.channel_count = (uint32_t)channels_.size();
    f.channels = channels_.data();
    if (with_stats) f.stats_buffer = stats_.buffer;
    const double t0 = now_ms();
    f.command_buffer = sub_->begin();
    full_barrier(f.command_buffer);
    timer_->reset(f.command_buffer, 0);
    timer_->stamp(f.command_buffer, 0, false);
    if (config_.shading_cache == Config::Cache::Split || config_.shading_cache == Config::Cache::ClassifyFused) {
        auto list = rrc_host::rrc_struct<rrc_vulkan_quad_list>(RRC_STRUCT_TYPE_VULKAN_QUAD_LIST);
        list.buffer = quads_.buffer;
        const bool split = config_.shading_cache == Config::Cache::Split;
        f.split_outputs = split && config_.split_outputs ? 1u : 0u;
        if (rrc_vulkan_record_classify(ctx_, &f, &list) != RRC_SUCCESS ||
            (split ? rrc_vulkan_record_resolve(ctx_, &f) : rrc_vulkan_record_frame(ctx_, &f)) != RRC_SUCCESS)
            throw std::runtime_error(std::string("rrc_vulkan_record_classify/resolve: ") + rrc_context_last_error(ctx_));
    } else if (rrc_vulkan_record_frame(ctx_, &f) != RRC_SUCCESS) {
        throw std::runtime_error(std::string("rrc_vulkan_record_frame: ") + rrc_context_last_error(ctx_));
    }
    timer_->stamp(f.command_buffer, 1, true);
    sub_->submit_and_wait();
    const double wall = now_ms() - t0;
    ++frame_;
    return {timer_->enabled() ? timer_->elapsed_ms(0) : wall, wall};
}

// One roof dispatch on `pose`'s inputs.
double InteropBench::roof_pass(int pose) {
    const double t0 = now_ms();
    VkCommandBuffer cmd = sub_->begin();
    full_barrier(cmd);
    timer_->reset(cmd, 2);
    timer_->stamp(cmd, 2, false);
    roof_->record(cmd, pose);
    timer_->stamp(cmd, 3, true);
    full_barrier(cmd);  // its writes are done before anything later reads or rewrites them
    sub_->submit_and_wait();
    const double wall = now_ms() - t0;
    return timer_->enabled() ? timer_->elapsed_ms(2) : wall;
}

void InteropBench::prime(int frames) {
    for (int i = 0; i < frames; ++i) kernel(false);
}

void InteropBench::step(bool record) {
    const int pose = (int)(frame_ % 2);  // the roof reads what this pair's kernel frame reads
    double k, w, t;
    if (steps_++ % 2 == 0) {
        std::tie(k, w) = kernel(false);
        t = roof_pass(pose);
    } else {
        t = roof_pass(pose);
        std::tie(k, w) = kernel(false);
    }
    if (!record) return;
    res_.kernel_ms.push_back(k);
    res_.wall_ms.push_back(w);
    res_.roof_ms.push_back(t);
    res_.ratio.push_back(k / t);
}

// Young pixels of the statistics frame: not background (mask) and age <
// kYoungAge in channel 0's age output, the pixels the fill works on
// (docs/CONVENTIONS.md, "The spatial fill").  Read back before the roof
// check rewrites both images.
uint64_t InteropBench::count_young() {
    const VkImageLayout g = VK_IMAGE_LAYOUT_GENERAL;
    const auto age = vk_.download(img_.age_out[0], image_bytes(img_.age_out[0]), g);
    const auto mask = vk_.download(img_.mask, image_bytes(img_.mask), g);
    uint64_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        uint16_t a;
        std::memcpy(&a, &age[2 * i], sizeof a);
        n += !(mask[i] & RRC_MASK_BACKGROUND) && a < kYoungAge;
    }
    return n;
}

InteropResult InteropBench::finish(bool check_roof) {
    kernel(true);
    std::memcpy(&res_.stats, stats_.mapped, sizeof res_.stats);
    if (quads_.mapped) std::memcpy(&res_.listed_quads, quads_.mapped, sizeof res_.listed_quads);
    res_.young = count_young();
    if (check_roof) {
        roof_pass(0);  // the roof is the last writer of the outputs it checks
        res_.roof_check = roof_->check(0);
    } else {
        res_.roof_check = "skipped";
    }
    return res_;
}

}  // namespace rrc_bench
