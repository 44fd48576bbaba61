// After rrc: the host's age map, the soft-shadow fallback (PCSS on misses),
// and the composed frames (accumulated signals; on checkpoints also the raw
// and the reference signals, for side-by-side pictures).
#pragma once

#include "channel_presets.h"
#include "kernel.h"
#include "raster.h"
#include "signals.h"

namespace rrc_sample {

enum ComposeInput : uint32_t { kComposeAccumulated = 0, kComposeRaw = 1, kComposeReference = 2 };

/** Display-only remaps of the accumulated PCF (compose.comp): never fed back to rrc. */
struct PcfDisplay {
    bool smoothstep = false;
    float e0 = 0.0f, e1 = 1.0f;
    float threshold = -1.0f;  // < 0: off
    bool any() const { return smoothstep || threshold >= 0.0f; }
    /** The same remap on the CPU (the metrics score what is shown). */
    float apply(float v) const;
};

class PostPasses {
public:
    /** soft_age: rrc's age of the soft channel (RrcStage::age), the n of the --soft-prior blend. */
    PostPasses(Gpu& gpu, const GpuScene& scene, const GBuffer& g, const ShadowMaps& maps, const Image& mask, const Image& soft_age,
               const SignalImages& accumulated, const SignalImages& raw, const SignalImages& reference, uint32_t width, uint32_t height,
               bool soft_fill = false, const PcfDisplay& pcf_display = {});
    ~PostPasses();
    PostPasses(const PostPasses&) = delete;
    PostPasses& operator=(const PostPasses&) = delete;

    /** The track age (age.comp: consecutive hits, frame parity selects the ping-pong side) and, with
     *  soft shadows, the fallback. */
    void record_age_and_fallback(VkCommandBuffer cmd, uint32_t signals, uint32_t parity, float soft_prior);
    /** The PCSS estimate alone (soft_pcss()), before rrc: the soft channel's fill fallback. */
    void record_pcss(VkCommandBuffer cmd, uint32_t parity);
    /** Before rrc, as the soft channel's settings ask (the centre map, lamp_centre, already rendered
     *  this frame), the image rrc's soft channel reads as its fallback, or null for none: with
     *  `soft.residual` (README.md, "The soft residual") the stable PCSS estimate b, which rrc
     *  subtracts from the sample and adds to its output (rrc_channel_desc.residual), else, with a
     *  fill prior, the PCSS estimate.  The channel's samples are the raw soft signal either way. */
    const Image* record_soft_fallback(VkCommandBuffer cmd, uint32_t parity, const ChannelSettings& soft);
    void record_compose(VkCommandBuffer cmd, uint32_t signals, ComposeInput input);

    const Image& age(uint32_t parity) const { return age_[parity]; }
    const Image& soft_shown() const { return shown_; }
    const Image& soft_pcss() const { return pcss_; }
    const Image& colour(ComposeInput input) const { return colour_[input]; }

private:
    Gpu& gpu_;
    uint32_t width_, height_;
    PcfDisplay pcf_display_;
    Image age_[2], shown_, pcss_, colour_[3];
    ComputeKernel age_kernel_, fallback_, compose_;
};

}  // namespace rrc_sample
