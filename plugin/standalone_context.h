// A context in standalone mode: the library's own device, CPU arrays in and
// out.  Over the shared accumulator core it owns only what this path adds:
// its copies of the frame's inputs, the staging buffers, and the command
// buffer and fence it submits and waits with.
#pragma once

#include "accumulator_core.h"
#include "frame.h"
#include "gpu_resources.h"

#include <map>
#include <memory>
#include <vector>

namespace rrc {

class StandaloneContext {
public:
    explicit StandaloneContext(const ContextConfig& config);
    ~StandaloneContext();

    // Runs already validated frames in one submission and fills `outputs`
    // (one per frame; an entry with caller == NULL reads nothing back).
    // Throws rrc::Error; a failure before the submission leaves history and
    // parity untouched.
    void run_frames(const std::vector<Frame>& frames, const std::vector<FrameOutputs>& outputs);

    // The shading cache's split frame (rrc_frame_classify, rrc_frame_resolve).
    // classify: geometry inputs in, mask and quad list out; history unchanged.
    // resolve: `channels` holds the host's samples (its geometry is the
    // classified frame's); completes the frame.  Throws rrc::Error.
    struct Classified {
        rrc_classify_output* caller = nullptr;
        uint8_t* mask = nullptr;
        uint32_t* quads = nullptr;
        uint32_t quad_capacity = 0;
    };
    void classify(const Frame& frame, const Classified& out);
    bool classified() const { return pending_; }
    void resolve(const Frame& channels, const FrameOutputs& out);

    const ContextConfig& config() const { return core_->config(); }
    const VulkanDevice& device() const { return core_->device(); }
    size_t memory_bytes() const;

private:
    // One readback target: a library image and where its bytes go.
    struct Readback {
        const GpuImage* image;
        void* destination;               // NULL: not requested
        uint16_t* age_destination = nullptr;  // a packed history's ages (its value|age words split on the CPU)
    };
    std::vector<Readback> readbacks(const FrameOutputs& out, const ViewState& view, uint32_t parity) const;
    size_t readback_bytes() const;
    // The image live input `input` is uploaded into for the frame writing `parity`.
    const GpuImage& own_input(const ViewState& view, size_t input, uint32_t parity) const;
    // The set of a frame that writes `parity` of `view` and reads `source`'s
    // set `source_parity`: made and written the first time it is needed.
    // A fill's displayed values are its host outputs.
    DescriptorSets set_for(uint32_t view, uint32_t parity, uint32_t source, uint32_t source_parity);
    // Classify's submission for a frame whose geometry is staged in slot 0.
    void run_classify(const Frame& frame);
    void initialise_images();
    void reserve_batch(uint32_t frames);
    // Which inputs a call uploads: all (Run), the geometry (Classify) or the channels' (Resolve).
    bool uploads(const LiveInput& in, PlanCall call) const;
    void upload(const Frame& frame, uint32_t slot, PlanCall call = PlanCall::Run);
    // Frame `frame` into `slot` of the staging buffers, writing its view's
    // `parity` and reading its source's `source_parity`.
    void record(const Frame& frame, const FrameOutputs& out, uint32_t slot, uint32_t parity, uint32_t source_parity, bool prev_valid,
                PlanCall call = PlanCall::Run);
    void begin();
    struct Stats {
        rrc_frame_stats counts;
        uint64_t refreshed;
    };
    Stats count_stats(const uint8_t* mask) const;
    void submit_and_wait();
    void read_back(const FrameOutputs& out, uint32_t slot, const ViewState& view, uint32_t parity);

    std::unique_ptr<AccumulatorCore> core_;
    std::vector<GpuImage> inputs_;  // one per core_->inputs() entry, except Depth (the view's depth[parity])
    std::vector<GpuImage> display_; // per channel: the fill's displayed values (empty without a fill)
    HostBuffer upload_, readback_;  // batch_capacity_ regions of *_bytes_ each
    HostBuffer quads_;              // classify's quad list (rrc_values.h layout), read on the CPU
    Frame classified_;              // the classified frame's parameters, for resolve's push constants
    bool pending_ = false;          // classified_ awaits its resolve (any other frame drops it)
    size_t upload_bytes_ = 0, readback_bytes_ = 0;
    uint32_t batch_capacity_ = 0;
    std::map<uint32_t, DescriptorSets> sets_;  // by (view, parity, source, source parity)
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace rrc
