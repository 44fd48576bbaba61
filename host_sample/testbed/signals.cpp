#include "signals.h"

#include "rrc_sample_signal_env_comp.h"
#include "rrc_sample_signal_pcf_comp.h"
#include "rrc_sample_signal_soft_comp.h"
#include "shaders/signal_modes.h"

#include <algorithm>
#include <cmath>

namespace rrc_sample {
namespace {

const VkDescriptorType UBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, TEX = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                       IMG = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
const VkImageLayout RO = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, GEN = VK_IMAGE_LAYOUT_GENERAL;

struct SamplesPush {  // signal_pcf.comp and signal_env.comp (the first six)
    uint32_t samples, reference, seed, pattern, confidence, env_base, pcf_base;
};
constexpr uint32_t kPcfBasePass = SAMPLE_PCF_BASE_PASS;  // signal_pcf.comp's `reference` value of the base pass

struct SoftPush {
    glm::mat4 light_vp;
    uint32_t pass, count;
};

}  // namespace

ShadowMaps create_shadow_maps(Gpu& gpu, const RenderSettings& s) {
    ShadowMaps maps;
    const VkImageUsageFlags map_use = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    maps.sun = gpu.create_image(VK_FORMAT_D32_SFLOAT, s.sun_map, s.sun_map, map_use, "sun shadow map");
    maps.lamp_point = gpu.create_image(VK_FORMAT_D32_SFLOAT, s.lamp_map, s.lamp_map, map_use, "lamp point map");
    maps.lamp_centre = gpu.create_image(VK_FORMAT_D32_SFLOAT, s.lamp_map, s.lamp_map, map_use, "lamp centre map");
    maps.reference = gpu.create_image(VK_FORMAT_D32_SFLOAT, s.lamp_map, s.lamp_map, map_use, "reference lamp map");
    gpu.immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> bs;
        for (Image* m : {&maps.sun, &maps.lamp_point, &maps.lamp_centre, &maps.reference})
            bs.push_back(rrc_host::layout_change(*m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0,
                                                 VK_ACCESS_SHADER_READ_BIT));
        rrc_host::image_barriers(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, bs);
    });
    return maps;
}

void destroy_shadow_maps(Gpu& gpu, ShadowMaps& maps) {
    for (Image* m : {&maps.sun, &maps.lamp_point, &maps.lamp_centre, &maps.reference}) gpu.destroy(*m);
}

SignalPasses::SignalPasses(Gpu& gpu, const GpuScene& scene, const GBuffer& g, const ShadowMaps& maps, uint32_t w, uint32_t h)
    : gpu_(gpu), maps_(maps), width_(w), height_(h) {
    // Sampled by rrc, written here, read back by the host.
    const VkImageUsageFlags use =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    raw_.pcf = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "pcf signal");
    raw_.env = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, use, "env signal");
    raw_.soft = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "soft signal");
    env_base_ = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, use, "env base");
    pcf_base_ = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "pcf base");
    ref_.pcf = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "pcf reference");
    ref_.env = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, use, "env reference");
    ref_.soft = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "soft reference");
    brute_.pcf = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "pcf brute force");
    brute_.env = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, use, "env brute force");
    brute_.soft = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "soft brute force");
    const char* conf_names[3] = {"pcf confidence", "pcf weighted target", "pcf brute-force confidence"};
    for (int s = 0; s < 3; ++s) conf_[s] = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, conf_names[s]);
    gpu.init_storage_images({&raw_.pcf, &raw_.env, &raw_.soft, &env_base_, &pcf_base_, &ref_.pcf, &ref_.env, &ref_.soft, &brute_.pcf, &brute_.env, &brute_.soft,
                             &conf_[0], &conf_[1], &conf_[2]});

    pcf_ = ComputeKernel(gpu, "signal_pcf", rrc_sample_signal_pcf_comp, sizeof rrc_sample_signal_pcf_comp, {UBO, TEX, TEX, TEX, IMG, IMG, IMG},
                         sizeof(SamplesPush), 3);
    env_ = ComputeKernel(gpu, "signal_env", rrc_sample_signal_env_comp, sizeof rrc_sample_signal_env_comp, {UBO, TEX, IMG, IMG},
                         sizeof(SamplesPush), 3);
    soft_ = ComputeKernel(gpu, "signal_soft", rrc_sample_signal_soft_comp, sizeof rrc_sample_signal_soft_comp, {UBO, TEX, TEX, TEX, IMG},
                          sizeof(SoftPush), 3);
    for (uint32_t s = 0; s < 3; ++s) {  // sets: 0 per-frame signal, 1 reference, 2 brute force
        const SignalImages& out = s == 0 ? raw_ : s == 1 ? ref_ : brute_;
        pcf_.bind_buffer(s, 0, scene.uniforms());
        pcf_.bind_image(s, 1, g.position.view, RO);
        pcf_.bind_image(s, 2, g.normal.view, RO);
        pcf_.bind_image(s, 3, maps.sun.view, RO);
        pcf_.bind_image(s, 4, out.pcf.view, GEN);
        pcf_.bind_image(s, 5, conf_[s].view, GEN);
        pcf_.bind_image(s, 6, pcf_base_.view, GEN);  // written by record_pcf_base (set 0) only
        env_.bind_buffer(s, 0, scene.uniforms());
        env_.bind_image(s, 1, g.normal.view, RO);
        env_.bind_image(s, 2, out.env.view, GEN);
        env_.bind_image(s, 3, env_base_.view, GEN);  // written by set 0 only
        soft_.bind_buffer(s, 0, scene.uniforms());
        soft_.bind_image(s, 1, g.position.view, RO);
        soft_.bind_image(s, 2, g.normal.view, RO);
        soft_.bind_image(s, 3, s ? maps.reference.view : maps.lamp_point.view, RO);
        soft_.bind_image(s, 4, out.soft.view, GEN);
    }
}

