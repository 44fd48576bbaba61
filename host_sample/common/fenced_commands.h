// One reusable command buffer and the fence its submission signals, and the
// timestamp query pool that times it: what rrc-sample's Renderer, rrc-sweep's
// Engine, rrc-cache's Bench and rrc-bench's interop run each used to set up
// and tear down themselves.  All four record a frame, submit it and wait for
// it before recording the next (one submission in flight), so one buffer and
// one fence suffice; the bootstrap's own begin()/submit_and_wait() allocate a
// fresh buffer per call and wait for the whole queue, which suits one-time
// uploads, not a loop that times its frames.
#pragma once

#include "vulkan_bootstrap.h"

#include <cstdint>
#include <vector>

namespace rrc_host {

/** Every command before it, and its writes, before anything after it reads or
 *  writes: the barrier each of those programs starts a submission with. */
void full_barrier(VkCommandBuffer cmd);

/** One primary command buffer from the bootstrap's pool (created with
 *  RESET_COMMAND_BUFFER, so it can be reset alone) and an unsignalled fence. */
class FencedCommands {
public:
    explicit FencedCommands(VulkanBootstrap& vk);  // throws std::runtime_error
    ~FencedCommands();
    FencedCommands(const FencedCommands&) = delete;
    FencedCommands& operator=(const FencedCommands&) = delete;

    /** Resets the buffer (its last submission has been waited for) and begins
     *  it for one submission (ONE_TIME_SUBMIT). */
    VkCommandBuffer begin();
    /** Ends, submits and waits for the fence, then resets it; returns the wall
     *  clock from vkQueueSubmit to the fence signalled, in milliseconds. */
    double submit_and_wait();

private:
    VulkanBootstrap& vk_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

/** `count` timestamp queries; none where the queue family has no valid
 *  timestamp bits (vkCmdWriteTimestamp is not allowed there: Vulkan spec,
 *  "Timestamp Queries"), and then every call but enabled() does nothing. */
class TimestampQueries {
public:
    TimestampQueries(VulkanBootstrap& vk, uint32_t count);  // throws std::runtime_error
    ~TimestampQueries();
    TimestampQueries(const TimestampQueries&) = delete;
    TimestampQueries& operator=(const TimestampQueries&) = delete;

    bool enabled() const { return pool_ != VK_NULL_HANDLE; }
    void reset(VkCommandBuffer cmd, uint32_t first, uint32_t count) const;
    void write(VkCommandBuffer cmd, VkPipelineStageFlagBits stage, uint32_t query) const;
    /** Queries first..first+count-1 in ticks (timestampPeriod ns each), waiting for them. */
    std::vector<uint64_t> ticks(uint32_t first, uint32_t count) const;

private:
    VulkanBootstrap& vk_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
};

}  // namespace rrc_host
