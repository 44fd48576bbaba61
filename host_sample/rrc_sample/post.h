// After rrc: the host's age map, the soft-shadow fallback (PCSS on misses),
// and the composed frames (accumulated signals; on checkpoints also the raw
// and the reference signals, for side-by-side pictures).
#pragma once

#include "kernel.h"
#include "raster.h"
#include "signals.h"

namespace rrc_sample {

enum ComposeInput : uint32_t { kComposeAccumulated = 0, kComposeRaw = 1, kComposeReference = 2 };

class PostPasses {
public:
    PostPasses(Gpu& gpu, const GpuScene& scene, const GBuffer& g, const ShadowMaps& maps, const Image& mask,
               const SignalImages& accumulated, const SignalImages& raw, const SignalImages& reference, uint32_t width, uint32_t height);
    ~PostPasses();
    PostPasses(const PostPasses&) = delete;
    PostPasses& operator=(const PostPasses&) = delete;

    /** Age (frame parity selects the ping-pong side) and, with soft shadows, the fallback. */
    void record_age_and_fallback(VkCommandBuffer cmd, uint32_t signals, uint32_t parity, float soft_prior);
    void record_compose(VkCommandBuffer cmd, uint32_t signals, ComposeInput input);

    const Image& age(uint32_t parity) const { return age_[parity]; }
    const Image& soft_shown() const { return shown_; }
    const Image& soft_pcss() const { return pcss_; }
    const Image& colour(ComposeInput input) const { return colour_[input]; }

private:
    Gpu& gpu_;
    uint32_t width_, height_;
    Image age_[2], shown_, pcss_, colour_[3];
    ComputeKernel age_kernel_, fallback_, compose_;
};

}  // namespace rrc_sample
