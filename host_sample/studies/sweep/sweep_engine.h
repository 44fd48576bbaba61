// The GPU objects of one sweep frame, shared by the sweep (sweep_run.cpp) and
// the rectification study (rectify_study.cpp): rrc-sample's scene, shadow
// maps, G-buffer and signal passes without its Renderer, one command buffer
// submitted and waited for at a time, with timestamps.
#pragma once

#include "fenced_commands.h"
#include "frame_state.h"
#include "gpu.h"
#include "raster.h"
#include "readback.h"
#include "rrc_stage.h"
#include "scene.h"
#include "signals.h"

#include <glm/gtc/packing.hpp>

#include <cstring>
#include <stdexcept>
#include <vector>

namespace rrc_sweep {

using rrc_sample::FrameState;
using rrc_sample::Gpu;
using rrc_sample::Image;
using rrc_sample::kSignalEnv;
using rrc_sample::kSignalPcf;
using rrc_sample::kSignalSoft;
using rrc_sample::Sampling;

constexpr uint32_t kQueries = 512;
// The brute force's and the rrc runs' seeds are 1..S; seeds 0 and 1 of the
// reference streams give env's target and its independent twin.
constexpr uint32_t kFirstSeed = 1;

/** One signal image as floats (R32F: 1 per pixel, RGBA32F: 4). */
inline std::vector<float> floats_of(const rrc_sample::Readback& r, int slot) {
    std::vector<float> v(r.bytes(slot) / sizeof(float));
    std::memcpy(v.data(), r.data(slot), r.bytes(slot));
    return v;
}

inline const Image& signal_image(const rrc_sample::SignalImages& images, uint32_t signal) {
    return signal == kSignalPcf ? images.pcf : signal == kSignalEnv ? images.env : images.soft;
}
inline int stride_of(uint32_t signal) { return signal == kSignalEnv ? 4 : 1; }

/** The GPU objects of the sample's frame, without rrc-sample's Renderer: the sweep records its own frames. */
struct Engine {
    Engine(Gpu& g, const rrc_sample::Scene& s, const rrc_sample::RenderSettings& rs)
        : gpu(g),
          scene(s),
          settings(rs),
          gpu_scene(g, s),
          maps(rrc_sample::create_shadow_maps(g, rs)),
          shadows(g, gpu_scene),
          gbuffer(g, gpu_scene, rs.width, rs.height),
          signals(g, gpu_scene, gbuffer.images(), maps, rs.width, rs.height),
          commands(g),
          queries(g, kQueries) {
        // The sweep's results are GPU times: without timestamps it has nothing to measure.
        if (!queries.enabled()) throw std::runtime_error("rrc-sweep: the device's queue has no timestamps");
    }
    ~Engine() {
        vkDeviceWaitIdle(gpu.device);
        rrc_sample::destroy_shadow_maps(gpu, maps);
    }

    /** Sets frame `index`'s uniforms (the GPU is idle) and returns its state. */
    FrameState begin_frame(int index, int taps, uint32_t seed) {
        rrc_sample::RenderSettings rs = settings;
        rs.taps = taps;
        rs.seed = seed;
        FrameState state = rrc_sample::make_frame_state(scene, rs, index);
        gpu_scene.update(state);
        return state;
    }

    /** Frame `index`'s scene (its light, its moving object's place) seen from frame `camera_frame`'s camera:
     *  a view-independent signal's value at the surface points frame `camera_frame` shows, as it was in
     *  frame `index` (bias_regions.h, PreviousTarget).  Sets the uniforms and returns the state. */
    FrameState begin_frame_seen_from(int index, int camera_frame) {
        FrameState state = rrc_sample::make_frame_state(scene, settings, index);
        const FrameState eye = rrc_sample::make_frame_state(scene, settings, camera_frame);
        state.uniforms.view_proj = eye.uniforms.view_proj;
        state.uniforms.prev_view_proj = eye.uniforms.prev_view_proj;
        state.uniforms.inv_view_proj = eye.uniforms.inv_view_proj;
        state.uniforms.camera_pos = glm::vec4(glm::vec3(eye.uniforms.camera_pos), state.uniforms.camera_pos.w);
        state.view_proj = eye.view_proj;
        state.prev_view_proj = eye.prev_view_proj;
        state.eye = eye.eye, state.prev_eye = eye.prev_eye;
        gpu_scene.update(state);
        return state;
    }

