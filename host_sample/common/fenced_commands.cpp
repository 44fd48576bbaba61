#include "fenced_commands.h"

#include <chrono>

namespace rrc_host {

void full_barrier(VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                   VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

FencedCommands::FencedCommands(VulkanBootstrap& vk) : vk_(vk) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = vk.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    vk_check(vkAllocateCommandBuffers(vk.device, &ai, &cmd_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    const VkResult r = vkCreateFence(vk.device, &fi, nullptr, &fence_);
    if (r != VK_SUCCESS) vkFreeCommandBuffers(vk.device, vk.pool, 1, &cmd_);
    vk_check(r, "vkCreateFence");
}

FencedCommands::~FencedCommands() {
    vkDestroyFence(vk_.device, fence_, nullptr);
    vkFreeCommandBuffers(vk_.device, vk_.pool, 1, &cmd_);
}

VkCommandBuffer FencedCommands::begin() {
    vk_check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    return cmd_;
}

double FencedCommands::submit_and_wait() {
    vk_check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    const auto t0 = std::chrono::steady_clock::now();
    vk_check(vkQueueSubmit(vk_.queue, 1, &si, fence_), "vkQueueSubmit");
    vk_check(vkWaitForFences(vk_.device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    vk_check(vkResetFences(vk_.device, 1, &fence_), "vkResetFences");
    return ms;
}

TimestampQueries::TimestampQueries(VulkanBootstrap& vk, uint32_t count) : vk_(vk) {
    if (!vk.timestamps) return;
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = count;
    vk_check(vkCreateQueryPool(vk.device, &qi, nullptr, &pool_), "vkCreateQueryPool");
}

TimestampQueries::~TimestampQueries() {
    if (pool_) vkDestroyQueryPool(vk_.device, pool_, nullptr);
}

void TimestampQueries::reset(VkCommandBuffer cmd, uint32_t first, uint32_t count) const {
    if (pool_) vkCmdResetQueryPool(cmd, pool_, first, count);
}

void TimestampQueries::write(VkCommandBuffer cmd, VkPipelineStageFlagBits stage, uint32_t query) const {
    if (pool_) vkCmdWriteTimestamp(cmd, stage, pool_, query);
}

std::vector<uint64_t> TimestampQueries::ticks(uint32_t first, uint32_t count) const {
    std::vector<uint64_t> t(count);
    if (!pool_ || count == 0) return t;
    vk_check(vkGetQueryPoolResults(vk_.device, pool_, first, count, count * sizeof(uint64_t), t.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
             "vkGetQueryPoolResults");
    return t;
}

}  // namespace rrc_host
