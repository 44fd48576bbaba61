#include "rrc_stage.h"

#include "rrc_interop.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rrc_sample {
namespace {

void log_to_stderr(void*, rrc_log_level level, const char* message) {
    if (level >= RRC_LOG_WARNING) std::fprintf(stderr, "rrc: %s\n", message);
}

rrc_vulkan_image view_of(const Image& img, VkImageLayout layout) { return rrc_host::vulkan_image(img, layout); }

}  // namespace

std::vector<rrc_channel_desc> channel_descs(uint32_t signals, const ChannelPresets& p) {
    auto make = [](const char* name, uint32_t components, const ChannelSettings& c, rrc_history_precision precision) {
        rrc_channel_desc d = rrc_host::channel(name, components, c.lambda, precision, c.blend, c.filter, c.age_cap, c.confidence);
        d.rectify = c.rectify;
        d.rectify_gamma = c.rectify_gamma;
        d.blur_sigma = c.blur_sigma;
        d.fill_age = c.fill_age;
        d.fill_radius = c.fill_radius;
        d.fill_depth_tolerance = c.fill_depth_tolerance;
        d.fill_prior = c.fill_prior;
        d.antilag = c.antilag;
        d.antilag_gamma = c.antilag ? c.antilag_gamma : 0.0f;
        d.antilag_threshold = c.antilag ? c.antilag_threshold : 0.0f;
        d.blur_bound = c.blur_bound;
        d.view_lobe = c.view_lobe;
        d.residual = c.residual;
        d.gate_kappa = c.gate_kappa;
        return d;
    };
    std::vector<rrc_channel_desc> c;
    // Amortized PCF and env-mapped bump mapping: fp16 history (rrc keeps fp32 above RRC_FP16_MAX_LAMBDA).
    if (signals & kSignalPcf) c.push_back(make("pcf", 1, p.pcf, RRC_HISTORY_FP16));
    if (signals & kSignalEnv) c.push_back(make("env", 4, p.env, RRC_HISTORY_FP16));
    // Soft shadow: fp32 history: a mean of binary samples over 64 frames would drift by fp16 rounding (2^-11 a step).
    if (signals & kSignalSoft) c.push_back(make("soft", 1, p.soft, RRC_HISTORY_FP32));
    return c;
}

RrcStage::RrcStage(Gpu& gpu, const RrcSettings& s) : gpu_(gpu), settings_(s) {
    channels_ = channel_descs(s.signals, s.channels);
    const VkImageUsageFlags use = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    out_.pcf = gpu.create_image(VK_FORMAT_R32_SFLOAT, s.width, s.height, use, "pcf accumulated");
    out_.env = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, s.width, s.height, use, "env accumulated");
    out_.soft = gpu.create_image(VK_FORMAT_R32_SFLOAT, s.width, s.height, use, "soft accumulated");
    mask_ = gpu.create_image(VK_FORMAT_R8_UINT, s.width, s.height, use, "rrc mask");
    const char* age_names[3] = {"pcf age", "env age", "soft age"};
    for (int k = 0; k < 3; ++k) ages_[k] = gpu.create_image(VK_FORMAT_R16_UINT, s.width, s.height, use, age_names[k]);
    gpu.init_storage_images({&out_.pcf, &out_.env, &out_.soft, &mask_, &ages_[0], &ages_[1], &ages_[2]});

    rrc_context_desc d = rrc_host::context_desc(s.width, s.height, channels_);
    d.depth_mode = RRC_DEPTH_MODE_REVERSED;  // the G-buffer's D32 reversed-z attachment
    d.depth_format = RRC_DEPTH_FORMAT_FLOAT32;
    d.near_plane = s.near_plane;  // used by plain MOTION to linearise depth
    d.far_plane = s.far_plane;
    d.epsilon_scale = s.epsilon_scale;
    d.depth_test = (rrc_depth_test)s.depth_test;
    d.reprojection = s.reprojection;
    d.use_object_id = s.use_object_id ? 1u : 0u;
    d.log = log_to_stderr;

    // One frame in flight: the sample waits for each frame (it reads every frame back).
    const rrc_vulkan_device_desc dd = rrc_host::vulkan_device_desc(gpu, 1);
    if (rrc_vulkan_context_create(&d, &dd, &ctx_) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_vulkan_context_create: ") + rrc_last_error());
}