    /** Records with `body` (after the previous frame's work and the query reset), submits, waits;
     *  returns the `stamps` timestamps in milliseconds. */
    template <typename Body>
    std::vector<double> submit(uint32_t stamps, Body&& body) {
        if (stamps > kQueries) throw std::runtime_error("rrc-sweep: more timestamps in a frame than the query pool holds");
        const VkCommandBuffer cmd = commands.begin();
        queries.reset(cmd, 0, kQueries);
        rrc_host::full_barrier(cmd);
        uint32_t next = 0;
        // A full barrier before each timestamp: lavapipe may write a BOTTOM_OF_PIPE timestamp before a
        // dispatch recorded ahead of it has finished (a lone dispatch then timed at 0.07 ms instead of
        // milliseconds); after the barrier each interval holds exactly the work recorded in it.
        auto stamp = [&] {
            rrc_host::full_barrier(cmd);
            queries.write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, next++);
        };
        body(cmd, stamp);
        last_wall_ms = commands.submit_and_wait();
        if (next != stamps) throw std::runtime_error("rrc-sweep: a frame wrote another number of timestamps than it declared");
        std::vector<double> ms;
        if (stamps == 0) return ms;
        const std::vector<uint64_t> ts = queries.ticks(0, stamps);
        const double period = gpu.properties.limits.timestampPeriod * 1e-6;
        for (uint32_t i = 0; i < stamps; ++i) ms.push_back((double)ts[i] * period);
        return ms;
    }

    /** rrc's settings over this engine's frames, one channel per bit of `signals`, the channels' presets as they are (without
     *  their residuals). */
    rrc_sample::RrcSettings rrc_settings(uint32_t signals) const {
        rrc_sample::RrcSettings s;
        s.width = settings.width;
        s.height = settings.height;
        s.signals = signals;
        s.near_plane = scene.near_plane;
        s.far_plane = scene.far_plane;
        s.ages = false;  // no row reads them: rrc's time is the channel's without the optional age output
        // No base here (rrc-sample's soft preset takes the stable PCSS estimate as its residual's
        // base, pcf's its bilinear compares, env's its filtered reflections): the preset rows set
        // their own channel, which turns them back on.
        s.channels.pcf.residual = 0;
        s.channels.env.residual = 0;
        s.channels.soft.residual = 0;
        s.channels.soft.fill_prior = 0.0f;  // nor the PCSS estimate as the fill's prior
        return s;
    }
    /** The same for one signal, its channel set to `channel` (a configuration the sweep or the study tries). */
    rrc_sample::RrcSettings rrc_settings(uint32_t signal, const rrc_sample::ChannelSettings& channel) const {
        rrc_sample::RrcSettings s = rrc_settings(signal);
        if (signal == kSignalPcf) s.channels.pcf = channel;
        if (signal == kSignalEnv) s.channels.env = channel;
        if (signal == kSignalSoft) s.channels.soft = channel;
        return s;
    }

    /** The frame's geometry: the sun's map (pcf's) and the G-buffer. */
    void record_geometry(VkCommandBuffer c, const FrameState& state, uint32_t sigs) {
        if (sigs & kSignalPcf) shadows.record(c, maps.sun, state.uniforms.sun_vp);
        gbuffer.record(c);
    }

