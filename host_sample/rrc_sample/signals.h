// The three per-frame noisy signals (compute passes over the G-buffer and
// the shadow maps), and the same passes with many samples: the brute-force
// reference of checkpoint frames.
#pragma once

#include "frame_state.h"
#include "kernel.h"
#include "raster.h"

namespace rrc_sample {

/** Shadow maps, D32, left in SHADER_READ_ONLY_OPTIMAL by ShadowPass. */
struct ShadowMaps {
    Image sun;          // orthographic, the PCF signal's
    Image lamp_point;   // this frame's random point of the area light (soft signal)
    Image lamp_centre;  // the light's centre (PCSS fallback)
    Image reference;    // one grid point after another (soft reference)
};

/** One image per signal; unused ones stay allocated (tiny) so descriptors are always valid. */
struct SignalImages {
    Image pcf;   // R32F: lit fraction of the sun
    Image env;   // RGBA32F: sphere colour, alpha 1 on sphere pixels
    Image soft;  // R32F: visibility of the area light
};

class SignalPasses {
public:
    SignalPasses(Gpu& gpu, const GpuScene& scene, const GBuffer& g, const ShadowMaps& maps, uint32_t width, uint32_t height);
    ~SignalPasses();
    SignalPasses(const SignalPasses&) = delete;
    SignalPasses& operator=(const SignalPasses&) = delete;

    /** The frame's noisy signals (bits: Signal), one sample set each. */
    void record(VkCommandBuffer cmd, uint32_t signals, const FrameState& state);
    /** The converged reference of the same frame: `samples` per pixel (soft:
     *  shadow maps from the points of an m x m grid on the light, m*m = samples
     *  rounded to a square). */
    void record_reference(VkCommandBuffer cmd, uint32_t signals, uint32_t samples, const Scene& scene, ShadowPass& shadows);
    /** Brute force at 4x the per-frame budget, for the paper's comparison
     *  ("4 taps cached ~ 16 taps"): 4k PCF taps, 4k env samples, soft shadows
     *  from 4 random points of the light (4 shadow maps). */
    void record_brute_force(VkCommandBuffer cmd, uint32_t signals, uint32_t taps, int frame, const Scene& scene, ShadowPass& shadows);

    const SignalImages& raw() const { return raw_; }
    const SignalImages& reference() const { return ref_; }
    const SignalImages& brute_force() const { return brute_; }

private:
    Gpu& gpu_;
    const ShadowMaps& maps_;
    uint32_t width_, height_;
    void record_many(VkCommandBuffer cmd, uint32_t signals, uint32_t set, uint32_t samples, const std::vector<glm::vec3>& light_points,
                     const Scene& scene, ShadowPass& shadows);
    SignalImages raw_, ref_, brute_;
    ComputeKernel pcf_, env_, soft_;
};

}  // namespace rrc_sample
