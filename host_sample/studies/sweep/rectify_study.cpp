#include "rectify_study.h"

#include "rrc_stage.h"
#include "sweep_engine.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

namespace rrc_sweep {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/** One configuration of the study: an application's FIXED/bilinear channel at lambda, rectify off or on. */
struct StudyConfig {
    App app;
    rrc_sample::ChannelSettings channel;
    int base = -1;       // the index of the same configuration without its cure
    std::string preset;  // "" or the preset row's name
    bool lighting_turn = true;  // with a view lobe: the frames carry the environment map's turn (rrc_stage.h)
};

/** A view lobe of `pixels` of the vertical angle at the study's size, in radians (rrc-sample's rule,
 *  channel_presets.h, kEnvViewLobePixels). */
float study_view_lobe(const SweepOptions& o, float pixels) {
    return pixels * rrc_sample::Scene::make(o.scene).camera(0.0).fov_y / (float)o.height;
}

std::vector<StudyConfig> study_configs(const SweepOptions& o, uint32_t sigs) {
    std::vector<StudyConfig> c;
    for (const App& app : apps_of(sigs)) {
        for (float lambda : o.lambdas) {
            rrc_sample::ChannelSettings off{lambda, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0};
            const int base = (int)c.size();
            c.push_back({app, off});
            for (float gamma : o.rectify_gammas) {
                rrc_sample::ChannelSettings on = off;
                on.rectify = 1;
                on.rectify_gamma = gamma;
                c.push_back({app, on, base});
            }
            // The lag detector (docs/CONVENTIONS.md, "The lag detector") on the same FIXED
            // blend, rectification off: the cure the moving light's lag target is about. Not on
            // soft, whose one-sample binary blocks make it drop right histories
            // (docs/measurements/PERFORMANCE.md, "The lag detector (0.5): what it buys, measured").
            if (o.antilag && app.signal != kSignalSoft)
                for (float gamma : o.antilag_gammas) {
                    rrc_sample::ChannelSettings on = off;
                    on.antilag = 1;
                    on.antilag_gamma = gamma;
                    on.antilag_threshold = o.antilag_threshold;
                    c.push_back({app, on, base});
                }
            // The view lobe with the lighting's turn (docs/CONVENTIONS.md, "The view-dependent
            // history"): env only, one row per --lobe-pixels (rrc-sample's lobe by default); the
            // frames carry the environment map's turn, so the cap acts only while the light moves.
            if (o.view_lobe && app.signal == kSignalEnv)
                for (float px : o.lobe_pixels) {
                    rrc_sample::ChannelSettings on = off;
                    on.view_lobe = study_view_lobe(o, px);
                    c.push_back({app, on, base});
                }
        }
        // rrc-sample's pcf and env presets (testbed/channel_presets.h) without and with their cures:
        // the residual (testbed README.md, "The pcf residual", "The env residual") and env's view
        // lobe fed the lighting's turn ("The env residual's view lobe"); env also with the residual
        // alone, each cure's share.
        if (o.antilag && app.signal != kSignalSoft) {
            const rrc_sample::ChannelPresets presets;
            const rrc_sample::ChannelSettings preset = app.signal == kSignalPcf ? presets.pcf : presets.env;
            rrc_sample::ChannelSettings without = preset;
            without.residual = 0;
            without.view_lobe = 0.0f;
            const int base = (int)c.size();
            c.push_back({app, without, -1, "the preset without its cures"});
            if (preset.view_lobe > 0.0f) {
                rrc_sample::ChannelSettings residual_only = preset;
                residual_only.view_lobe = 0.0f;
                c.push_back({app, residual_only, base, "the preset without its view lobe"});
            }
            c.push_back({app, preset, base, "the preset"});
            // The env preset with other lobes (--preset-lobes): the lobe's choice (testbed README.md,
            // "The env residual's view lobe").
            if (app.signal == kSignalEnv)
                for (float alpha : o.preset_lobes) {
                    rrc_sample::ChannelSettings other = preset;
                    other.view_lobe = alpha;
                    char name[64];
                    std::snprintf(name, sizeof name, "the preset with a view lobe of %g rad", (double)alpha);
                    c.push_back({app, other, base, name});
                }
        }
    }
    return c;
}

using rrc_host::full_barrier;

bool scored(uint32_t signal, uint8_t m) { return signal == kSignalEnv ? m == rrc_sample::kMatSphere : m != rrc_sample::kMatBackground; }

/** env's target noise per value, half the mean squared difference of the two estimates over `pixels`. */
double env_noise(const FrameTarget& t, const std::vector<uint32_t>& pixels) {
    double n = 0.0;
    for (uint32_t p : pixels)
        for (int c = 0; c < 3; ++c) n += 0.5 * std::pow((double)t.env[p * 4 + c] - t.env_twin[p * 4 + c], 2.0);
    return pixels.empty() ? 0.0 : n / (3.0 * (double)pixels.size());
}

/** What one scenario gives per application: its checkpoints' targets (only those with pixels to score). */
struct AppTargets {
    std::vector<CheckpointTarget> targets;
    std::vector<size_t> checkpoint;  // which of o.checkpoints() each is
    double fraction = 0.0, threshold = 0.0, change = 0.0;
    size_t pixels = 0;
};

/** Runs every configuration over every seed in one scene; returns each configuration's metrics.
 *  moving: the lag-error targets (changed pixels); else every scored pixel. */
std::vector<Metrics> run_scenario(Gpu& gpu, const rrc_sample::Scene& scene, const SweepOptions& o, uint32_t sigs,
                                  const std::vector<StudyConfig>& configs, bool moving, std::map<uint32_t, AppTargets>* stats,
                                  std::ostream* progress, const std::chrono::steady_clock::time_point& start) {
    rrc_sample::RenderSettings rs;
    rs.width = o.width;
    rs.height = o.height;
    Engine e(gpu, scene, rs);
    const std::vector<int> checkpoints = o.checkpoints();
    const int last = checkpoints.back();
    const int k = o.rrc_taps.front();

    // ---- Targets: each checkpoint's, and (moving) the frame's before, to find the pixels that changed.
    std::map<uint32_t, AppTargets> apps;
    for (size_t ci = 0; ci < checkpoints.size(); ++ci) {
        const int t = checkpoints[ci];
        const FrameTarget cur = frame_target(e, t, sigs, (uint32_t)o.reference_samples);
        FrameTarget prev;
        if (moving) prev = frame_target(e, t - 1, sigs, (uint32_t)o.reference_samples);
        for (const App& app : apps_of(sigs)) {
            AppTargets& at = apps[app.signal];
            const bool env = app.signal == kSignalEnv;
            const int stride = stride_of(app.signal), comps = env ? 3 : 1;
            const std::vector<float>& now = cur.of(app.signal);
            std::vector<uint32_t> all;
            for (uint32_t p = 0; p < cur.material.size(); ++p)
                if (scored(app.signal, cur.material[p])) all.push_back(p);
            const double noise_all = env ? env_noise(cur, all) : 0.0;
            CheckpointTarget ct;
            ct.components = comps;
            if (moving) {
                const std::vector<float>& before = prev.of(app.signal);
                const double tau = change_threshold(app.signal, o.change_threshold, noise_all);
                at.threshold = std::max(at.threshold, tau);
                double change = 0.0;
                for (uint32_t p : all) {
                    if (!scored(app.signal, prev.material[p])) continue;
                    double d = 0.0;
                    for (int c = 0; c < comps; ++c) d = std::max(d, (double)std::abs(now[p * stride + c] - before[p * stride + c]));
                    if (d > tau) ct.pixels.push_back(p), change += d;
                }
                at.fraction += all.empty() ? 0.0 : (double)ct.pixels.size() / (double)all.size() / (double)checkpoints.size();
                at.change += change;
                at.pixels += ct.pixels.size();
            } else {
                ct.pixels = all;
            }
            for (uint32_t p : ct.pixels)
                for (int c = 0; c < comps; ++c) ct.target.push_back(now[p * stride + c]);
            ct.noise = env ? env_noise(cur, ct.pixels) : 0.0;
            ct.is_static.assign(ct.pixels.size(), 0);
            if (moving && ci == 0 && !o.out.empty()) {  // the first checkpoint's changed pixels, to look at: changed_<app>.pgm
                std::filesystem::create_directories(o.out);
                std::ofstream pgm(std::filesystem::path(o.out) / ("changed_" + std::string(app.name) + ".pgm"), std::ios::binary);
                std::vector<uint8_t> img(cur.material.size(), 0);
                for (uint32_t p : all) img[p] = 80;
                for (uint32_t p : ct.pixels) img[p] = 255;
                pgm << "P5\n" << o.width << " " << o.height << "\n255\n";
                pgm.write((const char*)img.data(), (std::streamsize)img.size());
            }
            if (ct.pixels.empty()) continue;  // nothing to score at this checkpoint
            at.targets.push_back(std::move(ct));
            at.checkpoint.push_back(ci);
        }
    }
    for (auto& [sig, at] : apps)
        if (at.pixels) at.change /= (double)at.pixels;
    if (progress)
        *progress << (moving ? "light moving" : "light fixed") << ": targets of " << checkpoints.size() * (moving ? 2 : 1) << " frames ("
                  << (int)std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s)" << std::endl;