    Gpu& gpu;
    const rrc_sample::Scene& scene;
    rrc_sample::RenderSettings settings;
    rrc_sample::GpuScene gpu_scene;
    rrc_sample::ShadowMaps maps;
    rrc_sample::ShadowPass shadows;
    rrc_sample::GBufferPass gbuffer;
    rrc_sample::SignalPasses signals;
    rrc_host::FencedCommands commands;
    rrc_host::TimestampQueries queries;  // kQueries
    double last_wall_ms = 0.0;           // the last submission, vkQueueSubmit to its fence
};

/** The targets of one frame and its materials (the sweep's make_targets and the rectification study):
 *  `samples` per pixel; with env, its second, independent estimate (the random stream of seed 1). */
struct FrameTarget {
    std::vector<uint8_t> material;
    std::vector<float> depth;      // reversed-z depth of the G-buffer's surface point (0: background; bias_regions.h)
    std::vector<float> position;   // 4 a pixel: the G-buffer's world position (w: object + 1, 0 background)
    glm::dmat4 view_proj{1.0};     // the camera's, of the frame's state
    std::vector<float> pcf, env, env_twin, soft;
    const std::vector<float>& of(uint32_t signal) const { return signal == kSignalPcf ? pcf : signal == kSignalEnv ? env : soft; }
};

/** camera_frame >= 0: frame f's scene seen from that frame's camera (Engine::begin_frame_seen_from). */
inline FrameTarget frame_target(Engine& e, int f, uint32_t sigs, uint32_t samples, int camera_frame = -1, bool env_twin = true) {
    rrc_sample::Readback rb(e.gpu);
    const rrc_sample::SignalImages& ref = e.signals.reference();
    const int s_pcf = rb.add(ref.pcf), s_env = rb.add(ref.env), s_soft = rb.add(ref.soft);
    const int s_normal = rb.add(e.gbuffer.images().normal, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const int s_position = rb.add(e.gbuffer.images().position, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    rb.allocate();
    FrameTarget ft;
    const FrameState state = camera_frame >= 0 ? e.begin_frame_seen_from(f, camera_frame) : e.begin_frame(f, 1, 0);
    ft.view_proj = state.view_proj;
    for (uint32_t twin = 0; twin < ((sigs & kSignalEnv) && env_twin ? 2u : 1u); ++twin) {
        e.submit(0, [&](VkCommandBuffer c, auto&&) {
            e.record_geometry(c, state, sigs);
            // twin 1: env's second, independent estimate (the random stream of seed 1).
            e.signals.record_reference(c, twin ? kSignalEnv : sigs, samples, e.scene, e.shadows, twin);
            rb.record(c, twin ? std::vector<int>{s_env} : std::vector<int>{s_pcf, s_env, s_soft, s_normal, s_position});
        });
        if (twin) {
            ft.env_twin = floats_of(rb, s_env);
            continue;
        }
        ft.pcf = floats_of(rb, s_pcf);
        ft.env = floats_of(rb, s_env);
        ft.soft = floats_of(rb, s_soft);
        std::vector<uint16_t> nm(rb.bytes(s_normal) / 2);
        std::memcpy(nm.data(), rb.data(s_normal), rb.bytes(s_normal));
        ft.material.resize(nm.size() / 4);
        for (size_t i = 0; i < ft.material.size(); ++i) ft.material[i] = (uint8_t)(glm::unpackHalf1x16(nm[i * 4 + 3]) + 0.5f);
        // The depth the G-buffer's depth test kept, from its world position (w: object + 1, 0 background).
        ft.position = floats_of(rb, s_position);
        const std::vector<float>& pos = ft.position;
        ft.depth.assign(ft.material.size(), 0.0f);
        for (size_t i = 0; i < ft.depth.size(); ++i) {
            if (!(pos[i * 4 + 3] > 0.0f)) continue;
            const glm::dvec4 c = state.view_proj * glm::dvec4(pos[i * 4], pos[i * 4 + 1], pos[i * 4 + 2], 1.0);
            ft.depth[i] = (float)(c.z / c.w);
        }
    }
    return ft;
}

}  // namespace rrc_sweep
