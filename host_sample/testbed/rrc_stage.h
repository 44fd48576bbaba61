// rrc inside the sample's own device and command buffer (rrc_vulkan.h):
// one channel per signal the scene uses, configured here, recorded after
// the signal passes.  Owns the accumulated output images and the mask.
#pragma once

#include "channel_presets.h"
#include "frame_state.h"
#include "gpu.h"
#include "raster.h"
#include "signals.h"

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <string>
#include <vector>

namespace rrc_sample {

struct RrcSettings {
    uint32_t width = 0, height = 0;
    uint32_t signals = 0;  // one channel per bit, in the order pcf, env, soft
    uint32_t reprojection = RRC_REPROJECTION_PREV_CLIP;
    float epsilon_scale = 0.0f;  // 0 = none given: the library's default test
    uint32_t depth_test = 0;     // RRC_DEPTH_TEST_*; 0 = the library's default (ADAPTIVE for a 0.2 caller with no epsilon)
    float near_plane = 0.1f, far_plane = 200.0f;
    ChannelPresets channels;
    bool use_object_id = true;  // rrc_context_desc.use_object_id: the G-buffer's object id image goes to rrc
    // With a view lobe: each frame's lighting_turn (FrameState, the environment map's turn) goes to rrc.
    bool lighting_turn = true;
    // rrc writes each channel's age into age() (an optional output, which costs a store a pixel).
    bool ages = true;
};

/** The channel descriptions for the signals, in the order pcf, env, soft. */
std::vector<rrc_channel_desc> channel_descs(uint32_t signals, const ChannelPresets& presets);

class RrcStage {
public:
    RrcStage(Gpu& gpu, const RrcSettings& settings);  // throws std::runtime_error with rrc's message
    ~RrcStage();
    RrcStage(const RrcStage&) = delete;
    RrcStage& operator=(const RrcStage&) = delete;

    /** Records rrc's barriers and its dispatches.  reset: every pixel misses.  pcf_confidence:
     *  the pcf channel's confidence image (required iff its settings have confidence);
     *  soft_fallback: the soft channel's fill fallback, the PCSS estimate (required iff its
     *  fill_prior > 0), already written (and made visible) by the caller. */
    void record(VkCommandBuffer cmd, const GBuffer& g, const SignalImages& samples, const FrameState& state, uint64_t frame_index,
                bool reset, const Image* pcf_confidence = nullptr, const Image* soft_fallback = nullptr,
                const Image* env_base = nullptr, const Image* pcf_base = nullptr);

    const SignalImages& accumulated() const { return out_; }
    /** rrc's age of each channel after the frame (R16_UINT; rrc_vulkan_channel_images.age): the
     *  samples its history holds, shortened where a cure shortened it (docs/CONVENTIONS.md). */
    const Image& age(uint32_t signal) const { return signal == kSignalPcf ? ages_[0] : signal == kSignalEnv ? ages_[1] : ages_[2]; }
    const Image& mask() const { return mask_; }
    const std::vector<rrc_channel_desc>& channels() const { return channels_; }
    uint64_t memory_bytes() const;

private:
    Gpu& gpu_;
    RrcSettings settings_;
    std::vector<rrc_channel_desc> channels_;
    rrc_context* ctx_ = nullptr;
    SignalImages out_;
    Image ages_[3];  // pcf, env, soft
    Image mask_;
};

}  // namespace rrc_sample
