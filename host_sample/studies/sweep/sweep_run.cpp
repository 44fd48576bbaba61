#include "sweep_run.h"

#include "bias_output.h"
#include "sweep_engine.h"
#include "sweep_time.h"

#include "frame_state.h"
#include "gpu.h"
#include "metrics.h"
#include "post.h"
#include "raster.h"
#include "readback.h"
#include "rrc_stage.h"
#include "scene.h"
#include "signals.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>

namespace rrc_sweep {
namespace {

/** Which clock a pass's time is read from: timestamps on a GPU, the wall clock (less an empty
 *  submission's) on a CPU device, whose timestamps are wrong after graphics work (above). Also
 *  keeps how far the two disagree, for sweep.md. */
struct Clock {
    bool wall = false;
    std::vector<double> ratio;  // timestamps / (wall - empty) of signal passes and rrc, per frame
    double ms(const Timing& t, const Timing& empty) const { return pass_ms(t, empty, wall); }
    void compare(const std::vector<Timing>& a, const std::vector<Timing>& b, const Timing& empty) {
        double stamps = 0.0, wall = 0.0;
        for (const auto* v : {&a, &b})
            for (const Timing& t : *v) stamps += t.stamps_ms, wall += pass_ms(t, empty, true);
        if (wall > 0.0) ratio.push_back(stamps / wall);
    }
};

/** Transfer reads (a readback) before the next compute write of the same image. */
void transfer_to_compute(VkCommandBuffer cmd) {
    rrc_sample::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                               0);
}

/** Per application, per checkpoint: the pixels scored, the target, its noise, the static pixels. */
using Targets = std::map<uint32_t, std::vector<CheckpointTarget>>;

/** The pixels an application is scored on: env the sphere's, the others every surface's. */
bool scored_by(uint32_t signal, uint8_t material) {
    return signal == kSignalEnv ? material == rrc_sample::kMatSphere : material != rrc_sample::kMatBackground;
}

/** --bias-maps: the checkpoint frames' G-buffers (material, depth, position) and, per application and
 *  checkpoint, the pixels whose target changed within the window (bias_regions.h, mark_changes). */
struct RegionSources {
    std::map<int, FrameTarget> frames;
    std::map<uint32_t, std::vector<std::vector<uint8_t>>> changed;
    void clear() { frames.clear(), changed.clear(); }
};

// The changed pixels' thresholds (README.md, "Bias maps"): pcf's and soft's targets are noiseless and
// compared at the same point: 1e-3 (the sweep's static pixels' rule); env's is a 256-ray estimate:
// 3 standard deviations of the difference of two estimates, at least 0.01 (the rectification study's).
constexpr float kChangeNoiseless = 1e-3f;
float change_threshold(uint32_t signal, const CheckpointTarget& t) {
    return signal == kSignalEnv ? (float)std::max(0.01, 3.0 * std::sqrt(2.0 * t.noise)) : kChangeNoiseless;
}

/** Fills `keep`: for each checkpoint t and each of the `window` frames t - j before it, pcf's and soft's
 *  targets of frame t - j's scene seen from frame t's camera, env's of frame t - j as it was rendered. */
void find_changes(Engine& e, const SweepOptions& o, uint32_t sigs, const std::map<uint32_t, std::vector<CheckpointTarget>>& targets,
                  std::map<int, FrameTarget>& frames, RegionSources& keep, std::ostream* progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<int> cps = o.checkpoints();
    const uint32_t n = o.width * o.height, same_point = sigs & (kSignalPcf | kSignalSoft);
    for (size_t c = 0; c < cps.size(); ++c) {
        const int t = cps[c];
        const FrameTarget& cur = frames.at(t);
        for (const App& app : apps_of(sigs)) keep.changed[app.signal].push_back(std::vector<uint8_t>(n, 0));
        auto mark = [&](uint32_t signal, const FrameTarget& before, bool at_same_point) {
            PreviousTarget pt;
            pt.values = before.of(signal).data();
            pt.stride = stride_of(signal);
            for (uint8_t m : before.material) pt.scored.push_back(scored_by(signal, m) ? 1 : 0);
            pt.at_same_point = at_same_point;
            if (at_same_point) pt.material = before.material;
            for (int i = 0; i < 16; ++i) pt.view_proj[i] = before.view_proj[i / 4][i % 4];
            const CheckpointTarget& ct = targets.at(signal)[c];
            mark_changes(keep.changed[signal][c], ct, pt, cur.position.data(), cur.material, o.width, o.height, change_threshold(signal, ct));
        };
        for (int j = 1; j <= o.change_window && t - j >= 0; ++j) {
            if (same_point) {
                const FrameTarget seen = frame_target(e, t - j, same_point, (uint32_t)o.reference_samples, t, false);
                for (uint32_t s : {(uint32_t)kSignalPcf, (uint32_t)kSignalSoft})
                    if (same_point & s) mark(s, seen, true);
            }
            if (sigs & kSignalEnv) {
                auto it = frames.find(t - j);
                if (it != frames.end()) {
                    mark(kSignalEnv, it->second, false);
                } else {
                    const FrameTarget own = frame_target(e, t - j, kSignalEnv, (uint32_t)o.reference_samples, -1, false);
                    mark(kSignalEnv, own, false);
                }
            }
        }
    }
    for (int t : cps) keep.frames[t] = frames.at(t);
    if (progress)
        *progress << "bias regions: the targets of the " << o.change_window << " frames before each checkpoint, "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s" << std::endl;
}

Targets make_targets(Engine& e, const SweepOptions& o, uint32_t sigs, std::ostream* progress, RegionSources* keep) {
    std::map<int, FrameTarget> frames;
    const auto t0 = std::chrono::steady_clock::now();
    for (int t : o.checkpoints())
        for (int f : {t - 1, t}) frames[f] = frame_target(e, f, sigs, (uint32_t)o.reference_samples);
    if (progress)
        *progress << "targets: " << frames.size() << " frames (checkpoints and the frames before them), "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s" << std::endl;

    Targets targets;
    for (const App& app : apps_of(sigs)) {
        for (int t : o.checkpoints()) {
            const FrameTarget& cur = frames.at(t);
            const FrameTarget& prev = frames.at(t - 1);
            const bool env = app.signal == kSignalEnv;
            auto scored = [&](uint8_t m) { return scored_by(app.signal, m); };
            const std::vector<float>& now = env ? cur.env : app.signal == kSignalPcf ? cur.pcf : cur.soft;
            const std::vector<float>& before = env ? prev.env : app.signal == kSignalPcf ? prev.pcf : prev.soft;
            CheckpointTarget ct;
            ct.components = env ? 3 : 1;
            const int stride = stride_of(app.signal);
            double noise = 0.0;
            for (uint32_t p = 0; p < cur.material.size(); ++p) {
                if (!scored(cur.material[p])) continue;
                ct.pixels.push_back(p);
                for (int c = 0; c < ct.components; ++c) {
                    ct.target.push_back(now[p * stride + c]);
                    // env: two independent estimates x, y of variance s^2 each: E(x - y)^2 = 2 s^2.
                    if (env) noise += 0.5 * std::pow((double)cur.env[p * 4 + c] - cur.env_twin[p * 4 + c], 2.0);
                }
            }
            ct.noise = ct.target.empty() ? 0.0 : noise / (double)ct.target.size();
            // Static: scored in both frames, and the target moved by less than tau (pcf's and soft's are
            // noiseless, 1e-3; env's is noisy: 3 standard deviations of a difference of two estimates).
            const double tau = env ? std::max(1e-3, 3.0 * std::sqrt(2.0 * ct.noise)) : 1e-3;
            for (uint32_t p : ct.pixels) {
                bool still = scored(prev.material[p]);
                for (int c = 0; c < ct.components && still; ++c) still = std::abs(now[p * stride + c] - before[p * stride + c]) <= tau;
                ct.is_static.push_back(still ? 1 : 0);
            }
            targets[app.signal].push_back(std::move(ct));
        }
    }
    if (keep) find_changes(e, o, sigs, targets, frames, *keep, progress);
    return targets;
}

/** The regions of every application at every checkpoint (bias_regions.h), from the targets' frames and
 *  rrc's mask and age at each checkpoint; also writes each application's region image. */
std::map<uint32_t, std::vector<RegionMap>> make_regions(const SweepOptions& o, uint32_t sigs, const Targets& targets, const RegionSources& sources,
                                                        const std::map<int, std::vector<uint8_t>>& masks,
                                                        const std::map<int, std::vector<uint16_t>>& ages) {
    std::map<uint32_t, std::vector<RegionMap>> maps;
    const std::vector<int> cps = o.checkpoints();
    for (const App& app : apps_of(sigs)) {
        std::vector<std::vector<uint8_t>> images;
        std::vector<std::vector<uint16_t>> age_images;
        std::vector<std::vector<float>> target_images;
        for (size_t c = 0; c < cps.size(); ++c) {
            const int t = cps[c];
            const FrameTarget& cur = sources.frames.at(t);
            RegionFrame g;
            g.width = o.width, g.height = o.height;
            g.material = cur.material, g.depth = cur.depth;
            g.mask = masks.at(t), g.age = ages.at(t);
            const CheckpointTarget& ct = targets.at(app.signal)[c];
            RegionThresholds th;
            th.object_material = rrc_sample::kMatMover;
            maps[app.signal].push_back(classify_regions(g, ct, sources.changed.at(app.signal)[c], th));
            images.push_back(region_image(maps[app.signal].back(), ct, g.material.size()));
            age_images.push_back(g.age);
            std::vector<float> target(g.material.size(), std::numeric_limits<float>::quiet_NaN());
            for (size_t i = 0; i < ct.pixels.size(); ++i) {
                double v = 0.0;
                for (int k = 0; k < ct.components; ++k) v += ct.target[i * ct.components + k];
                target[ct.pixels[i]] = (float)(v / ct.components);
            }
            target_images.push_back(std::move(target));
        }
        write_region_images(o, app.name, images, age_images, target_images);
    }
    return maps;
}

/** --bias-maps: a row's bias maps at every checkpoint into its EXR. */
void write_row_maps(const SweepOptions& o, const std::string& label, const Ensemble& e, const std::vector<CheckpointTarget>& targets) {
    std::vector<std::vector<float>> maps;
    for (size_t c = 0; c < targets.size(); ++c) maps.push_back(bias_map(e, c, targets[c], (size_t)o.width * o.height));
    write_bias_map(o, label, maps);
}

std::string eta(double done, double total, double seconds) {
    if (done <= 0.0) return "";
    const double left = seconds * (total - done) / done;
    return ", about " + std::to_string((int)std::lround(left)) + " s left";
}

}  // namespace

