#include "clean_study.h"

#include "post.h"
#include "sweep_engine.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

namespace rrc_sweep {
namespace {

using rrc_host::full_barrier;

struct CleanConfig {
    App app;
    std::string preset;
    rrc_sample::ChannelSettings channel;
};

std::vector<CleanConfig> clean_configs(uint32_t sigs) {
    const rrc_sample::ChannelPresets with(true), without(false);
    std::vector<CleanConfig> c;
    for (const App& app : apps_of(sigs)) {
        auto of = [&](const rrc_sample::ChannelPresets& p) { return app.signal == kSignalPcf ? p.pcf : app.signal == kSignalEnv ? p.env : p.soft; };
        c.push_back({app, "preset", of(with)});
        c.push_back({app, "preset without its base", of(without)});
    }
    return c;
}

bool scored(uint32_t signal, uint8_t m) { return signal == kSignalEnv ? m == rrc_sample::kMatSphere : m != rrc_sample::kMatBackground; }

std::vector<uint8_t> bytes_of(const rrc_sample::Readback& r, int slot) {
    std::vector<uint8_t> v(r.bytes(slot));
    std::memcpy(v.data(), r.data(slot), v.size());
    return v;
}

using rrc_host::clean_number;

}  // namespace

CleanResult run_clean_study(const SweepOptions& o, std::ostream* progress) {
    if (o.quiet) progress = nullptr;
    const auto start = std::chrono::steady_clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    rrc_sample::Scene scene = rrc_sample::Scene::make(o.scene);
    if (o.motion != "all") scene.camera_speed = 0.0f;
    if (o.motion == "still")
        for (auto& obj : scene.objects) obj.moves = false;
    scene.light_speed = o.light_speed;
    const uint32_t sigs = o.signals ? (o.signals & scene.signals) : scene.signals;
    if (!sigs) throw std::runtime_error("scene " + scene.name + " uses none of the signals asked for");
    Gpu gpu(rrc_sample::GpuOptions{o.validation, o.device});
    CleanResult r;
    r.device = gpu.device_name();
    const std::vector<CleanConfig> configs = clean_configs(sigs);
    const std::vector<int> checkpoints = o.checkpoints();
    if (progress)
        *progress << "rrc-sweep --study clean: scene " << scene.name << ", " << o.width << "x" << o.height << ", motion " << o.motion
                  << ", the targets at " << o.reference_samples << " samples as input, " << configs.size() << " rows, frames 0.."
                  << o.frames - 1 << ", scored " << checkpoints.front() << ".." << checkpoints.back() << " every " << o.checkpoint_every
                  << "\ndevice: " << r.device << (o.validation ? " (validation layer on)" : "") << std::endl;

    rrc_sample::RenderSettings rs;
    rs.width = o.width;
    rs.height = o.height;
    Engine e(gpu, scene, rs);
    std::vector<std::unique_ptr<rrc_sample::RrcStage>> stages;
    std::vector<std::unique_ptr<rrc_sample::PostPasses>> pcss;
    bool env_residual = false;
    for (const CleanConfig& c : configs) {
        rrc_sample::RrcSettings s = e.rrc_settings(c.app.signal, c.channel);
        s.ages = true;  // the regions need each channel's age
        stages.emplace_back(new rrc_sample::RrcStage(gpu, s));
        // The soft preset's fill prior and residual base: rrc-sample's PCSS estimate (post.h), as the sweep's soft preset rows.
        const bool soft_fallback = c.app.signal == kSignalSoft && (c.channel.fill_prior > 0.0f || c.channel.residual);
        pcss.emplace_back(soft_fallback ? new rrc_sample::PostPasses(gpu, e.gpu_scene, e.gbuffer.images(), e.maps, stages.back()->mask(),
                                                                      stages.back()->age(kSignalSoft), stages.back()->accumulated(),
                                                                      e.signals.raw(), e.signals.reference(), o.width, o.height, true)
                                        : nullptr);
        env_residual |= c.app.signal == kSignalEnv && c.channel.residual;
    }
    rrc_sample::Readback rb(gpu);
    std::vector<int> out_slots, mask_slots, age_slots;
    for (size_t i = 0; i < stages.size(); ++i) {
        out_slots.push_back(rb.add(signal_image(stages[i]->accumulated(), configs[i].app.signal)));
        mask_slots.push_back(rb.add(stages[i]->mask()));
        age_slots.push_back(rb.add(stages[i]->age(configs[i].app.signal)));
    }
    rb.allocate();
    for (const CleanConfig& c : configs) r.rows.push_back({c.app, c.preset, c.channel, {}});

    for (int f = 0; f < o.frames; ++f) {
        // The clean input: the frame's target (its G-buffer and sun map with it), left in the reference images.
        const FrameTarget clean = frame_target(e, f, sigs, (uint32_t)o.reference_samples, -1, false);
        const FrameState state = e.begin_frame(f, 1, kFirstSeed);
        const bool read = std::find(checkpoints.begin(), checkpoints.end(), f) != checkpoints.end();
        e.submit(0, [&](VkCommandBuffer c, auto&&) {
            // The presets' bases, as rrc-sample renders them: env's filtered reflections (written by the
            // per-frame env pass beside its noisy signal, which nothing reads here) and pcf's bilinear compares.
            if (env_residual) e.signals.record(c, kSignalEnv, state, Sampling{kFirstSeed, 0, false, rrc_sample::kSampleEnvBase});
            full_barrier(c);
            for (size_t i = 0; i < stages.size(); ++i) {
                const rrc_sample::Image *soft_fallback = nullptr, *pcf_base = nullptr, *env_base = nullptr;
                if (pcss[i]) {
                    e.shadows.record(c, e.maps.lamp_centre, state.uniforms.lamp_centre_vp);
                    soft_fallback = pcss[i]->record_soft_fallback(c, 0, configs[i].channel);
                }
                if (configs[i].channel.residual && configs[i].app.signal == kSignalPcf)
                    pcf_base = e.signals.record_pcf_base(c, rrc_sample::kSamplePcfBaseTaps);
                if (configs[i].channel.residual && configs[i].app.signal == kSignalEnv) env_base = &e.signals.env_base();
                stages[i]->record(c, e.gbuffer.images(), e.signals.reference(), state, (uint64_t)f, f == 0, nullptr, soft_fallback, env_base,
                                  pcf_base);
            }
            if (read) {
                std::vector<int> slots = out_slots;
                slots.insert(slots.end(), mask_slots.begin(), mask_slots.end());
                slots.insert(slots.end(), age_slots.begin(), age_slots.end());
                rb.record(c, slots);
            }
        });
        if (read) {
            ++r.scored_frames;
            std::vector<uint32_t> object_id(clean.material.size());
            for (size_t p = 0; p < object_id.size(); ++p) object_id[p] = (uint32_t)clean.position[p * 4 + 3];  // object + 1, 0 background
            for (size_t i = 0; i < stages.size(); ++i) {
                const uint32_t sig = configs[i].app.signal;
                const std::vector<uint8_t> mask = bytes_of(rb, mask_slots[i]);
                std::vector<uint16_t> age(mask.size());
                std::memcpy(age.data(), rb.data(age_slots[i]), age.size() * sizeof(uint16_t));
                rrc_host::CleanFrame cf;
                cf.width = o.width, cf.height = o.height;
                cf.mask = mask.data(), cf.age = age.data();
                cf.inverse_depth = clean.depth.data();  // reversed z: proportional to 1 / view depth
                cf.object_id = object_id.data();
                cf.fill_age = configs[i].channel.fill_age;
                std::vector<uint8_t> keep(mask.size());
                for (size_t p = 0; p < keep.size(); ++p) keep[p] = scored(sig, clean.material[p]);
                const std::vector<float> out = floats_of(rb, out_slots[i]);
                rrc_host::add_clean_errors(r.rows[i].sums, rrc_host::clean_regions(cf), clean.of(sig).data(), out.data(), stride_of(sig),
                                           sig == kSignalEnv ? 3 : 1, keep.data());
            }
        }
        if (progress && (f + 1) % 8 == 0)
            *progress << "frame " << f + 1 << "/" << o.frames << " (" << (int)seconds() << " s)" << std::endl;
    }
    r.seconds = seconds();
    vkDeviceWaitIdle(gpu.device);
    r.validation_messages = gpu.message_count();
    return r;
}

void write_clean_files(const SweepOptions& o, const CleanResult& r, const std::string& command_line) {
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);
    std::ofstream csv(dir / "clean.csv");
    csv << "app,preset," << rrc_host::kCleanCsvColumns << "\n";
    for (const CleanRow& row : r.rows) csv << rrc_host::clean_csv_rows(std::string(row.app.name) + "," + row.preset, row.sums);
    std::ofstream md(dir / "clean.md");
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    md << "# What rrc adds to a clean input\n\n"
       << "- command: `" << command_line << "`\n"
       << "- date: " << date << "; device: " << r.device << "; " << (int)r.seconds << " s\n"
       << "- scene " << o.scene << ", " << o.width << "x" << o.height << ", motion " << o.motion << ", frames 0.." << o.frames - 1
       << " from a reset, scored at " << r.scored_frames << " frames (" << o.checkpoints().front() << ".." << o.checkpoints().back()
       << " every " << o.checkpoint_every << ")\n"
       << "- input: each application's target at " << o.reference_samples
       << " samples (README.md, \"Clean input\"); output: rrc-sample's preset; error: output against that frame's input, over the "
          "pixels the application scores\n"
       << "- each region cell: RMSE (share of the squared error / share of the pixels)\n\n"
       << "| app | row | all |";
    for (int g = 0; g < rrc_host::kCleanRegionCount; ++g) md << " " << rrc_host::clean_region_name(g) << " |";
    md << "\n|---|---|---|";
    for (int g = 0; g < rrc_host::kCleanRegionCount; ++g) md << "---|";
    md << "\n";
    for (const CleanRow& row : r.rows) {
        const double sse = row.sums.total_sse(), px = (double)row.sums.total_pixels();
        md << "| " << row.app.name << " | " << row.preset << " | " << clean_number(row.sums.rmse(rrc_host::kCleanRegionCount), "%.4f") << " |";
        for (int g = 0; g < rrc_host::kCleanRegionCount; ++g) {
            if (!row.sums.pixels[g]) {
                md << " - |";
                continue;
            }
            md << " " << clean_number(row.sums.rmse(g), "%.4f") << " (" << clean_number(sse > 0 ? 100.0 * row.sums.sse[g] / sse : 0.0, "%.0f") << "% / "
               << clean_number(100.0 * (double)row.sums.pixels[g] / px, "%.0f") << "%) |";
        }
        md << "\n";
    }
    md << "\n| app | row | blend | lambda | filter | fill_age | residual |\n|---|---|---|---|---|---|---|\n";
    for (const CleanRow& row : r.rows)
        md << "| " << row.app.name << " | " << row.preset << " | " << blend_label(row.channel.blend) << " | " << clean_number(row.channel.lambda, "%.2f")
           << " | " << filter_label(row.channel) << " | " << row.channel.fill_age << " | " << row.channel.residual << " |\n";
}

}  // namespace rrc_sweep
