// One frame of the small engine: shadow maps, G-buffer, the noisy signals,
// rrc, the host's post passes, on checkpoints the brute-force reference,
// then the readback -- all in one command buffer, timed with GPU timestamps.
#pragma once

#include "fenced_commands.h"
#include "frame_state.h"
#include "gpu.h"
#include "post.h"
#include "raster.h"
#include "readback.h"
#include "rrc_stage.h"
#include "scene.h"
#include "signals.h"

#include <array>
#include <memory>
#include <vector>

namespace rrc_sample {

struct RendererSettings {
    RenderSettings render;
    uint32_t signals = 0;
    uint32_t reprojection = 0;
    float epsilon_scale = 0.0f;
    uint32_t depth_test = 0;  // RRC_DEPTH_TEST_*
    float soft_prior = 4.0f;
    ChannelPresets channels;    // soft.fill_age: rrc's fill (the display shows rrc's soft output); pcf.confidence: w per pixel
    PcfDisplay pcf_display;     // display-only remaps of the accumulated PCF
    bool use_object_id = true;  // rrc_context_desc.use_object_id
    uint32_t reference_samples = 256;
};

/** Milliseconds of GPU time per stage (timestamps; CPU wall clock where the queue has none). */
struct FrameTimings {
    double shadows = 0, gbuffer = 0, signals = 0, rrc = 0, post = 0, reference = 0;
    double brute_force = 0;  // checkpoints: the signals at 4x the samples (the paper's equal-quality comparison)
    double render() const { return shadows + gbuffer + signals; }
    double cpu_frame = 0;  // record + submit + wait, wall clock
    bool from_timestamps = false;
};

/** One signal's images of a frame, on the CPU, row-major (components interleaved). */
struct SignalData {
    int components = 1;
    std::vector<float> raw, accumulated, reference;  // reference: checkpoints only
    std::vector<uint16_t> age;                       // rrc's age of the channel (rrc_vulkan_channel_images.age)
    std::vector<float> brute_force;                  // checkpoints: 4x the per-frame samples
    std::vector<float> shown, pcss;                  // soft only: the --soft-prior display, the fallback
    std::vector<float> base;                         // pcf, env with the residual, checkpoints: its base (signals.h, pcf_base, env_base)
    std::vector<float> display;                      // pcf with a PcfDisplay remap: what is shown (the remapped accumulated)
    std::vector<float> confidence;                   // pcf with confidence: the per-frame w
    std::vector<float> weighted_target;              // pcf with confidence, checkpoints: the confidence-weighted disk mean
};

struct FrameOutput {
    int index = 0;
    bool checkpoint = false;
    int width = 0, height = 0;
    std::vector<uint8_t> mask;                   // rrc's mask bits
    std::vector<uint16_t> age;                   // the track age (age.comp): consecutive hits, whatever the channels
    std::array<std::vector<uint8_t>, 3> colour;  // RGBA8: accumulated; raw, reference (checkpoints)
    std::vector<float> position;                 // G-buffer world position, RGBA
    std::vector<uint16_t> object;                // G-buffer object index + 1, 0 background (the visibility oracle)
    std::vector<float> prev_clip;                // G-buffer previous clip position, RGBA
    std::vector<uint8_t> material;               // G-buffer material id
    std::vector<float> normal;                   // G-buffer world normal, xyz
    glm::vec3 eye{0.0f};                         // camera position
    float pixel_angle = 0.0f;                    // radians per pixel, vertically
    SignalData pcf, env, soft;
    FrameTimings timings;
};

class Renderer {
public:
    Renderer(Gpu& gpu, const Scene& scene, const RendererSettings& settings);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /** Renders frame `index` (reset makes rrc miss everywhere); reference pass if `checkpoint`. */
    FrameOutput render(int index, bool reset, bool checkpoint);
    uint64_t rrc_memory_bytes() const { return rrc_->memory_bytes(); }
    const RrcStage& rrc() const { return *rrc_; }

private:
    void read_back(FrameOutput& out, uint32_t parity) const;
    Gpu& gpu_;
    const Scene& scene_;
    RendererSettings s_;
    std::unique_ptr<GpuScene> gpu_scene_;
    ShadowMaps maps_;
    std::unique_ptr<ShadowPass> shadows_;
    std::unique_ptr<GBufferPass> gbuffer_;
    std::unique_ptr<SignalPasses> signals_;
    std::unique_ptr<RrcStage> rrc_;
    std::unique_ptr<PostPasses> post_;
    std::unique_ptr<Readback> readback_;
    struct Slots {
        int mask, age[2], rrc_age[3], colour[3], raw[3], acc[3], ref[3], brute[3], shown, pcss, position, normal, prev_clip, confidence,
            weighted, pcf_base, env_base;
    } slot_{};
    rrc_host::FencedCommands commands_;
    rrc_host::TimestampQueries queries_;  // kStampCount
    uint32_t parity_ = 0;
};

}  // namespace rrc_sample