SweepResult run_sweep(const SweepOptions& o, std::ostream* progress) {
    if (o.quiet) progress = nullptr;
    const auto start = std::chrono::steady_clock::now();
    rrc_sample::Scene scene = rrc_sample::Scene::make(o.scene);
    if (o.motion != "all") scene.camera_speed = 0.0f;
    if (o.motion == "still")
        for (auto& obj : scene.objects) obj.moves = false;
    scene.light_speed = o.light_speed;  // the targets follow it: make_targets renders each scored frame's own light
    SweepResult result;
    result.signals = o.signals ? (o.signals & scene.signals) : scene.signals;
    if (!result.signals) throw std::runtime_error("scene " + scene.name + " uses none of the signals asked for");
    const uint32_t sigs = result.signals;

    rrc_sample::RenderSettings rs;
    rs.width = o.width;
    rs.height = o.height;
    Gpu gpu(rrc_sample::GpuOptions{o.validation, o.device});
    result.device = gpu.device_name();
    if (!gpu.timestamps) throw std::runtime_error("rrc-sweep times every pass with timestamps; this device's queue has none");
    Clock clock;
    clock.wall = o.clock == "wall" || (o.clock == "auto" && gpu.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
    result.clock = clock.wall ? "wall clock of each pass's own submission, less the fastest empty submission's" : "GPU timestamps";
    const std::vector<int> checkpoints = o.checkpoints();
    std::set<int> evaluated;  // frames read back: each checkpoint and the frame before it (flicker)
    for (int t : checkpoints) evaluated.insert(t - 1), evaluated.insert(t);
    const int last = checkpoints.back();
    if (progress)
        *progress << "rrc-sweep: scene " << scene.name << ", " << o.width << "x" << o.height << ", " << o.seeds << " seeds, frames 0.." << last
                  << ", checkpoints " << checkpoints.front() << ".." << last << " every " << o.checkpoint_every << "\ndevice: " << result.device
                  << (o.validation ? " (validation layer on)" : "") << std::endl;
    {
        Engine e(gpu, scene, rs);
        RegionSources target_frames;  // --bias-maps: the regions' inputs, until the regions are made
        const Targets targets = make_targets(e, o, sigs, progress, o.bias_maps ? &target_frames : nullptr);
        // --bias-maps: rrc's mask and its age (followed on the host) at each checkpoint, from the first run's
        // first seed: both depend on the geometry alone, which every run and seed shares.
        std::map<int, std::vector<uint8_t>> cp_masks;
        std::map<int, std::vector<uint16_t>> cp_ages;
        std::vector<uint16_t> age;
        std::map<uint32_t, std::vector<RegionMap>> regions;
        auto checkpoint_of = [&](int f) { return (size_t)(std::find(checkpoints.begin(), checkpoints.end(), f) - checkpoints.begin()); };

        // Brute force is timed inside the rrc runs' frames, one configuration a frame in turn, so that
        // both are timed under the same load (the machine may be shared); its errors come after.
        const std::vector<BruteConfig> brute = brute_configs(o, sigs);
        std::vector<std::vector<double>> brute_ms(brute.size());
        size_t brute_turn = 0;
        // The default channels of the applications alone and in one context together: what sharing saves.
        std::vector<double> together_ms, alone_sum_ms;
        // A channel's rrc time does not depend on k: its samples from every run are pooled, so that
        // every row's time is drawn from the whole sweep's span, as the brute force's is.
        std::map<std::string, std::vector<double>> pooled_rrc_ms;
        auto channel_key = [](const RrcConfig& c) {
            return std::string(c.app.name) + "/" + std::to_string(c.channel.lambda) + "/" + std::to_string((int)c.channel.blend) + "/" +
                   filter_label(c.channel) + "/" + std::to_string(c.channel.age_cap);
        };

        // ---- rrc: one run per (k, pattern), every configuration fed from the same signals.
        const std::vector<RrcRun> runs = rrc_runs(o, sigs);
        double work_total = 0.0, work_done = 0.0;
        for (const RrcRun& r : runs) work_total += (double)o.seeds * (last + 1) * (2.0 + 0.02 * r.configs.size() * 10.0);
        for (size_t ri = 0; ri < runs.size(); ++ri) {
            const RrcRun& run = runs[ri];
            std::vector<std::unique_ptr<rrc_sample::RrcStage>> stages;
            for (const RrcConfig& c : run.configs)
                stages.emplace_back(new rrc_sample::RrcStage(gpu, e.rrc_settings(c.app.signal, c.channel)));
            // The soft preset rows' fill fallback and soft residual (sweep_configs.cpp): rrc-sample's PCSS
            // estimates from the light centre's map (post.h), recorded in the row's own timed pass before
            // its dispatch, so that the row's rrc time holds the map and the estimate.  One set of passes
            // a row.  Soft's rows only: pcf's residual has its own base (below).
            std::vector<std::unique_ptr<rrc_sample::PostPasses>> pcss(stages.size());
            for (size_t i = 0; i < stages.size(); ++i)
                if (run.configs[i].app.signal == kSignalSoft && (run.configs[i].channel.fill_prior > 0.0f || run.configs[i].channel.residual))
                    pcss[i].reset(new rrc_sample::PostPasses(gpu, e.gpu_scene, e.gbuffer.images(), e.maps, stages[i]->mask(),
                                                             stages[i]->age(kSignalSoft), stages[i]->accumulated(), e.signals.raw(),
                                                             e.signals.reference(), o.width, o.height, true));
            // The sharing probe: each application's default channel alone, then all of them in one context.
            std::vector<std::unique_ptr<rrc_sample::RrcStage>> probe;
            const bool probing = run.pattern == 0 && apps_of(sigs).size() > 1;
            if (probing) {
                for (uint32_t bits : {(uint32_t)kSignalPcf, (uint32_t)kSignalEnv, (uint32_t)kSignalSoft, sigs}) {
                    if (!(bits & sigs)) continue;
                    probe.emplace_back(new rrc_sample::RrcStage(gpu, e.rrc_settings(bits & sigs)));
                }
            }
            rrc_sample::Readback rb(gpu);
            std::vector<int> out_slots;
            for (size_t i = 0; i < stages.size(); ++i)
                out_slots.push_back(rb.add(signal_image(stages[i]->accumulated(), run.configs[i].app.signal)));
            const int mask_slot = rb.add(stages.front()->mask());
            const int clip_slot = o.bias_maps ? rb.add(e.gbuffer.images().prev_clip, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL) : -1;
            rb.allocate();
            std::vector<Ensemble> ensembles(stages.size(), Ensemble(checkpoints.size()));
            std::map<uint32_t, std::vector<double>> signal_ms;  // per application
            std::vector<std::vector<double>> rrc_ms(stages.size());
            const std::vector<App> run_apps = run.pattern ? std::vector<App>{{kSignalPcf, "pcf"}} : apps_of(sigs);
            uint32_t run_sigs = 0;
            for (const App& a : run_apps) run_sigs |= a.signal;
            for (int seed = 0; seed < o.seeds; ++seed) {
                const Sampling sampling{kFirstSeed + (uint32_t)seed, run.pattern};
                // --pcf-base-in-signal: the pcf pass writes the base too (Sampling::pcf_base).
                Sampling pcf_sampling = sampling;
                if (o.pcf_base_in_signal) pcf_sampling.pcf_base = rrc_sample::kSamplePcfBaseTaps;
                std::vector<std::vector<float>> previous(stages.size());
                Timing floor{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
                for (int f = 0; f <= last; ++f) {
                    const FrameState state = e.begin_frame(f, run.k, sampling.seed);
                    const bool read = evaluated.count(f) != 0;
                    const bool hits = ri == 0 && seed == 0;  // the hit ratio per frame, once
                    const bool timed = f >= 2;  // frame 0 resets, frame 1 warms caches
                    const size_t bj = brute_turn % brute.size();
                    if (timed) ++brute_turn;
                    // Each pass in a submission of its own, timed both by two timestamps after full barriers
                    // and by the wall clock from vkQueueSubmit to its fence (less an empty submission's):
                    // lavapipe's timestamps around compute work are wrong once a frame has rendered the soft
                    // signal's shadow map (a 2.3 ms env pass stamped at 0.08 ms; README.md, "Definitions"),
                    // so on a CPU device the wall clock is what counts (Clock below).
                    e.submit(0, [&](VkCommandBuffer c, auto&&) { e.record_geometry(c, state, run_sigs); });
                    auto timed_pass = [&](auto&& record) {
                        const std::vector<double> t = e.submit(2, [&](VkCommandBuffer c, auto&& stamp) {
                            stamp();
                            record(c);
                            stamp();
                        });
                        return Timing{t[1] - t[0], e.last_wall_ms};
                    };
                    // The submission overhead is the fastest empty submission so far: one
                    // slow empty submission (a load spike) must not eat a pass's time.
                    Timing empty = timed_pass([](VkCommandBuffer) {});
                    floor = empty_floor(floor, empty);
                    empty = floor;
                    std::vector<Timing> app_t, stage_t, probe_t;
                    for (const App& a : run_apps)
                        app_t.push_back(timed_pass([&](VkCommandBuffer c) {
                            if (a.signal == kSignalSoft)  // k light points, one shadow map each (in the signal's time)
                                e.signals.record(c, a.signal, state, sampling, rrc_sample::lamp_frame_points(scene.lamp, f, run.k, sampling.seed),
                                                 scene, e.shadows);
                            else
                                e.signals.record(c, a.signal, state, a.signal == kSignalPcf ? pcf_sampling : sampling);
                        }));
                    for (size_t i = 0; i < stages.size(); ++i)
                        stage_t.push_back(timed_pass([&](VkCommandBuffer c) {
                            // As rrc-sample's renderer: the PCSS fallback, or the soft residual
                            // (testbed README.md, "The soft residual"); pcf's residual base ("The
                            // pcf residual").
                            const rrc_sample::Image *soft_fallback = nullptr, *pcf_base = nullptr;
                            if (pcss[i]) {
                                e.shadows.record(c, e.maps.lamp_centre, state.uniforms.lamp_centre_vp);
                                soft_fallback = pcss[i]->record_soft_fallback(c, 0, run.configs[i].channel);
                            }
                            if (run.configs[i].app.signal == kSignalPcf && run.configs[i].channel.residual)
                                pcf_base = e.signals.record_pcf_base(c, rrc_sample::kSamplePcfBaseTaps, o.pcf_base_in_signal);
                            stages[i]->record(c, e.gbuffer.images(), e.signals.raw(), state, (uint64_t)f, f == 0, nullptr, soft_fallback,
                                              nullptr, pcf_base);
                        }));
                    for (auto& st : probe)
                        probe_t.push_back(timed_pass([&](VkCommandBuffer c) { st->record(c, e.gbuffer.images(), e.signals.raw(), state, (uint64_t)f, f == 0); }));
                    if (timed) {  // its output is not read here
                        const Timing bt = timed_pass([&](VkCommandBuffer c) {
                            e.signals.record_brute_force(c, brute[bj].app.signal, (uint32_t)brute[bj].k, f, Sampling{sampling.seed, brute[bj].pattern},
                                                         scene, e.shadows);
                        });
                        brute_ms[bj].push_back(clock.ms(bt, empty));
                        for (size_t a = 0; a < run_apps.size(); ++a) signal_ms[run_apps[a].signal].push_back(clock.ms(app_t[a], empty));
                        for (size_t i = 0; i < stages.size(); ++i) rrc_ms[i].push_back(clock.ms(stage_t[i], empty));
                        if (probing) {
                            double alone = 0.0;
                            for (size_t i = 0; i + 1 < probe_t.size(); ++i) alone += clock.ms(probe_t[i], empty);
                            alone_sum_ms.push_back(alone);
                            together_ms.push_back(clock.ms(probe_t.back(), empty));
                        }
                        clock.compare(app_t, stage_t, empty);
                    }
                    if (read || hits)
                        e.submit(0, [&](VkCommandBuffer c, auto&&) {
                            std::vector<int> slots = {mask_slot};
                            if (hits && clip_slot >= 0) slots.push_back(clip_slot);
                            if (read) slots.insert(slots.end(), out_slots.begin(), out_slots.end());
                            rb.record(c, slots);
                        });
                    if (hits) {
                        std::vector<uint8_t> mask(rb.bytes(mask_slot));
                        std::memcpy(mask.data(), rb.data(mask_slot), mask.size());
                        result.hit_ratio.push_back(rrc_sample::hit_stats(mask).ratio());
                        if (clip_slot >= 0) {
                            const std::vector<float> clip = floats_of(rb, clip_slot);
                            age = next_age(age, mask, clip.data(), o.width, o.height, RRC_MAX_AGE_CAP);
                            if (checkpoint_of(f) < checkpoints.size()) cp_masks[f] = mask, cp_ages[f] = age;
                        }
                    }
                    if (!read) continue;
                    const size_t cp = checkpoint_of(f);
                    for (size_t i = 0; i < stages.size(); ++i) {
                        std::vector<float> img = floats_of(rb, out_slots[i]);
                        const uint32_t sig = run.configs[i].app.signal;
                        if (cp < checkpoints.size())
                            ensembles[i].add(cp, targets.at(sig)[cp], img.data(), stride_of(sig), previous[i].empty() ? nullptr : previous[i].data());
                        previous[i] = std::move(img);
                    }
                }
                work_done += (last + 1) * (2.0 + 0.02 * run.configs.size() * 10.0);
                if (progress)
                    *progress << "rrc k = " << run.k << (run.pattern ? " (rotated pattern)" : "") << ", " << run.configs.size()
                              << " configurations: seed " << seed + 1 << "/" << o.seeds << " done"
                              << eta(work_done, work_total, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
                              << std::endl;
            }
            if (o.bias_maps && ri == 0) {
                regions = make_regions(o, sigs, targets, target_frames, cp_masks, cp_ages);
                target_frames.clear();
            }
            for (size_t i = 0; i < stages.size(); ++i) {
                RrcRow row;
                row.config = run.configs[i];
                row.k = run.k;
                row.pattern = run.pattern;
                row.signal_ms = median(signal_ms[run.configs[i].app.signal]);  // replaced below by the brute force's at the same k
                std::vector<double>& pool = pooled_rrc_ms[channel_key(run.configs[i])];
                pool.insert(pool.end(), rrc_ms[i].begin(), rrc_ms[i].end());
                row.metrics = ensembles[i].metrics(targets.at(run.configs[i].app.signal));
                if (o.bias_maps) {
                    const uint32_t sig = run.configs[i].app.signal;
                    row.regions = decompose(ensembles[i], targets.at(sig), regions.at(sig));
                    row.has_regions = true;
                    write_row_maps(o, row_label(row), ensembles[i], targets.at(sig));
                }
                result.rrc.push_back(row);
            }
        }

        // Each application's share of rrc: its channel alone, less a third of what one context for all
        // three saves (docs/measurements/PERFORMANCE.md, "Error against run time"; the arithmetic: sweep_time.h).
        result.rrc_together_ms = median(together_ms);
        result.rrc_alone_sum_ms = median(alone_sum_ms);
        const double saving = sharing_saving_ms(alone_sum_ms, together_ms, apps_of(sigs).size());
        for (RrcRow& row : result.rrc) {
            row.rrc_alone_ms = median(pooled_rrc_ms[channel_key(row.config)]);
            row.rrc_ms = rrc_share_ms(row.rrc_alone_ms, saving);
        }

        // ---- Brute force: the per-frame estimator with k samples, on the frames that are scored.
        rrc_sample::Readback rb(gpu);
        std::vector<int> slots;
        for (const BruteConfig& b : brute) slots.push_back(rb.add(signal_image(e.signals.brute_force(), b.app.signal)));
        rb.allocate();
        std::vector<Ensemble> ensembles(brute.size(), Ensemble(checkpoints.size()));
        const auto brute_start = std::chrono::steady_clock::now();
        for (int seed = 0; seed < o.seeds; ++seed) {
            std::vector<std::vector<float>> previous(brute.size());
            for (int f : evaluated) {
                // Taps = the rotated pattern's base set (its brute force rotates it); the disk pattern ignores it.
                const FrameState state = e.begin_frame(f, kRotatedBaseTaps, kFirstSeed + (uint32_t)seed);
                e.submit(0, [&](VkCommandBuffer c, auto&&) {
                    e.record_geometry(c, state, sigs);
                    for (size_t j = 0; j < brute.size(); ++j) {
                        const Sampling sampling{kFirstSeed + (uint32_t)seed, brute[j].pattern};
                        e.signals.record_brute_force(c, brute[j].app.signal, (uint32_t)brute[j].k, f, sampling, scene, e.shadows);
                        rb.record(c, {slots[j]});
                        transfer_to_compute(c);
                    }
                });
                const size_t cp = checkpoint_of(f);
                for (size_t j = 0; j < brute.size(); ++j) {
                    std::vector<float> img = floats_of(rb, slots[j]);
                    const uint32_t sig = brute[j].app.signal;
                    if (cp < checkpoints.size())
                        ensembles[j].add(cp, targets.at(sig)[cp], img.data(), stride_of(sig), previous[j].empty() ? nullptr : previous[j].data());
                    previous[j] = std::move(img);
                }
            }
            if (progress)
                *progress << "brute force, " << brute.size() << " configurations: seed " << seed + 1 << "/" << o.seeds << " done ("
                          << (int)std::chrono::duration<double>(std::chrono::steady_clock::now() - brute_start).count() << " s)" << std::endl;
        }
        for (size_t j = 0; j < brute.size(); ++j) {
            BruteRow row;
            row.config = brute[j];
            row.signal_ms = median(brute_ms[j]);
            row.metrics = ensembles[j].metrics(targets.at(brute[j].app.signal));
            if (o.bias_maps) {
                row.regions = decompose(ensembles[j], targets.at(brute[j].app.signal), regions.at(brute[j].app.signal));
                row.has_regions = true;
                write_row_maps(o, row_label(row), ensembles[j], targets.at(brute[j].app.signal));
            }
            result.brute.push_back(row);
        }
        // The signal pass of an rrc row is the brute-force pass at the same k (the same estimator, the
        // same work), timed one configuration a frame across every run: both sides on one clock.  With
        // --pcf-base-in-signal a pcf residual row's pass also writes its base: that row keeps its own
        // pass's time, measured in its runs.
        for (RrcRow& row : result.rrc) {
            if (o.pcf_base_in_signal && row.config.app.signal == kSignalPcf && row.config.channel.residual) continue;
            for (const BruteRow& b : result.brute)
                if (b.config.app.signal == row.config.app.signal && b.config.k == row.k && b.config.pattern == row.pattern)
                    row.signal_ms = b.signal_ms;
        }
    }
    result.stamps_over_wall = median(clock.ratio);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    vkDeviceWaitIdle(gpu.device);
    result.validation_messages = gpu.message_count();
    return result;
}

}  // namespace rrc_sweep
