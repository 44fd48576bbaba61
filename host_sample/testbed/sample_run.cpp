#include "sample_run.h"

#include "finish.h"
#include "output.h"
#include "scene.h"
#include "summary.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <future>
#include <stdexcept>

namespace rrc_sample {
namespace {

std::string channel_line(const rrc_channel_desc& c) {
    const char* blend = c.blend == RRC_BLEND_FIXED ? "fixed" : c.blend == RRC_BLEND_AGE_AWARE ? "age_aware" : "running_mean";
    const char* filter = c.filter == RRC_HISTORY_FILTER_NEAREST       ? "nearest"
                         : c.filter == RRC_HISTORY_FILTER_CATMULL_ROM ? "catmull_rom"
                         : c.filter == RRC_HISTORY_FILTER_GAUSSIAN    ? "gaussian"
                                                                      : "bilinear";
    char line[256];
    if (c.blend == RRC_BLEND_RUNNING_MEAN)
        std::snprintf(line, sizeof line, "%s: %u component%s, %s, age cap %u, %s, %s history", c.name, c.components,
                      c.components > 1 ? "s" : "", blend, c.age_cap ? c.age_cap : 255u, filter,
                      c.precision == RRC_HISTORY_FP32 ? "fp32" : "fp16");
    else
        std::snprintf(line, sizeof line, "%s: %u component%s, %s, lambda %.2f, %s, %s history", c.name, c.components,
                      c.components > 1 ? "s" : "", blend, c.lambda, filter, c.precision == RRC_HISTORY_FP32 ? "fp32" : "fp16");
    std::string l = line;
    if (c.filter == RRC_HISTORY_FILTER_GAUSSIAN)
        l += ", blur sigma " + std::to_string(c.blur_sigma > 0.0f ? c.blur_sigma : RRC_DEFAULT_BLUR_SIGMA).substr(0, 5);
    if (c.confidence) l += ", confidence";
    if (c.rectify) l += ", rectified (gamma " + std::to_string(c.rectify_gamma > 0.0f ? c.rectify_gamma : RRC_DEFAULT_RECTIFY_GAMMA).substr(0, 4) + ")";
    if (c.antilag)
        l += ", anti-lag (gamma " + std::to_string(c.antilag_gamma > 0.0f ? c.antilag_gamma : RRC_DEFAULT_ANTILAG_GAMMA).substr(0, 4) +
             ", threshold " + std::to_string(c.antilag_threshold > 0.0f ? c.antilag_threshold : RRC_DEFAULT_ANTILAG_THRESHOLD).substr(0, 5) + ")";
    if (c.blur_bound > 0.0f) l += ", blur bound " + std::to_string(c.blur_bound).substr(0, 5) + " px^2";
    if (c.view_lobe > 0.0f) l += ", view lobe " + std::to_string(c.view_lobe).substr(0, 6) + " rad";
    // The sample's bases: soft's stable PCSS estimate (README.md, "The soft residual"), pcf's
    // bilinear compares ("The pcf residual"), env's deterministic sample ("The env residual").
    if (c.residual)
        l += std::string(", the residual against its base (") +
             (std::strcmp(c.name, "soft") == 0  ? "the stable PCSS estimate"
              : std::strcmp(c.name, "pcf") == 0 ? "the mean of bilinear shadow compares"
                                                : "the env pass's deterministic sample") +
             ")";
    if (c.fill_age)
        l += ", fill below age " + std::to_string(c.fill_age) + " (radius " + std::to_string(c.fill_radius ? c.fill_radius : RRC_DEFAULT_FILL_RADIUS) +
             ", fallback weight " + std::to_string(c.fill_prior).substr(0, 4) + ")";
    return l;
}

}  // namespace

bool is_checkpoint(const Options& o, int frame) {
    for (int f : o.reference_frames)
        if (f == frame) return true;
    if (o.reference_every <= 0) return false;
    return frame % o.reference_every == o.reference_every - 1 || frame == o.frames - 1;
}

RunResult run_sample(const Options& o, std::ostream* progress,
                     const std::function<void(const FrameOutput&, const FrameRecord&)>& on_frame) {
    if (o.quiet) progress = nullptr;
    Scene scene = Scene::make(o.scene);
    if (o.static_camera) scene.camera_speed = 0.0f;
    scene.light_speed = o.light_speed;
    scene.frozen_mirror_view = o.frozen_mirror_view;
    RunResult run;
    run.options = o;
    run.signals = o.signals ? (o.signals & scene.signals) : scene.signals;
    if (o.signals & ~scene.signals && progress)
        *progress << "note: scene " << scene.name << " does not use " << signal_list(o.signals & ~scene.signals)
                  << "; no channel is made for it\n";
    if (!run.signals) throw std::runtime_error("scene " + scene.name + " uses none of the signals asked for");

    RendererSettings rs;
    rs.render.width = o.width;
    rs.render.height = o.height;
    rs.render.taps = o.taps;
    rs.render.fps = o.fps;
    rs.render.sun_map = o.sun_map;
    rs.render.lamp_map = o.lamp_map;
    rs.render.pcf_radius = o.pcf_radius;
    rs.signals = run.signals;
    rs.reprojection = o.reprojection;
    rs.epsilon_scale = o.epsilon_scale;
    rs.depth_test = o.depth_test;
    rs.soft_prior = o.soft_prior;
    rs.channels = o.channels;
    // env's view lobe in pixels of the vertical angle (channel_presets.h, kEnvViewLobePixels).
    if (o.env_view_lobe_px > 0.0f) rs.channels.env.view_lobe = o.env_view_lobe_px * scene.camera(0.0).fov_y / (float)o.height;
    rs.pcf_display.smoothstep = o.pcf_smoothstep;
    rs.pcf_display.e0 = o.pcf_smooth_e0, rs.pcf_display.e1 = o.pcf_smooth_e1;
    rs.pcf_display.threshold = o.pcf_threshold;
    rs.render.seed = o.seed;
    rs.render.pcf_pattern = o.pcf_pattern;
    rs.render.env_base = o.channels.env.residual ? o.env_base : 0u;
    rs.render.pcf_base = o.channels.pcf.residual ? o.pcf_base : 0u;
    rs.use_object_id = o.object_id;
    rs.reference_samples = (uint32_t)o.reference_samples;

    std::filesystem::create_directories(o.out);
    Gpu gpu(GpuOptions{o.validation, o.device});
    run.device = gpu.device_name();
    try {
        Renderer renderer(gpu, scene, rs);
        run.rrc_memory_bytes = renderer.rrc_memory_bytes();
        for (const rrc_channel_desc& c : renderer.rrc().channels()) run.channels.push_back(channel_line(c));
        if (progress) {
            *progress << "rrc-sample: scene " << scene.name << ", " << o.width << "x" << o.height << ", " << o.frames << " frames, signals "
                      << signal_list(run.signals) << ", reprojection " << reprojection_name(o.reprojection) << ", depth test "
                      << depth_test_description(o) << (o.object_id ? ", object ids" : ", no object ids") << ", k = " << o.taps
                      << (o.reference_every > 0 ? ", reference " + std::to_string(o.reference_samples) + " samples every " +
                                                      std::to_string(o.reference_every) + " frames"
                                                : std::string(", no reference"))
                      << "\n"
                      << "device: " << run.device << (o.validation ? " (validation layer on)" : "") << "\n";
            for (const std::string& c : run.channels) *progress << "  rrc channel " << c << "\n";
        }
        std::unique_ptr<OutputWriter> writer;
        if (o.write_images) writer.reset(new OutputWriter(o.out, o.width, o.height));

        // Warm-up: lavapipe compiles shaders at their first dispatch; frame 0 then runs again with reset.
        renderer.render(0, true, false);
        const auto start = std::chrono::steady_clock::now();
        const VisibilityOracle oracle(scene);
        FinishReport finish(o, run.signals);
        FrameOutput previous;
        for (int t = 0; t < o.frames; ++t) {
            const bool reset = t == 0;
            FrameOutput out = renderer.render(t, reset, is_checkpoint(o, t));
            FrameRecord rec;
            // The oracle sees the matrices the renderer drew with (make_frame_state is pure CPU);
            // after a reset there is no previous frame, so nothing was visible.
            OracleView current_view, previous_view;
            oracle_views(make_frame_state(scene, rs.render, t), current_view, previous_view);
            static const std::vector<uint16_t> kNoPrevious;
            // Its ray casts overlap the frame's errors and files (single-threaded PNG/EXR
            // encoding), so the default run barely slows down; it only reads `out` and `previous`.
            std::vector<uint8_t> verdict;  // per pixel, for oracle/oracle_NNNN.png
            std::future<double> oracle_done = std::async(std::launch::async, [&] {
                const auto oracle_start = std::chrono::steady_clock::now();
                rec.visibility =
                    oracle.judge(current_view, previous_view, o.width, o.height, out.mask, reset ? kNoPrevious : previous.object, &verdict);
                return std::chrono::duration<double>(std::chrono::steady_clock::now() - oracle_start).count();
            });
            rec.index = t;
            rec.checkpoint = out.checkpoint;
            rec.hits = hit_stats(out.mask);
            rec.timings = out.timings;
            rec.errors = frame_errors(out);
            rec.finish = finish_errors(out);
            if (writer) writer->write(out);
            run.oracle_seconds += oracle_done.get();
            if (writer) writer->write_oracle(t, verdict);
            finish.add(out, verdict);
            if (on_frame) on_frame(out, rec);
            if (progress) *progress << progress_line(rec, o.frames) << std::flush;
            run.frames.push_back(std::move(rec));
            previous = std::move(out);
        }
        run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        finish.write(o.out);
        run.finish_table = finish.table();
        if (progress) *progress << run.finish_table;
    } catch (...) {
        gpu.shutdown();
        throw;
    }
    gpu.shutdown();  // leaked objects are reported here
    run.validation_messages = gpu.message_count();
    run.messages = gpu.messages();
    write_summary_files(run, o.out);
    return run;
}

}  // namespace rrc_sample