    // ---- rrc: one context per configuration, all fed the same signals, frame by frame and seed by seed.
    std::vector<std::unique_ptr<rrc_sample::RrcStage>> stages;
    for (const StudyConfig& c : configs) {
        rrc_sample::RrcSettings s = e.rrc_settings(c.app.signal, c.channel);
        s.lighting_turn = c.lighting_turn;
        stages.emplace_back(new rrc_sample::RrcStage(gpu, s));
    }
    bool pcf_residual = false, env_residual = false;  // a row accumulates the residual: the frame writes its base
    for (const StudyConfig& c : configs) {
        pcf_residual |= c.app.signal == kSignalPcf && c.channel.residual;
        env_residual |= c.app.signal == kSignalEnv && c.channel.residual;
    }
    rrc_sample::Readback rb(gpu);
    std::vector<int> slots;
    for (size_t i = 0; i < stages.size(); ++i) slots.push_back(rb.add(signal_image(stages[i]->accumulated(), configs[i].app.signal)));
    rb.allocate();
    std::vector<Ensemble> ensembles;
    for (const StudyConfig& c : configs) ensembles.emplace_back(apps[c.app.signal].targets.size());
    for (int seed = 0; seed < o.seeds; ++seed) {
        const Sampling sampling{kFirstSeed + (uint32_t)seed, 0, false, env_residual ? rrc_sample::kSampleEnvBase : 0u};
        for (int f = 0; f <= last; ++f) {
            const FrameState state = e.begin_frame(f, k, sampling.seed);
            const auto cp = std::find(checkpoints.begin(), checkpoints.end(), f);
            const bool read = cp != checkpoints.end();
            e.submit(0, [&](VkCommandBuffer c, auto&&) {
                e.record_geometry(c, state, sigs);
                full_barrier(c);
                // soft: the frame's one point of the light, its map rendered here (as the sweep's k = 1 runs).
                e.signals.record(c, sigs, state, sampling, rrc_sample::lamp_frame_points(scene.lamp, f, 1, sampling.seed), scene,
                                 e.shadows);
                // pcf's residual base for the preset rows that take it (testbed README.md, "The pcf residual").
                const rrc_sample::Image* pcf_base = pcf_residual ? e.signals.record_pcf_base(c, rrc_sample::kSamplePcfBaseTaps) : nullptr;
                full_barrier(c);
                for (size_t i = 0; i < stages.size(); ++i) {
                    const bool residual = configs[i].channel.residual != 0, env = configs[i].app.signal == kSignalEnv;
                    stages[i]->record(c, e.gbuffer.images(), e.signals.raw(), state, (uint64_t)f, f == 0, nullptr, nullptr,
                                      residual && env ? &e.signals.env_base() : nullptr, residual && !env ? pcf_base : nullptr);
                }
                if (read) rb.record(c, slots);
            });
            if (!read) continue;
            const size_t ci = (size_t)(cp - checkpoints.begin());
            for (size_t i = 0; i < stages.size(); ++i) {
                const AppTargets& at = apps[configs[i].app.signal];
                const auto it = std::find(at.checkpoint.begin(), at.checkpoint.end(), ci);
                if (it == at.checkpoint.end()) continue;
                const size_t j = (size_t)(it - at.checkpoint.begin());
                const std::vector<float> img = floats_of(rb, slots[i]);
                ensembles[i].add(j, at.targets[j], img.data(), stride_of(configs[i].app.signal));
            }
        }
        if (progress)
            *progress << (moving ? "light moving" : "light fixed") << ", " << configs.size() << " configurations: seed " << seed + 1 << "/"
                      << o.seeds << " done (" << (int)std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                      << " s)" << std::endl;
    }
    std::vector<Metrics> m;
    for (size_t i = 0; i < configs.size(); ++i) {
        const AppTargets& at = apps[configs[i].app.signal];
        if (at.targets.empty()) {
            Metrics none;
            none.rmse = none.bias2 = none.variance = none.mse_measured = none.psnr = none.flicker = kNaN;
            m.push_back(none);
        } else {
            m.push_back(ensembles[i].metrics(at.targets));
        }
    }
    if (stats) *stats = apps;
    return m;
}

