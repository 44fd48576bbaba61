#include "post.h"

#include "rrc_sample_age_comp.h"
#include "rrc_sample_compose_comp.h"
#include "rrc_sample_soft_fallback_comp.h"

#include <algorithm>

namespace rrc_sample {
namespace {

const VkDescriptorType UBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, TEX = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                       IMG = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
const VkImageLayout RO = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, GEN = VK_IMAGE_LAYOUT_GENERAL;

struct FallbackPush {  // soft_fallback.comp
    float prior;
    uint32_t mode;  // 0 PCSS and the shown blend, 1 PCSS only
};
struct ComposePush {  // compose.comp
    uint32_t signals, pcf_remap;
    float e0, e1, x;
};

}  // namespace

float PcfDisplay::apply(float v) const {
    if (smoothstep) {  // GLSL's smoothstep
        const float t = std::min(std::max((v - e0) / (e1 - e0), 0.0f), 1.0f);
        v = t * t * (3.0f - 2.0f * t);
    }
    if (threshold >= 0.0f) v = v >= threshold ? 1.0f : 0.0f;
    return v;
}

PostPasses::PostPasses(Gpu& gpu, const GpuScene& scene, const GBuffer& g, const ShadowMaps& maps, const Image& mask,
                       const Image& soft_age, const SignalImages& acc, const SignalImages& raw, const SignalImages& ref, uint32_t w, uint32_t h, bool soft_fill,
                       const PcfDisplay& pcf_display)
    : gpu_(gpu), width_(w), height_(h), pcf_display_(pcf_display) {
    const VkImageUsageFlags use = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    age_[0] = gpu.create_image(VK_FORMAT_R16_UINT, w, h, use, "age 0");
    age_[1] = gpu.create_image(VK_FORMAT_R16_UINT, w, h, use, "age 1");
    shown_ = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use, "soft shown");
    // Sampled too: with --soft-fill rrc reads it as the soft channel's fallback.
    pcss_ = gpu.create_image(VK_FORMAT_R32_SFLOAT, w, h, use | VK_IMAGE_USAGE_SAMPLED_BIT, "soft pcss");
    const char* names[3] = {"frame accumulated", "frame raw", "frame reference"};
    for (int i = 0; i < 3; ++i) colour_[i] = gpu.create_image(VK_FORMAT_R8G8B8A8_UNORM, w, h, use, names[i]);
    gpu.init_storage_images({&age_[0], &age_[1], &shown_, &pcss_, &colour_[0], &colour_[1], &colour_[2]});

    age_kernel_ = ComputeKernel(gpu, "age", rrc_sample_age_comp, sizeof rrc_sample_age_comp, {UBO, TEX, IMG, IMG, IMG}, 4, 2);
    fallback_ = ComputeKernel(gpu, "soft_fallback", rrc_sample_soft_fallback_comp, sizeof rrc_sample_soft_fallback_comp,
                              {UBO, TEX, TEX, TEX, IMG, IMG, IMG, IMG, IMG}, sizeof(FallbackPush), 2);
    for (uint32_t p = 0; p < 2; ++p) {
        age_kernel_.bind_buffer(p, 0, scene.uniforms());
        age_kernel_.bind_image(p, 1, g.prev_clip.view, RO);
        age_kernel_.bind_image(p, 2, mask.view, GEN);
        age_kernel_.bind_image(p, 3, age_[1 - p].view, GEN);
        age_kernel_.bind_image(p, 4, age_[p].view, GEN);
        fallback_.bind_buffer(p, 0, scene.uniforms());
        fallback_.bind_image(p, 1, g.position.view, RO);
        fallback_.bind_image(p, 2, g.normal.view, RO);
        fallback_.bind_image(p, 3, maps.lamp_centre.view, RO);
        fallback_.bind_image(p, 4, acc.soft.view, GEN);
        fallback_.bind_image(p, 5, mask.view, GEN);
        fallback_.bind_image(p, 6, soft_age.view, GEN);  // rrc's: the samples the history holds
        fallback_.bind_image(p, 7, shown_.view, GEN);
        fallback_.bind_image(p, 8, pcss_.view, GEN);
    }
    compose_ = ComputeKernel(gpu, "compose", rrc_sample_compose_comp, sizeof rrc_sample_compose_comp, {UBO, TEX, TEX, IMG, IMG, IMG, IMG},
                             sizeof(ComposePush), 3);
    for (uint32_t s = 0; s < 3; ++s) {
        const SignalImages& in = s == kComposeAccumulated ? acc : s == kComposeRaw ? raw : ref;
        compose_.bind_buffer(s, 0, scene.uniforms());
        compose_.bind_image(s, 1, g.position.view, RO);
        compose_.bind_image(s, 2, g.normal.view, RO);
        compose_.bind_image(s, 3, in.pcf.view, GEN);
        compose_.bind_image(s, 4, in.env.view, GEN);
        // The displayed soft shadow: the --soft-prior blend, or with rrc's fill its output (the fill's displayed value).
        compose_.bind_image(s, 5, s == kComposeAccumulated && !soft_fill ? shown_.view : in.soft.view, GEN);
        compose_.bind_image(s, 6, colour_[s].view, GEN);
    }
}

PostPasses::~PostPasses() {
    age_kernel_.release();
    fallback_.release();
    compose_.release();
    for (Image* i : {&age_[0], &age_[1], &shown_, &pcss_, &colour_[0], &colour_[1], &colour_[2]}) gpu_.destroy(*i);
}

void PostPasses::record_age_and_fallback(VkCommandBuffer cmd, uint32_t signals, uint32_t parity, float soft_prior) {
    const uint32_t cap = 255;
    age_kernel_.dispatch(cmd, parity, &cap, width_, height_);
    compute_to_compute(cmd);
    if (signals & kSignalSoft) {
        const FallbackPush p{soft_prior, 0};
        fallback_.dispatch(cmd, parity, &p, width_, height_);
        compute_to_compute(cmd);
    }
}

void PostPasses::record_pcss(VkCommandBuffer cmd, uint32_t parity) {
    const FallbackPush p{0.0f, 1};
    fallback_.dispatch(cmd, parity, &p, width_, height_);
    compute_to_compute(cmd);
}

const Image* PostPasses::record_soft_fallback(VkCommandBuffer cmd, uint32_t parity, const ChannelSettings& soft) {
    if (soft.residual) {
        const FallbackPush p{0.0f, 2};  // the stable estimate b: rrc's base
        fallback_.dispatch(cmd, parity, &p, width_, height_);
        compute_to_compute(cmd);
        return &pcss_;
    }
    if (soft.fill_prior <= 0.0f) return nullptr;
    record_pcss(cmd, parity);
    return &pcss_;
}

void PostPasses::record_compose(VkCommandBuffer cmd, uint32_t signals, ComposeInput input) {
    const PcfDisplay& d = pcf_display_;
    ComposePush p{signals, 0, d.e0, d.e1, d.threshold};
    if (input == kComposeAccumulated) p.pcf_remap = (d.smoothstep ? 1u : 0u) | (d.threshold >= 0.0f ? 2u : 0u);
    compose_.dispatch(cmd, input, &p, width_, height_);
}

}  // namespace rrc_sample
