// A context in standalone mode: the library's own device, CPU arrays in and
// out.  Owns the ping-pong history, age, weight and previous depth, the
// per-frame input images and the staging buffers.
#pragma once

#include "accumulate_pipeline.h"
#include "channel_history.h"
#include "config.h"
#include "gpu_resources.h"
#include "vulkan_device.h"

#include <memory>
#include <vector>

namespace rrc {

class StandaloneContext {
public:
    explicit StandaloneContext(const ContextConfig& config);
    ~StandaloneContext();

    // Runs already validated frames in one submission and fills `outputs`
    // (NULL, or one per frame).  Throws rrc::Error; a failure before the
    // submission leaves history and parity untouched.
    void run_frames(uint32_t count, const rrc_frame_desc* frames, rrc_frame_output* outputs);

    const ContextConfig& config() const { return config_; }
    const VulkanDevice& device() const { return *dev_; }
    size_t memory_bytes() const;

private:
    struct Channel {
        GpuImage samples, confidence;  // this frame's inputs
        std::unique_ptr<ChannelHistory> state;
    };
    void create_images();
    void write_descriptor_sets();
    void initialise_images();
    void reserve_batch(uint32_t frames);
    void upload(const rrc_frame_desc& frame, uint32_t slot);
    void record(const rrc_frame_desc& frame, const rrc_frame_output* output, uint32_t slot, uint32_t parity, bool prev_valid);
    void submit_and_wait();
    void transition(const std::vector<const GpuImage*>& images, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags src_stage,
                    VkAccessFlags src_access, VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);
    void read_back(rrc_frame_output* output, uint32_t slot, uint32_t parity);
    template <typename F>
    void for_each_readback(const rrc_frame_output* output, uint32_t parity, uint32_t slot, F&& f);

    ContextConfig config_;
    std::unique_ptr<VulkanDevice> dev_;
    std::unique_ptr<AccumulatePipeline> pipeline_;
    GpuImage depth_[2];  // [parity]: this frame's depth; the other is the previous frame's
    GpuImage reprojection_, nocache_, mask_;
    std::vector<Channel> channels_;
    std::unique_ptr<Placeholders> placeholders_;
    HostBuffer upload_, readback_;  // batch_capacity_ regions of *_bytes_ each
    size_t upload_bytes_ = 0, readback_bytes_ = 0;
    uint32_t batch_capacity_ = 0;
    VkDescriptorSet sets_[2] = {};
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    uint32_t parity_ = 0;  // the image set this frame writes
    bool have_previous_ = false;
};

}  // namespace rrc