SignalPasses::~SignalPasses() {
    pcf_.release();
    env_.release();
    soft_.release();
    for (Image* i : {&raw_.pcf, &raw_.env, &raw_.soft, &env_base_, &pcf_base_, &ref_.pcf, &ref_.env, &ref_.soft, &brute_.pcf, &brute_.env, &brute_.soft, &conf_[0],
                     &conf_[1], &conf_[2]})
        gpu_.destroy(*i);
}

void SignalPasses::record(VkCommandBuffer cmd, uint32_t signals, const FrameState& state, const Sampling& sampling) {
    const SamplesPush one{0, 0, sampling.seed, sampling.pcf_pattern, sampling.pcf_confidence ? 1u : 0u, sampling.env_base, sampling.pcf_base};
    if (signals & kSignalPcf) pcf_.dispatch(cmd, 0, &one, width_, height_);
    if (signals & kSignalEnv) env_.dispatch(cmd, 0, &one, width_, height_);
    if (signals & kSignalSoft) {
        const SoftPush p{state.uniforms.lamp_point_vp, 0, 0};
        soft_.dispatch(cmd, 0, &p, width_, height_);
    }
}

const Image* SignalPasses::record_pcf_base(VkCommandBuffer cmd, uint32_t taps, bool written) {
    if (taps == 0) return nullptr;
    const SamplesPush base{taps, kPcfBasePass, 0, 0, 0, 0, 0};  // deterministic: no seed, no pattern
    if (!written) pcf_.dispatch(cmd, 0, &base, width_, height_);
    compute_to_compute(cmd);
    return &pcf_base_;
}

void SignalPasses::record(VkCommandBuffer cmd, uint32_t signals, const FrameState& state, const Sampling& sampling,
                          const std::vector<glm::vec3>& soft_points, const Scene& scene, ShadowPass& shadows) {
    record(cmd, signals & ~kSignalSoft, state, sampling);
    if (signals & kSignalSoft) record_many(cmd, kSignalSoft, 0, 0, sampling, soft_points, scene, shadows);
}

void SignalPasses::record_many(VkCommandBuffer cmd, uint32_t signals, uint32_t set, uint32_t samples, const Sampling& sampling,
                               const std::vector<glm::vec3>& light_points, const Scene& scene, ShadowPass& shadows) {
    // The set (1 reference, 2 brute force) picks the stream.  Brute force stays the plain mean; the
    // reference writes the confidence-weighted target beside the exact one when asked.
    const SamplesPush many{samples, set, sampling.seed, sampling.pcf_pattern, set == 1 && sampling.pcf_confidence ? 1u : 0u, 0, 0};
    if (signals & kSignalPcf) pcf_.dispatch(cmd, set, &many, width_, height_);
    if (signals & kSignalEnv) env_.dispatch(cmd, set, &many, width_, height_);
    if (signals & kSignalSoft) {
        // One shadow map per light point, each pixel's test added in (the sum is read-modify-write).
        // Set 0 (the per-frame signal) samples the frame's point map, the others the reference map.
        const Image& map = set == 0 ? maps_.lamp_point : maps_.reference;
        const uint32_t count = (uint32_t)light_points.size();
        for (uint32_t j = 0; j < count; ++j) {
            const glm::mat4 vp = lamp_view_proj(scene.lamp, light_points[j]);
            shadows.record(cmd, map, vp);
            const SoftPush p{vp, j, count};
            soft_.dispatch(cmd, set, &p, width_, height_);
            compute_to_compute(cmd);
        }
    }
}

void SignalPasses::record_reference(VkCommandBuffer cmd, uint32_t signals, uint32_t samples, const Scene& scene, ShadowPass& shadows,
                                    uint32_t seed, bool pcf_confidence) {
    const uint32_t m = std::max(1u, (uint32_t)std::lround(std::sqrt((double)samples)));
    std::vector<glm::vec3> points;
    for (uint32_t j = 0; j < m * m; ++j) points.push_back(lamp_grid_point(scene.lamp, (int)j, (int)(m * m)));
    record_many(cmd, signals, 1, samples, Sampling{seed, 0, pcf_confidence}, points, scene, shadows);
}

void SignalPasses::record_brute_force(VkCommandBuffer cmd, uint32_t signals, uint32_t taps, int frame, const Sampling& sampling,
                                      const Scene& scene, ShadowPass& shadows) {
    // Points of the light sequence no per-frame signal uses (offset 1000003), shifted by the seed.
    std::vector<glm::vec3> points;
    for (uint32_t j = 0; j < taps; ++j)
        points.push_back(lamp_sequence_point(scene.lamp, 1000003 + (int)taps * frame + (int)j, sampling.seed));
    record_many(cmd, signals, 2, taps, sampling, points, scene, shadows);
}

}  // namespace rrc_sample
