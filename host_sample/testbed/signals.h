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

/** The four maps, D32 at the settings' sizes, each already in SHADER_READ_ONLY_OPTIMAL
 *  (every map is sampled by some descriptor set, even if its pass never runs). */
ShadowMaps create_shadow_maps(Gpu& gpu, const RenderSettings& settings);
void destroy_shadow_maps(Gpu& gpu, ShadowMaps& maps);

/** One image per signal; unused ones stay allocated (tiny) so descriptors are always valid. */
struct SignalImages {
    Image pcf;   // R32F: lit fraction of the sun
    Image env;   // RGBA32F: sphere colour, alpha 1 on sphere pixels
    Image soft;  // R32F: visibility of the area light
};

/** The estimators' randomness: the ensemble member and the PCF pattern (RenderSettings). */
struct Sampling {
    uint32_t seed = 0;
    uint32_t pcf_pattern = 0;     // 0 uniform disk, 1 the paper's rotated Poisson disk
    bool pcf_confidence = false;  // confidence-weighted taps, w written to confidence() (signal_pcf.comp)
    uint32_t env_base = 0;        // the per-frame env pass also writes env_base(): 1 centre sample, 2 unbumped (signal_env.comp)
    uint32_t pcf_base = 0;        // the per-frame pcf pass also writes pcf_base(): that many bilinear compares (record_pcf_base)
};

class SignalPasses {
public:
    SignalPasses(Gpu& gpu, const GpuScene& scene, const GBuffer& g, const ShadowMaps& maps, uint32_t width, uint32_t height);
    ~SignalPasses();
    SignalPasses(const SignalPasses&) = delete;
    SignalPasses& operator=(const SignalPasses&) = delete;

    /** The frame's noisy signals (bits: Signal): pcf and env with the frame's k
     *  (state.uniforms.frame.y) taps, soft from the frame's light point whose map
     *  the shadow pass rendered (lamp_point). */
    void record(VkCommandBuffer cmd, uint32_t signals, const FrameState& state, const Sampling& sampling);
    /** The same with soft from several light points (one shadow map each, rendered here). */
    void record(VkCommandBuffer cmd, uint32_t signals, const FrameState& state, const Sampling& sampling,
                const std::vector<glm::vec3>& soft_points, const Scene& scene, ShadowPass& shadows);
    /** The target of the same frame, one per signal and independent of k, the
     *  pattern and the seed: pcf the exact disk mean (no samples); env `samples`
     *  sub-pixel rays (random stream of `seed`: two seeds give two independent
     *  estimates, whose difference measures the reference's own noise); soft the
     *  shadow maps from the points of an m x m grid on the light, m*m = samples
     *  rounded to a square. */
    void record_reference(VkCommandBuffer cmd, uint32_t signals, uint32_t samples, const Scene& scene, ShadowPass& shadows,
                          uint32_t seed = 0, bool pcf_confidence = false);
    /** Brute force, the per-frame estimator with `taps` samples: pcf and env
     *  taps, soft from `taps` points of the light sequence (one map each). */
    void record_brute_force(VkCommandBuffer cmd, uint32_t signals, uint32_t taps, int frame, const Sampling& sampling, const Scene& scene,
                            ShadowPass& shadows);

    /** The pcf residual's base (README.md, "The pcf residual"): the mean of `taps` bilinear shadow
     *  compares at fixed points of the frame's PCF disk (signal_pcf.comp), deterministic; written to
     *  pcf_base() and made visible to later compute passes, which the result points to (nullptr,
     *  nothing recorded, when taps is 0).  `written`: the per-frame pass wrote it already
     *  (Sampling::pcf_base, the same taps), so only the barrier is recorded. */
    const Image* record_pcf_base(VkCommandBuffer cmd, uint32_t taps, bool written = false);

    const SignalImages& raw() const { return raw_; }
    const SignalImages& reference() const { return ref_; }
    const SignalImages& brute_force() const { return brute_; }
    /** R32F, written by every pcf pass: the per-frame signal's confidence w (1 without
     *  Sampling::pcf_confidence, and on the background); rrc's pcf confidence image. */
    const Image& pcf_confidence() const { return conf_[0]; }
    /** The env residual's base (Sampling::env_base; README.md, "The env residual"). */
    const Image& env_base() const { return env_base_; }
    /** The pcf residual's base (record_pcf_base). */
    const Image& pcf_base() const { return pcf_base_; }
    /** R32F, checkpoints with confidence: the confidence-weighted disk mean, what the pcf
     *  channel converges to with confidence (signal_pcf.comp); 1 without. */
    const Image& pcf_weighted_target() const { return conf_[1]; }

private:
    Gpu& gpu_;
    const ShadowMaps& maps_;
    uint32_t width_, height_;
    void record_many(VkCommandBuffer cmd, uint32_t signals, uint32_t set, uint32_t samples, const Sampling& sampling,
                     const std::vector<glm::vec3>& light_points, const Scene& scene, ShadowPass& shadows);
    SignalImages raw_, ref_, brute_;
    Image env_base_, pcf_base_;
    Image conf_[3];  // per set: confidence, weighted target, brute force's (unused)
    ComputeKernel pcf_, env_, soft_;
};

}  // namespace rrc_sample
