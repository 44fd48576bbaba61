#include "interop_run.h"

#include "rrc_interop.h"
#include "stats.h"

#include <cstring>
#include <stdexcept>
#include <tuple>

namespace rrc_bench {
namespace {

using rrc_host::vk_check;

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
void full_barrier(VkCommandBuffer cmd) {
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

rrc_vulkan_image general(const Image& img) { return rrc_host::vulkan_image(img, VK_IMAGE_LAYOUT_GENERAL); }

}  // namespace

InteropResult run_interop(VulkanBootstrap& vk, const Config& c, const SceneInputs& scene, BenchImages& img, LogCounter& log, int reps,
                          int warmup, bool check_roof, const std::function<void(bool)>& between) {
    InteropResult res;
    ContextSetup setup(c, log);
    // One frame in flight: the bench waits for every submission.
    const rrc_vulkan_device_desc dd = rrc_host::vulkan_device_desc(vk, 1);
    rrc_context* ctx = nullptr;
    if (rrc_vulkan_context_create(setup.desc(), &dd, &ctx) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_vulkan_context_create: ") + rrc_last_error());
    rrc_context_memory_usage(ctx, &res.memory_bytes);

    rrc_host::Buffer stats = vk.create_buffer(256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "bench stats");
    try {
        Roof roof(vk, c, img);
        res.roof_bytes_bound = roof.bound_bytes();
        Timer timer(vk);
        Submitter sub(vk);
        res.timestamps = timer.enabled();

        std::vector<rrc_vulkan_channel_images> channels;
        for (size_t ch = 0; ch < c.channels.size(); ++ch) {
            auto ci = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
            ci.samples = general(img.samples[ch]);
            if (c.channels[ch].confidence) ci.confidence = general(img.confidence[ch]);
            ci.output = general(img.values[ch]);
            ci.age = general(img.age_out[ch]);
            channels.push_back(ci);
        }

        uint64_t frame = 0;
        // One kernel frame (pose = frame parity): {GPU ms, wall ms}.  Timed
        // frames pass no statistics buffer (the library's default; counting
        // costs the kernel time the roof does not spend); one untimed frame
        // at the end does, for the hit/miss mix the report gives.
        auto kernel = [&](bool with_stats = false) {
            const int pose = (int)(frame % 2);
            const PoseFrame& pf = scene.poses[pose];
            auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
            f.frame_index = frame;
            f.depth = general(img.poses[pose].depth);
            if (img.poses[pose].reprojection.image) f.reprojection = general(img.poses[pose].reprojection);
            if (c.nocache) f.nocache = general(img.nocache);
            if (c.object_id) f.object_id = general(img.poses[pose].object_id);
            f.mask = general(img.mask);
            for (int i = 0; i < 16; ++i) {
                f.view_proj[i] = pf.view_proj[i / 4][i % 4];  // column-major, as GLM stores it
                f.prev_view_proj[i] = pf.prev_view_proj[i / 4][i % 4];
            }
            f.channel_count = (uint32_t)channels.size();
            f.channels = channels.data();
            if (with_stats) f.stats_buffer = stats.buffer;
            const double t0 = now_ms();
            f.command_buffer = sub.begin();
            full_barrier(f.command_buffer);
            timer.reset(f.command_buffer, 0);
            timer.stamp(f.command_buffer, 0, false);
            if (rrc_vulkan_record_frame(ctx, &f) != RRC_SUCCESS)
                throw std::runtime_error(std::string("rrc_vulkan_record_frame: ") + rrc_context_last_error(ctx));
            timer.stamp(f.command_buffer, 1, true);
            sub.submit_and_wait();
            const double wall = now_ms() - t0;
            ++frame;
            return std::make_pair(timer.enabled() ? timer.elapsed_ms(0) : wall, wall);
        };
        // One roof dispatch on the pose of the frame just recorded (or about to be).
        auto roof_pass = [&](int pose) {
            const double t0 = now_ms();
            VkCommandBuffer cmd = sub.begin();
            full_barrier(cmd);
            timer.reset(cmd, 2);
            timer.stamp(cmd, 2, false);
            roof.record(cmd, pose);
            timer.stamp(cmd, 3, true);
            full_barrier(cmd);  // its writes are done before anything later reads or rewrites them
            sub.submit_and_wait();
            const double wall = now_ms() - t0;
            return timer.enabled() ? timer.elapsed_ms(2) : wall;
        };

        // Warm-up: lavapipe compiles each pipeline at its first dispatch, and
        // the first frames have no history yet (every pixel misses).
        for (int i = 0; i < warmup; ++i) {
            kernel();
            roof_pass(0);
            if (between) between(false);
        }
        for (int r = 0; r < reps; ++r) {
            const int pose = (int)(frame % 2);
            double k, w, t;
            if (r % 2 == 0) {
                std::tie(k, w) = kernel();
                t = roof_pass(pose);
            } else {
                t = roof_pass(pose);
                std::tie(k, w) = kernel();
            }
            res.kernel_ms.push_back(k);
            res.wall_ms.push_back(w);
            res.roof_ms.push_back(t);
            res.ratio.push_back(k / t);
            if (between) between(true);
        }
        kernel(true);
        std::memcpy(&res.stats, stats.mapped, sizeof res.stats);
        if (check_roof) {
            roof_pass(0);  // the roof is the last writer of the outputs it checks
            res.roof_check = roof.check(0);
        } else {
            res.roof_check = "skipped";
        }
    } catch (...) {
        vkDeviceWaitIdle(vk.device);
        rrc_context_destroy(ctx);
        vk.destroy(stats);
        throw;
    }
    vkDeviceWaitIdle(vk.device);
    rrc_context_destroy(ctx);
    vk.destroy(stats);
    return res;
}

}  // namespace rrc_bench