RrcStage::~RrcStage() {
    rrc_context_destroy(ctx_);  // the device is idle (the renderer waited)
    for (Image* i : {&out_.pcf, &out_.env, &out_.soft, &mask_, &ages_[0], &ages_[1], &ages_[2]}) gpu_.destroy(*i);
}

uint64_t RrcStage::memory_bytes() const {
    uint64_t bytes = 0;
    rrc_get_memory_usage(ctx_, &bytes);
    return bytes;
}

void RrcStage::record(VkCommandBuffer cmd, const GBuffer& g, const SignalImages& samples, const FrameState& state, uint64_t frame_index,
                      bool reset, const Image* pcf_confidence, const Image* soft_fallback, const Image* env_base,
                      const Image* pcf_base) {
    const VkImageLayout RO = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, GEN = VK_IMAGE_LAYOUT_GENERAL;
    std::vector<rrc_vulkan_channel_images> ch;
    auto add = [&](const Image& in, const Image& out, const Image& age, const ChannelSettings& cs, const Image* confidence,
                   const Image* fallback) {
        auto c = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
        c.samples = view_of(in, GEN);
        c.output = view_of(out, GEN);
        if (settings_.ages) c.age = view_of(age, GEN);
        if (cs.confidence) {
            if (!confidence) throw std::runtime_error("rrc_stage: a confidence channel needs its confidence image");
            c.confidence = view_of(*confidence, GEN);
        }
        if (cs.fill_prior > 0.0f || cs.residual) {
            if (!fallback) throw std::runtime_error("rrc_stage: a fill with a prior or a residual needs its fallback image");
            c.fallback = view_of(*fallback, GEN);
        }
        ch.push_back(c);
    };
    const ChannelPresets& p = settings_.channels;
    if (settings_.signals & kSignalPcf) add(samples.pcf, out_.pcf, ages_[0], p.pcf, pcf_confidence, pcf_base);
    if (settings_.signals & kSignalEnv) add(samples.env, out_.env, ages_[1], p.env, nullptr, env_base);
    if (settings_.signals & kSignalSoft) add(samples.soft, out_.soft, ages_[2], p.soft, nullptr, soft_fallback);

    auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
    f.command_buffer = cmd;
    f.frame_index = frame_index;
    f.reset = reset ? 1u : 0u;
    f.depth = view_of(g.depth, RO);  // the G-buffer pass leaves it SHADER_READ_ONLY_OPTIMAL
    if (settings_.reprojection == RRC_REPROJECTION_PREV_CLIP) f.reprojection = view_of(g.prev_clip, RO);
    if (settings_.reprojection == RRC_REPROJECTION_MOTION || settings_.reprojection == RRC_REPROJECTION_MOTION_DEPTH)
        f.reprojection = view_of(g.motion, RO);
    if (settings_.use_object_id) f.object_id = view_of(g.object_id, RO);  // left SHADER_READ_ONLY_OPTIMAL, as depth
    f.mask = view_of(mask_, GEN);
    for (int i = 0; i < 16; ++i) {
        f.view_proj[i] = state.view_proj[i / 4][i % 4];  // column-major, as GLM stores it
        f.prev_view_proj[i] = state.prev_view_proj[i / 4][i % 4];
    }
    for (int k = 0; k < 3; ++k) f.camera_position[k] = state.eye[k], f.prev_camera_position[k] = state.prev_eye[k];
    // The environment map's turn adds to the view lobes' view turn (docs/CONVENTIONS.md, "The
    // view-dependent history"); rrc refuses it without a lobe.
    const bool lobe = ((settings_.signals & kSignalPcf) && p.pcf.view_lobe > 0.0f) || ((settings_.signals & kSignalEnv) && p.env.view_lobe > 0.0f) ||
                      ((settings_.signals & kSignalSoft) && p.soft.view_lobe > 0.0f);
    if (lobe && settings_.lighting_turn) f.lighting_turn = state.lighting_turn;
    f.channel_count = (uint32_t)ch.size();
    f.channels = ch.data();
    if (rrc_vulkan_record_frame(ctx_, &f) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_vulkan_record_frame: ") + rrc_context_last_error(ctx_));
}

}  // namespace rrc_sample
