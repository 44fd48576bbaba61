#include "renderer.h"

#include <glm/gtc/packing.hpp>

#include <chrono>
#include <cstring>

namespace rrc_sample {
namespace {

enum Stamp : uint32_t { kStart, kShadows, kGBuffer, kSignals, kRrc, kPost, kReference, kBrute, kStampCount };

template <typename T>
std::vector<T> copy_of(const void* data, size_t bytes) {
    std::vector<T> v(bytes / sizeof(T));
    std::memcpy(v.data(), data, bytes);
    return v;
}

void label(const Gpu& gpu, VkCommandBuffer cmd, const char* name) {
    if (!gpu.debug_utils || !vkCmdInsertDebugUtilsLabelEXT) return;
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    l.pLabelName = name;
    vkCmdInsertDebugUtilsLabelEXT(cmd, &l);
}

}  // namespace

Renderer::Renderer(Gpu& gpu, const Scene& scene, const RendererSettings& s)
    : gpu_(gpu), scene_(scene), s_(s), commands_(gpu), queries_(gpu, kStampCount) {
    const uint32_t w = s.render.width, h = s.render.height;
    gpu_scene_.reset(new GpuScene(gpu, scene));
    maps_ = create_shadow_maps(gpu, s.render);
    shadows_.reset(new ShadowPass(gpu, *gpu_scene_));
    gbuffer_.reset(new GBufferPass(gpu, *gpu_scene_, w, h));
    signals_.reset(new SignalPasses(gpu, *gpu_scene_, gbuffer_->images(), maps_, w, h));
    // In RrcSettings' order: extent, signals, reprojection, epsilon scale, depth test, planes, channels, object ids.
    const RrcSettings rs{
        w, h, s.signals, s.reprojection, s.epsilon_scale, s.depth_test, scene.near_plane, scene.far_plane, s.channels, s.use_object_id};
    rrc_.reset(new RrcStage(gpu, rs));
    post_.reset(new PostPasses(gpu, *gpu_scene_, gbuffer_->images(), maps_, rrc_->mask(), rrc_->age(kSignalSoft), rrc_->accumulated(), signals_->raw(),
                               signals_->reference(), w, h, s.channels.soft.fill_age > 0, s.pcf_display));

    readback_.reset(new Readback(gpu));
    Readback& r = *readback_;
    slot_.mask = r.add(rrc_->mask());
    for (uint32_t p = 0; p < 2; ++p) slot_.age[p] = r.add(post_->age(p));
    const uint32_t bit[3] = {kSignalPcf, kSignalEnv, kSignalSoft};
    for (int k = 0; k < 3; ++k) slot_.rrc_age[k] = r.add(rrc_->age(bit[k]));
    for (uint32_t c = 0; c < 3; ++c) slot_.colour[c] = r.add(post_->colour((ComposeInput)c));
    const SignalImages* sets[4] = {&signals_->raw(), &rrc_->accumulated(), &signals_->reference(), &signals_->brute_force()};
    int* slots[4] = {slot_.raw, slot_.acc, slot_.ref, slot_.brute};
    for (int k = 0; k < 4; ++k) {
        slots[k][0] = r.add(sets[k]->pcf);
        slots[k][1] = r.add(sets[k]->env);
        slots[k][2] = r.add(sets[k]->soft);
    }
    slot_.shown = r.add(post_->soft_shown());
    slot_.pcss = r.add(post_->soft_pcss());
    const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    slot_.position = r.add(gbuffer_->images().position, ro);
    slot_.normal = r.add(gbuffer_->images().normal, ro);
    slot_.prev_clip = r.add(gbuffer_->images().prev_clip, ro);
    slot_.confidence = r.add(signals_->pcf_confidence());
    slot_.weighted = r.add(signals_->pcf_weighted_target());
    slot_.pcf_base = r.add(signals_->pcf_base());
    slot_.env_base = r.add(signals_->env_base());
    r.allocate();
}

Renderer::~Renderer() {
    vkDeviceWaitIdle(gpu_.device);
    readback_.reset();
    post_.reset();
    rrc_.reset();
    signals_.reset();
    gbuffer_.reset();
    shadows_.reset();
    destroy_shadow_maps(gpu_, maps_);
    gpu_scene_.reset();
}

FrameOutput Renderer::render(int index, bool reset, bool checkpoint) {
    const auto t0 = std::chrono::steady_clock::now();
    const FrameState state = make_frame_state(scene_, s_.render, index);
    gpu_scene_->update(state);  // the previous frame's fence has been waited for
    const uint32_t sig = s_.signals;
    const VkCommandBuffer cmd = commands_.begin();
    auto stamp = [&](Stamp s) {
        queries_.write(cmd, s == kStart ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s);
    };
    queries_.reset(cmd, 0, kStampCount);
    // Everything of the previous frame (readback copies included) before anything of this one.
    rrc_host::full_barrier(cmd);
    stamp(kStart);

    label(gpu_, cmd, "shadow maps");
    if (sig & kSignalPcf) shadows_->record(cmd, maps_.sun, state.uniforms.sun_vp);
    if (sig & kSignalSoft) {
        shadows_->record(cmd, maps_.lamp_point, state.uniforms.lamp_point_vp);
        shadows_->record(cmd, maps_.lamp_centre, state.uniforms.lamp_centre_vp);
    }
    stamp(kShadows);
    label(gpu_, cmd, "g-buffer");
    gbuffer_->record(cmd);
    stamp(kGBuffer);
    label(gpu_, cmd, "signals");
    const bool confidence = s_.channels.pcf.confidence != 0;
    // pcf's residual base (README.md, "The pcf residual") is written by the pcf pass itself,
    // which reads the pixel's G-buffer and light transform once for both.
    const uint32_t pcf_base_taps = (sig & kSignalPcf) ? s_.render.pcf_base : 0u;
    const Sampling sampling{s_.render.seed, s_.render.pcf_pattern, confidence, s_.render.env_base, pcf_base_taps};
    signals_->record(cmd, sig, state, sampling);
    // soft's fallback: the PCSS estimate, or the stable PCSS estimate as the residual's base,
    // which rrc subtracts and adds back (README.md, "The soft residual").
    const Image* soft_fallback = (sig & kSignalSoft) ? post_->record_soft_fallback(cmd, parity_, s_.channels.soft) : nullptr;
    // pcf's residual base, written above, made visible to rrc.
    const Image* pcf_base = (sig & kSignalPcf) ? signals_->record_pcf_base(cmd, pcf_base_taps, true) : nullptr;
    stamp(kSignals);
    const Image* env_base = s_.channels.env.residual ? &signals_->env_base() : nullptr;
    rrc_->record(cmd, gbuffer_->images(), signals_->raw(), state, (uint64_t)index, reset, &signals_->pcf_confidence(), soft_fallback,
                 env_base, pcf_base);
    stamp(kRrc);
    label(gpu_, cmd, "post");
    post_->record_age_and_fallback(cmd, sig, parity_, s_.soft_prior);
    post_->record_compose(cmd, sig, kComposeAccumulated);
    stamp(kPost);
    if (checkpoint) {
        label(gpu_, cmd, "reference");
        signals_->record_reference(cmd, sig, s_.reference_samples, scene_, *shadows_, 0, confidence);
        stamp(kReference);
        // 4x the per-frame budget: 4k pcf taps and env rays, soft from 4 light points (it has one a frame).
        signals_->record_brute_force(cmd, sig & ~kSignalSoft, 4 * (uint32_t)s_.render.taps, index, sampling, scene_, *shadows_);
        signals_->record_brute_force(cmd, sig & kSignalSoft, 4, index, sampling, scene_, *shadows_);
        stamp(kBrute);
        compute_to_compute(cmd);
        post_->record_compose(cmd, sig, kComposeRaw);
        post_->record_compose(cmd, sig, kComposeReference);
    }
    std::vector<int> slots = {slot_.mask, slot_.age[parity_], slot_.colour[0], slot_.shown,
                              slot_.pcss, slot_.position,     slot_.normal,    slot_.prev_clip};
    for (int k = 0; k < 3; ++k) slots.push_back(slot_.raw[k]), slots.push_back(slot_.acc[k]), slots.push_back(slot_.rrc_age[k]);
    if (confidence) slots.push_back(slot_.confidence);
    if (confidence && checkpoint) slots.push_back(slot_.weighted);
    if (s_.render.pcf_base && checkpoint) slots.push_back(slot_.pcf_base);
    if (s_.render.env_base && checkpoint) slots.push_back(slot_.env_base);
    if (checkpoint)
        for (int k = 0; k < 3; ++k) slots.push_back(slot_.ref[k]), slots.push_back(slot_.brute[k]);
    if (checkpoint) slots.push_back(slot_.colour[1]), slots.push_back(slot_.colour[2]);
    readback_->record(cmd, slots);
    commands_.submit_and_wait();
    const auto t1 = std::chrono::steady_clock::now();

    FrameOutput out;
    out.index = index;
    out.checkpoint = checkpoint;
    out.width = (int)s_.render.width, out.height = (int)s_.render.height;
    out.eye = glm::vec3(state.uniforms.camera_pos);
    out.pixel_angle = scene_.camera(state.uniforms.camera_pos.w).fov_y / (float)s_.render.height;
    out.timings.cpu_frame = std::chrono::duration<double, std::milli>(t1 - t0).count();
    if (queries_.enabled()) {
        const std::vector<uint64_t> ts = queries_.ticks(0, checkpoint ? kStampCount : kReference);
        const double ms = gpu_.properties.limits.timestampPeriod * 1e-6;
        auto d = [&](Stamp a, Stamp b) { return (double)(ts[b] - ts[a]) * ms; };
        FrameTimings& t = out.timings;
        t.shadows = d(kStart, kShadows);
        t.gbuffer = d(kShadows, kGBuffer);
        t.signals = d(kGBuffer, kSignals);
        t.rrc = d(kSignals, kRrc);
        t.post = d(kRrc, kPost);
        t.reference = checkpoint ? d(kPost, kReference) : 0.0;
        t.brute_force = checkpoint ? d(kReference, kBrute) : 0.0;
        t.from_timestamps = true;
    }
    read_back(out, parity_);
    parity_ = 1 - parity_;
    return out;
}

void Renderer::read_back(FrameOutput& out, uint32_t parity) const {
    const Readback& r = *readback_;
    out.mask = copy_of<uint8_t>(r.data(slot_.mask), r.bytes(slot_.mask));
    out.age = copy_of<uint16_t>(r.data(slot_.age[parity]), r.bytes(slot_.age[parity]));
    out.colour[0] = copy_of<uint8_t>(r.data(slot_.colour[0]), r.bytes(slot_.colour[0]));
    out.position = copy_of<float>(r.data(slot_.position), r.bytes(slot_.position));
    out.prev_clip = copy_of<float>(r.data(slot_.prev_clip), r.bytes(slot_.prev_clip));
    out.object.resize(out.position.size() / 4);
    for (size_t i = 0; i < out.object.size(); ++i) out.object[i] = (uint16_t)out.position[i * 4 + 3];
    const std::vector<uint16_t> nm = copy_of<uint16_t>(r.data(slot_.normal), r.bytes(slot_.normal));
    out.material.resize(nm.size() / 4);
    out.normal.resize(nm.size() / 4 * 3);
    for (size_t i = 0; i < out.material.size(); ++i) {
        for (int c = 0; c < 3; ++c) out.normal[i * 3 + c] = glm::unpackHalf1x16(nm[i * 4 + c]);
        out.material[i] = (uint8_t)(glm::unpackHalf1x16(nm[i * 4 + 3]) + 0.5f);
    }
    if (out.checkpoint)
        for (int c = 1; c < 3; ++c) out.colour[c] = copy_of<uint8_t>(r.data(slot_.colour[c]), r.bytes(slot_.colour[c]));
    SignalData* sd[3] = {&out.pcf, &out.env, &out.soft};
    const uint32_t bits[3] = {kSignalPcf, kSignalEnv, kSignalSoft};
    for (int k = 0; k < 3; ++k) {
        if (!(s_.signals & bits[k])) continue;
        sd[k]->components = k == 1 ? 4 : 1;
        sd[k]->raw = copy_of<float>(r.data(slot_.raw[k]), r.bytes(slot_.raw[k]));
        sd[k]->accumulated = copy_of<float>(r.data(slot_.acc[k]), r.bytes(slot_.acc[k]));
        sd[k]->age = copy_of<uint16_t>(r.data(slot_.rrc_age[k]), r.bytes(slot_.rrc_age[k]));
        if (out.checkpoint) {
            sd[k]->reference = copy_of<float>(r.data(slot_.ref[k]), r.bytes(slot_.ref[k]));
            sd[k]->brute_force = copy_of<float>(r.data(slot_.brute[k]), r.bytes(slot_.brute[k]));
        }
    }
    if ((s_.signals & kSignalPcf) && s_.channels.pcf.confidence) {
        out.pcf.confidence = copy_of<float>(r.data(slot_.confidence), r.bytes(slot_.confidence));
        if (out.checkpoint) out.pcf.weighted_target = copy_of<float>(r.data(slot_.weighted), r.bytes(slot_.weighted));
    }
    if ((s_.signals & kSignalPcf) && s_.render.pcf_base && out.checkpoint)
        out.pcf.base = copy_of<float>(r.data(slot_.pcf_base), r.bytes(slot_.pcf_base));
    if ((s_.signals & kSignalEnv) && s_.render.env_base && out.checkpoint)
        out.env.base = copy_of<float>(r.data(slot_.env_base), r.bytes(slot_.env_base));
    if ((s_.signals & kSignalPcf) && s_.pcf_display.any()) {
        out.pcf.display.resize(out.pcf.accumulated.size());
        for (size_t i = 0; i < out.pcf.display.size(); ++i) out.pcf.display[i] = s_.pcf_display.apply(out.pcf.accumulated[i]);
    }
    if (s_.signals & kSignalSoft) {
        out.soft.shown = copy_of<float>(r.data(slot_.shown), r.bytes(slot_.shown));
        out.soft.pcss = copy_of<float>(r.data(slot_.pcss), r.bytes(slot_.pcss));
    }
}

}  // namespace rrc_sample