std::string num(double v, const char* fmt = "%.4g") {
    if (std::isnan(v)) return "n/a";
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return b;
}

std::string cure_label(const RectifyRow& row) {
    if (!row.preset.empty()) return row.preset + " (" + blend_label(row.channel.blend) + ", " + filter_label(row.channel) + ")";
    if (row.antilag) return "lag detector, γ_a = " + num(row.antilag_gamma, "%g") + ", T = " + num(row.antilag_threshold, "%g");
    if (row.lighting_turn) return "view lobe α = " + num(row.channel.view_lobe, "%.4g") + " rad with the lighting's turn";
    return row.rectify ? "rectify, γ = " + num(row.gamma, "%g") : std::string("none");
}

const RectifyRow* off_row(const RectifyResult& r, const RectifyRow& row) { return row.base >= 0 ? &r.rows[(size_t)row.base] : nullptr; }

}  // namespace

double change_threshold(uint32_t signal, double tau, double noise) {
    // env's values are radiance and its target is itself a 256-ray estimate: its changes are
    // scored above the noise of a difference of two estimates (3 sigma), at least 0.01.
    return signal == kSignalEnv ? std::max(0.01, 3.0 * std::sqrt(2.0 * noise)) : tau;
}

RectifyResult run_rectify_study(const SweepOptions& o, std::ostream* progress) {
    if (o.quiet) progress = nullptr;
    if (o.light_speed == 0.0f) throw std::runtime_error("the rectification study needs a moving light (--light-speed)");
    const auto start = std::chrono::steady_clock::now();
    rrc_sample::Scene scene = rrc_sample::Scene::make(o.scene);
    if (o.motion != "all") scene.camera_speed = 0.0f;
    if (o.motion == "still")
        for (auto& obj : scene.objects) obj.moves = false;
    RectifyResult r;
    const uint32_t sigs = o.signals ? (o.signals & scene.signals) : scene.signals;
    if (!sigs) throw std::runtime_error("scene " + scene.name + " uses none of the signals asked for");
    r.k = o.rrc_taps.front();
    r.light_speed = o.light_speed;
    r.apps = apps_of(sigs);
    Gpu gpu(rrc_sample::GpuOptions{o.validation, o.device});
    r.device = gpu.device_name();
    const std::vector<StudyConfig> configs = study_configs(o, sigs);
    if (progress)
        *progress << "rrc-sweep --study rectify: scene " << scene.name << ", " << o.width << "x" << o.height << ", motion " << o.motion
                  << ", light " << o.light_speed << " degrees a frame, k = " << r.k << ", " << configs.size() << " configurations, "
                  << o.seeds << " seeds, checkpoints " << o.checkpoints().front() << ".." << o.checkpoints().back() << " every "
                  << o.checkpoint_every << "\ndevice: " << r.device << (o.validation ? " (validation layer on)" : "") << std::endl;

    std::map<uint32_t, AppTargets> moving_stats;
    scene.light_speed = o.light_speed;
    const std::vector<Metrics> lag = run_scenario(gpu, scene, o, sigs, configs, true, &moving_stats, progress, start);
    scene.light_speed = 0.0f;
    const std::vector<Metrics> still = run_scenario(gpu, scene, o, sigs, configs, false, nullptr, progress, start);
    for (size_t i = 0; i < configs.size(); ++i) {
        RectifyRow row;
        row.app = configs[i].app;
        row.lambda = configs[i].channel.lambda;
        row.rectify = configs[i].channel.rectify;
        row.gamma = row.rectify ? configs[i].channel.rectify_gamma : 0.0f;
        row.antilag = configs[i].channel.antilag;
        row.antilag_gamma = row.antilag ? configs[i].channel.antilag_gamma : 0.0f;
        row.antilag_threshold = row.antilag ? configs[i].channel.antilag_threshold : 0.0f;
        row.channel = configs[i].channel;
        row.preset = configs[i].preset;
        row.lighting_turn = configs[i].channel.view_lobe > 0.0f && configs[i].lighting_turn;
        row.base = configs[i].base;
        row.lag = lag[i];
        row.still = still[i];
        r.rows.push_back(row);
    }
    for (const App& app : r.apps) {
        const AppTargets& at = moving_stats[app.signal];
        r.changed_fraction.push_back(at.fraction);
        r.change_threshold.push_back(at.threshold);
        r.mean_change.push_back(at.pixels ? at.change : kNaN);
        r.changed_pixels.push_back(at.pixels);
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    vkDeviceWaitIdle(gpu.device);
    r.validation_messages = gpu.message_count();
    return r;
}

void write_rectify_files(const SweepOptions& o, const RectifyResult& r, const std::string& command_line) {
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);
    auto open = [&](const char* name) {
        std::ofstream f(dir / name);
        if (!f) throw std::runtime_error("cannot write " + (dir / name).string());
        return f;
    };
    {
        std::ofstream f = open("rectify.csv");
        f << "app,k,lambda,blend,filter,rectify,gamma,antilag,antilag_gamma,antilag_threshold,light_speed,lag_rmse,lag_bias2,"
             "lag_variance,lag_checkpoints,static_variance,static_rmse,static_bias2,lag_ratio,lag_bias2_ratio,variance_ratio,"
             "static_rmse_ratio,seeds,preset,lighting_turn\n";
        for (const RectifyRow& row : r.rows) {
            const RectifyRow* off = off_row(r, row);
            const double lag_ratio = off ? row.lag.rmse / off->lag.rmse : kNaN;
            const double bias_ratio = off ? row.lag.bias2 / off->lag.bias2 : kNaN;
            const double var_ratio = off ? row.still.variance / off->still.variance : kNaN;
            const double rmse_ratio = off ? row.still.rmse / off->still.rmse : kNaN;
            f << row.app.name << "," << r.k << "," << num(row.lambda, "%.2f") << "," << blend_label(row.channel.blend) << ","
              << filter_label(row.channel) << "," << row.rectify << ","
              << num(row.gamma, "%.2f") << "," << row.antilag << "," << num(row.antilag_gamma, "%.2f") << ","
              << num(row.antilag_threshold, "%.2f") << "," << num(r.light_speed, "%g") << "," << num(row.lag.rmse, "%.6g") << ","
              << num(row.lag.bias2, "%.6g") << "," << num(row.lag.variance, "%.6g") << "," << row.lag.checkpoints << ","
              << num(row.still.variance, "%.6g") << "," << num(row.still.rmse, "%.6g") << "," << num(row.still.bias2, "%.6g") << ","
              << num(lag_ratio, "%.4f") << "," << num(bias_ratio, "%.4f") << "," << num(var_ratio, "%.4f") << ","
              << num(rmse_ratio, "%.4f") << "," << row.still.seeds << "," << row.preset << "," << (row.lighting_turn ? 1 : 0) << "\n";
        }
    }
    std::ofstream f = open("rectify.md");
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    f << "# History rectification: lag error and static variance\n\n"
      << "- command: `" << command_line << "`\n"
      << "- date: " << date << "; device: " << r.device << "; " << (int)r.seconds << " s\n"
      << "- scene " << o.scene << ", " << o.width << "x" << o.height << ", motion " << o.motion << " (camera"
      << (o.motion == "all"            ? " and torus move"
          : o.motion == "camera-still" ? " still, the torus moves"
                                       : " and torus still")
      << "), k = " << r.k << " samples a frame, FIXED blend, bilinear history, " << o.seeds << " seeds, frames 0.."
      << o.checkpoints().back() << " from a reset, scored at " << o.checkpoints().front() << ".." << o.checkpoints().back() << " every "
      << o.checkpoint_every << "\n"
      << "- moving light: the sun and the environment map turn " << r.light_speed
      << " degrees a frame about the vertical axis (30 frames a second of scene time); the area lamp (soft) does not move\n"
      << "- lag error: RMSE against the moving light's target on the pixels whose target changed since the frame before (a component by "
         "more than the threshold below), MSE over seeds and those pixels, averaged over the scored frames (env: the target's own noise "
         "subtracted)\n"
      << "- static variance: the same rows with the light fixed, the unbiased variance across seeds per value, averaged over every scored "
         "pixel and frame; ratio = with rectification / without, same lambda\n\n"
      << "| app | changed pixels (share of scored) | threshold | mean change |\n|---|---|---|---|\n";
    for (size_t a = 0; a < r.apps.size(); ++a)
        f << "| " << r.apps[a].name << " | " << r.changed_pixels[a] << " (" << num(100.0 * r.changed_fraction[a], "%.1f") << "%) | "
          << num(r.change_threshold[a], "%.3g") << " | " << num(r.mean_change[a], "%.3g") << " |\n";
    f << "\n| app | lambda | cure | lag error | lag ratio | lag bias² | bias² ratio | static variance | variance ratio | static RMSE | "
         "RMSE ratio | static bias² |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RectifyRow& row : r.rows) {
        const RectifyRow* off = off_row(r, row);
        const bool cured = off != nullptr;
        auto ratio = [&](double a, double b) { return cured ? num(a / b, "%.2f") : std::string(""); };
        f << "| " << row.app.name << " | " << num(row.lambda, "%.2f") << " | " << cure_label(row) << " | " << num(row.lag.rmse, "%.4f")
          << " | " << (cured ? ratio(row.lag.rmse, off->lag.rmse) : "") << " | " << num(row.lag.bias2, "%.3g") << " | "
          << (cured ? ratio(row.lag.bias2, off->lag.bias2) : "") << " | " << num(row.still.variance, "%.3g") << " | "
          << (cured ? ratio(row.still.variance, off->still.variance) : "") << " | " << num(row.still.rmse, "%.4f") << " | "
          << (cured ? ratio(row.still.rmse, off->still.rmse) : "") << " | " << num(row.still.bias2, "%.3g") << " |\n";
    }
    f << "\n## Verdicts (lambda = 0.9: lag error at most half of without, static variance at most 1.5x)\n\n";
    bool any = false;
    for (const RectifyRow& row : r.rows) {
        if (!row.rectify || !row.preset.empty() || std::abs(row.lambda - 0.9f) > 1e-4f) continue;
        const RectifyRow* off = off_row(r, row);
        if (!off) continue;
        any = true;
        const double lr = row.lag.rmse / off->lag.rmse, vr = row.still.variance / off->still.variance;
        const bool soft = row.app.signal == kSignalSoft;
        f << "- " << row.app.name << ", γ = " << num(row.gamma, "%g") << ": lag error " << num(off->lag.rmse, "%.4f") << " -> "
          << num(row.lag.rmse, "%.4f");
        if (std::isnan(lr))
            f << " (no pixel's target changed)";
        else
            f << " (x" << num(lr, "%.3f") << ", target <= 0.5: " << (lr <= 0.5 ? "PASS" : "FAIL") << ")";
        f << "; static variance " << num(off->still.variance, "%.3g") << " -> " << num(row.still.variance, "%.3g") << " (x"
          << num(vr, "%.3f") << ", target <= 1.5: "
          << (std::isnan(vr) ? "n/a"
              : vr <= 1.5    ? "PASS"
                             : "FAIL")
          << "); static RMSE " << num(off->still.rmse, "%.4f") << " -> " << num(row.still.rmse, "%.4f")
          << (soft ? " (soft: outside the study's targets, shown to say what happens)" : "") << "\n";
    }
    if (!any) f << "- no lambda = 0.9 rows\n";
    f << "\n## Verdicts, the lag detector, the view lobe with the lighting's turn and the presets' cures (lambda = 0.9: lag bias² on the changed pixels at "
         "most half of without, static RMSE at most 1.1x)\n\n";
    any = false;
    for (const RectifyRow& row : r.rows) {
        // The cures' rows at lambda 0.9 and every preset row that has a row without its cures.
        if (row.preset.empty() && (!(row.antilag || row.lighting_turn) || std::abs(row.lambda - 0.9f) > 1e-4f)) continue;
        const RectifyRow* off = off_row(r, row);
        if (!off) continue;
        any = true;
        const double br = row.lag.bias2 / off->lag.bias2, rr = row.still.rmse / off->still.rmse;
        f << "- " << row.app.name << ", " << cure_label(row) << ": lag bias² " << num(off->lag.bias2, "%.3g") << " -> "
          << num(row.lag.bias2, "%.3g");
        if (std::isnan(br))
            f << " (no pixel's target changed)";
        else
            f << " (x" << num(br, "%.3f") << ", target <= 0.5: " << (br <= 0.5 ? "PASS" : "FAIL") << ")";
        f << "; static RMSE " << num(off->still.rmse, "%.4f") << " -> " << num(row.still.rmse, "%.4f") << " (x" << num(rr, "%.3f")
          << ", target <= 1.1: "
          << (std::isnan(rr) ? "n/a"
              : rr <= 1.1    ? "PASS"
                             : "FAIL")
          << "); lag error " << num(off->lag.rmse, "%.4f") << " -> " << num(row.lag.rmse, "%.4f") << "\n";
    }
    if (!any) f << "- no lambda = 0.9 rows with the lag detector or the lighting's turn\n";
}

}  // namespace rrc_sweep
