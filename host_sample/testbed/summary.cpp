#include "summary.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace rrc_sample {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Aggregate {
    double hit_mean = 0, hit_min = 1;
    VisibilityStats vis;  // summed over frames 2.. (the oracle, oracle.h)
    int hit_frames = 0;
    double render = 0, rrc = 0, post = 0, reference = 0, cpu = 0, signals = 0, brute = 0;
    // Per signal: mean RMSE and PSNR over checkpoints (raw, accumulated, shown, fallback).
    struct Sig {
        int n = 0;
        double rmse_raw = 0, rmse_acc = 0, psnr_raw = 0, psnr_acc = 0, rmse_shown = 0, rmse_fallback = 0, psnr_shown = 0;
        double rmse_brute = 0, psnr_brute = 0;
    };
    std::map<std::string, Sig> sig;
    std::vector<std::string> order;
};

Aggregate aggregate(const RunResult& run) {
    Aggregate a;
    std::vector<double> render, rrc, post, ref, cpu, signals, brute;
    for (const FrameRecord& f : run.frames) {
        if (f.index > 0) {  // frame 0 misses everywhere by definition
            a.hit_mean += f.hits.ratio();
            a.hit_min = std::min(a.hit_min, f.hits.ratio());
            a.vis += f.visibility;
            ++a.hit_frames;
        }
        render.push_back(f.timings.render());
        rrc.push_back(f.timings.rrc);
        post.push_back(f.timings.post);
        cpu.push_back(f.timings.cpu_frame);
        signals.push_back(f.timings.signals);
        if (f.checkpoint) ref.push_back(f.timings.reference), brute.push_back(f.timings.brute_force);
        for (const SignalErrors& e : f.errors) {
            if (!a.sig.count(e.signal)) a.order.push_back(e.signal);
            Aggregate::Sig& s = a.sig[e.signal];
            ++s.n;
            s.rmse_raw += e.raw.rmse;
            s.rmse_acc += e.accumulated.rmse;
            s.psnr_raw += e.raw.psnr;
            s.psnr_acc += e.accumulated.psnr;
            s.rmse_shown += e.shown.rmse;
            s.psnr_shown += e.shown.psnr;
            s.rmse_fallback += e.fallback.rmse;
            s.rmse_brute += e.brute_force.rmse;
            s.psnr_brute += e.brute_force.psnr;
        }
    }
    if (a.hit_frames)
        a.hit_mean /= a.hit_frames;
    else
        a.hit_min = 0;
    a.render = median(render);
    a.rrc = median(rrc);
    a.post = median(post);
    a.reference = median(ref);
    a.cpu = median(cpu);
    a.signals = median(signals);
    a.brute = median(brute);
    for (auto& [name, s] : a.sig) {
        const double n = std::max(s.n, 1);
        s.rmse_raw /= n, s.rmse_acc /= n, s.psnr_raw /= n, s.psnr_acc /= n, s.rmse_shown /= n, s.psnr_shown /= n, s.rmse_fallback /= n;
        s.rmse_brute /= n, s.psnr_brute /= n;
    }
    return a;
}

void open_or_throw(std::ofstream& f, const std::string& path) {
    f.open(path);
    if (!f) throw std::runtime_error("cannot write " + path);
}

/** What the frame's "signals" interval holds (renderer.cpp): the signal passes at k and, with the soft
 *  residual, its stable PCSS estimate (rrc's base), or else, when rrc's soft fill has a prior, the PCSS
 *  fallback, recorded before the interval closes; soft's one shadow map a frame is under "shadows". */
std::string signals_label(const RunResult& run) {
    const bool soft = (run.signals & kSignalSoft) != 0;
    if (soft && run.options.channels.soft.residual) return "the signal passes + the soft residual's stable PCSS estimate";
    const bool pcss = soft && run.options.channels.soft.fill_prior > 0.0f;
    return std::string("the signal passes") + (pcss ? " + the soft fill's PCSS fallback" : "");
}

}  // namespace

std::string progress_line(const FrameRecord& f, int frames) {
    std::ostringstream os;
    char b[256];
    std::snprintf(b, sizeof b, "frame %3d/%d  hit %5.1f%%  recall %5.1f%%  false hits %4llu  render %7.2f ms  rrc %6.2f ms  post %6.2f ms",
                  f.index + 1, frames, 100.0 * f.hits.ratio(), 100.0 * f.visibility.recall(), (unsigned long long)f.visibility.false_hits,
                  f.timings.render(), f.timings.rrc, f.timings.post);
    os << b;
    if (f.checkpoint) {
        std::snprintf(b, sizeof b, "  | reference %.0f ms, RMSE raw -> accumulated:", f.timings.reference);
        os << b;
        for (const SignalErrors& e : f.errors) {
            std::snprintf(b, sizeof b, " %s %.4f -> %.4f", e.signal.c_str(), e.raw.rmse, e.accumulated.rmse);
            os << b;
        }
    }
    os << "\n";
    return os.str();
}

void print_summary(const RunResult& run, std::ostream& os) {
    const Aggregate a = aggregate(run);
    char b[512];
    os << "\nsummary (" << run.frames.size() << " frames, " << run.options.width << "x" << run.options.height << ", " << run.device
       << ")\n";
    std::snprintf(b, sizeof b,
                  "  hit ratio, frames 2..%zu: mean %.1f%%, min %.1f%%; depth test: %s\n"
                  "  against true visibility: recall %.2f%% (%llu of %llu visible pixels off silhouettes), false hits %llu "
                  "(%llu straddling), straddling %llu, excluded %llu\n",
                  run.frames.size(), 100.0 * a.hit_mean, 100.0 * a.hit_min, depth_test_description(run.options).c_str(),
                  100.0 * a.vis.recall(), (unsigned long long)a.vis.clean_hits, (unsigned long long)a.vis.clean_visible,
                  (unsigned long long)a.vis.false_hits, (unsigned long long)a.vis.false_hits_straddling,
                  (unsigned long long)a.vis.straddling, (unsigned long long)a.vis.excluded);
    os << b;
    std::snprintf(
        b, sizeof b,
        "  GPU ms per frame (median): render %.2f (shadows + g-buffer + signals), rrc %.2f, post %.2f; reference %.0f on checkpoints\n"
        "  %s: %.2f ms with k = %d samples; brute force at 4k%s: %.2f ms (timestamps in one command buffer, no barrier\n"
        "  between passes: on a CPU device such as lavapipe not the passes' own cost; rrc-sweep times each pass alone)\n",
        a.render, a.rrc, a.post, a.reference, signals_label(run).c_str(), a.signals, run.options.taps,
        (run.signals & kSignalSoft) ? " (soft: its 4 shadow maps included)" : "", a.brute);
    os << b;
    if (!a.order.empty()) {
        os << "  error against the reference (mean over checkpoints; PSNR with peak 1):\n";
        std::snprintf(b, sizeof b, "    %-6s %10s %10s %10s %10s %10s %10s %9s\n", "signal", "RMSE raw", "RMSE 4x", "RMSE acc", "PSNR raw",
                      "PSNR 4x", "PSNR acc", "acc-raw");
        os << b;
        for (const std::string& name : a.order) {
            const Aggregate::Sig& s = a.sig.at(name);
            std::snprintf(b, sizeof b, "    %-6s %10.4f %10.4f %10.4f %7.2f dB %7.2f dB %7.2f dB %+6.2f dB\n", name.c_str(), s.rmse_raw,
                          s.rmse_brute, s.rmse_acc, s.psnr_raw, s.psnr_brute, s.psnr_acc, s.psnr_acc - s.psnr_raw);
            os << b;
            if (name == "soft") {
                const bool fill = run.options.channels.soft.fill_age != 0;  // then rrc's output (acc) is what is displayed
                std::snprintf(b, sizeof b, "    %-6s %10s %10s %10.4f %10s %10s %7.2f dB   (%s; PCSS alone %.4f)\n",
                              fill ? "prior" : "shown", "", "", s.rmse_shown, "", "", s.psnr_shown,
                              fill ? "the --soft-prior blend; displayed: acc, rrc's fill" : "displayed: accumulated + PCSS fallback",
                              s.rmse_fallback);
                os << b;
            }
        }
        os << "    (raw: one frame's k samples; 4x: one frame at 4k samples, 4 shadow maps for soft; acc: rrc's output)\n";
    }
    if (run.options.validation)
        os << "  validation messages: " << run.validation_messages << (run.validation_messages ? " (see stderr)" : "") << "\n";
    if (run.options.write_images) os << "  images: " << run.options.out << "/{frames,coherence,age,exr}/\n";
    os << "  summary: " << run.options.out << "/summary.md, summary.csv, errors.csv\n";
}

void write_summary_files(const RunResult& run, const std::string& out_dir) {
    namespace fs = std::filesystem;
    fs::create_directories(out_dir);
    const Options& o = run.options;
    const Aggregate a = aggregate(run);
    {
        std::ofstream f;
        open_or_throw(f, (fs::path(out_dir) / "summary.csv").string());
        f << "frame,checkpoint,hit_ratio,hits,misses,background,recall,visible,straddling,clean_visible,clean_hits,false_hits,"
             "false_hits_straddling,excluded,excluded_hits,ms_shadows,ms_gbuffer,ms_signals,ms_render,ms_rrc,ms_post,ms_reference,"
             "ms_brute_force,ms_cpu_frame\n";
        for (const FrameRecord& r : run.frames) {
            const FrameTimings& t = r.timings;
            f << r.index << "," << (r.checkpoint ? 1 : 0) << "," << fmt("%.6f", r.hits.ratio()) << "," << r.hits.hits << ","
              << r.hits.misses << "," << r.hits.background << ",";
            const VisibilityStats& v = r.visibility;
            f << fmt("%.6f", v.recall()) << "," << v.visible << "," << v.straddling << "," << v.clean_visible << "," << v.clean_hits << ","
              << v.false_hits << "," << v.false_hits_straddling << "," << v.excluded << "," << v.excluded_hits << ","
              << fmt("%.4f", t.shadows) << "," << fmt("%.4f", t.gbuffer) << "," << fmt("%.4f", t.signals) << "," << fmt("%.4f", t.render())
              << "," << fmt("%.4f", t.rrc) << "," << fmt("%.4f", t.post) << "," << fmt("%.4f", t.reference) << ","
              << fmt("%.4f", t.brute_force) << "," << fmt("%.4f", t.cpu_frame) << "\n";
        }
    }
    {
        std::ofstream f;
        open_or_throw(f, (fs::path(out_dir) / "errors.csv").string());
        f << "frame,signal,pixels,rmse_raw,rmse_brute_force_4x,rmse_accumulated,psnr_raw,psnr_brute_force_4x,psnr_accumulated,rmse_raw_"
             "hits,"
             "rmse_accumulated_hits,rmse_shown,psnr_shown,rmse_pcss,rmse_accumulated_vs_weighted,rmse_weighted_vs_target\n";
        for (const FrameRecord& r : run.frames)
            for (const SignalErrors& e : r.errors) {
                f << r.index << "," << e.signal << "," << e.raw.pixels << "," << fmt("%.6f", e.raw.rmse) << ","
                  << fmt("%.6f", e.brute_force.rmse) << "," << fmt("%.6f", e.accumulated.rmse) << "," << fmt("%.3f", e.raw.psnr) << ","
                  << fmt("%.3f", e.brute_force.psnr) << "," << fmt("%.3f", e.accumulated.psnr) << "," << fmt("%.6f", e.raw_hits.rmse) << ","
                  << fmt("%.6f", e.accumulated_hits.rmse) << ",";
                // shown: soft's --soft-prior display; pcf's remapped display (--pcf-smoothstep/--pcf-threshold)
                const bool pcf = e.signal == "pcf";
                const ErrorStats& shown = pcf ? r.finish.pcf_display : e.shown;
                if (shown.pixels)
                    f << fmt("%.6f", shown.rmse) << "," << fmt("%.3f", shown.psnr) << ",";
                else
                    f << ",,";
                if (e.signal == "soft") f << fmt("%.6f", e.fallback.rmse);
                f << ",";
                if (pcf && r.finish.weighted_vs_target.pixels)
                    f << fmt("%.6f", r.finish.pcf_vs_weighted.rmse) << "," << fmt("%.6f", r.finish.weighted_vs_target.rmse);
                else
                    f << ",";
                f << "\n";
            }
    }
    std::ofstream f;
    open_or_throw(f, (fs::path(out_dir) / "summary.md").string());
    f << "# rrc-sample run\n\n";
    f << "| setting | value |\n|---|---|\n";
    f << "| scene | " << o.scene << " |\n| size | " << o.width << "x" << o.height << " |\n| frames | " << o.frames << " (" << o.fps
      << " per second of scene time) |\n";
    f << "| signals | " << signal_list(run.signals) << " |\n| reprojection | " << reprojection_name(o.reprojection) << " |\n";
    f << "| taps k (pcf taps, env sub-pixel samples) | " << o.taps << " |\n";
    f << "| reference | " << o.reference_samples << " samples per pixel on frames " << o.reference_every - 1 << ", "
      << 2 * o.reference_every - 1 << ", ... and the last |\n";
    f << "| depth test | " << depth_test_description(o) << " |\n";
    f << "| object ids | " << (o.object_id ? "given (use_object_id = 1)" : "none (--no-object-id)") << " |\n";
    f << "| device | " << run.device << " |\n| rrc device memory | " << run.rrc_memory_bytes << " bytes |\n";
    f << "| wall time of the frame loop (files included) | " << fmt("%.1f", run.wall_seconds) << " s; the visibility oracle's ray casts "
      << fmt("%.1f", run.oracle_seconds) << " s of it, overlapping the files |\n";
    if (o.validation) f << "| validation messages | " << run.validation_messages << " |\n";
    f << "\nrrc channels:\n\n";
    for (const std::string& c : run.channels) f << "- " << c << "\n";
    f << "\n## Results\n\n";
    f << "- hit ratio (frames 2.." << run.frames.size() << "): mean " << fmt("%.1f", 100.0 * a.hit_mean) << "%, min "
      << fmt("%.1f", 100.0 * a.hit_min) << "%\n";
    const VisibilityStats& v = a.vis;
    f << "- against true visibility (the ray-cast oracle, README.md), frames 2.." << run.frames.size() << ": **recall "
      << fmt("%.2f", 100.0 * v.recall()) << "%** (" << v.clean_hits << " hits of " << v.clean_visible
      << " visible pixels that straddle no silhouette), **false hits " << v.false_hits << "** (hits whose point was not visible; "
      << v.false_hits_straddling << " of them straddle a silhouette); of " << v.surface << " surface pixels " << v.visible
      << " were visible, " << v.straddling << " straddle a silhouette (counted apart from recall), " << v.excluded
      << " excluded (ray and G-buffer disagree on background, or the point left the image by under fp32 rounding; " << v.excluded_hits
      << " of them hits)\n";
    f << "- visible pixels off silhouettes that missed, by surface:";
    for (uint32_t m = 1; m < kMaterialCount; ++m) f << (m > 1 ? "," : "") << " " << material_name(m) << " " << v.missed_by_material[m];
    f << "\n";
    f << "- GPU time per frame (median): rendering " << fmt("%.2f", a.render) << " ms (shadow maps + G-buffer + signals), rrc "
      << fmt("%.2f", a.rrc) << " ms, post " << fmt("%.2f", a.post) << " ms (age, PCSS fallback, compose); reference "
      << fmt("%.0f", a.reference) << " ms per checkpoint\n";
    f << "- " << signals_label(run) << ": " << fmt("%.2f", a.signals) << " ms with k = " << o.taps << " samples; brute force at 4k"
      << ((run.signals & kSignalSoft) ? " (soft: its 4 shadow maps included)" : "") << ": " << fmt("%.2f", a.brute)
      << " ms (checkpoints). GPU timestamps in one command buffer, no barrier between passes: on a CPU device such as "
         "lavapipe they are not the passes' own cost (docs/measurements/BIAS.md, \"What the sample's signal-pass time measures\"); "
         "rrc-sweep times each pass in its own submission\n";
    if (!a.order.empty()) {
        f << "\nError against the brute-force reference, mean over checkpoint frames (PSNR with peak 1; pcf and soft over every "
             "surface pixel, env over the mirror sphere's pixels, RGB):\n\n";
        f << "| signal | RMSE raw (1 frame, k) | RMSE brute force (1 frame, 4k) | RMSE accumulated | PSNR raw | PSNR 4k | PSNR accumulated "
             "| "
             "accumulated - raw |\n|---|---|---|---|---|---|---|---|\n";
        for (const std::string& name : a.order) {
            const Aggregate::Sig& s = a.sig.at(name);
            f << "| " << name << " | " << fmt("%.4f", s.rmse_raw) << " | " << fmt("%.4f", s.rmse_brute) << " | " << fmt("%.4f", s.rmse_acc)
              << " | " << fmt("%.2f", s.psnr_raw) << " dB | " << fmt("%.2f", s.psnr_brute) << " dB | " << fmt("%.2f", s.psnr_acc)
              << " dB | " << fmt("%+.2f", s.psnr_acc - s.psnr_raw) << " dB |\n";
            if (name == "soft")
                f << (o.channels.soft.fill_age ? "| soft, the --soft-prior blend (not displayed: --soft-fill shows rrc's output) | | | "
                                               : "| soft, displayed (accumulated + PCSS fallback) | | | ")
                  << fmt("%.4f", s.rmse_shown) << " | | | " << fmt("%.2f", s.psnr_shown) << " dB | |\n| soft, PCSS alone | | | "
                  << fmt("%.4f", s.rmse_fallback) << " | | | | |\n";
            if (name == "pcf" && o.channels.pcf.residual)
                f << "| pcf, the residual's base alone (" << o.pcf_base << " bilinear compares) | | | " << fmt("%.4f", s.rmse_fallback)
                  << " | | | | |\n";
            if (name == "env" && o.channels.env.residual)
                f << "| env, the residual's base alone (--env-residual " << env_base_name(o.env_base) << ") | | | " << fmt("%.4f", s.rmse_fallback)
                  << " | | | | |\n";
        }
        f << "\nFor soft shadows \"k\" is one shadow map a frame and \"4k\" four shadow maps from random points of the light.\n";
        f << "\nPer checkpoint:\n\n| frame | signal | pixels | RMSE raw | RMSE accumulated | RMSE raw, hits | RMSE accumulated, hits | "
             "PSNR raw | "
             "PSNR accumulated |\n|---|---|---|---|---|---|---|---|---|\n";
        for (const FrameRecord& r : run.frames)
            for (const SignalErrors& e : r.errors)
                f << "| " << r.index << " | " << e.signal << " | " << e.raw.pixels << " | " << fmt("%.4f", e.raw.rmse) << " | "
                  << fmt("%.4f", e.accumulated.rmse) << " | " << fmt("%.4f", e.raw_hits.rmse) << " | "
                  << fmt("%.4f", e.accumulated_hits.rmse) << " | " << fmt("%.2f", e.raw.psnr) << " | " << fmt("%.2f", e.accumulated.psnr)
                  << " |\n";
    }
    if (!run.finish_table.empty())
        f << "\nYoung soft-shadow pixels (finish.h; young.csv has the ages):\n\n```\n" << run.finish_table << "```\n";
    f << "\nLimits of the theory: the (1 - lambda)/(1 + lambda) variance law holds for independent samples at a static pixel; "
         "bilinear resampling of the history under motion lowers the variance further but blurs, so the accumulated signals "
         "converge to a slightly blurred version of the reference; a stratified pattern such as a Poisson disk makes "
         "\"4 taps ~ 16\" an approximation.  Disoccluded pixels restart from one frame's samples.\n";
    f << "\n## Per frame\n\n| frame | hit % | recall % | false hits | straddling | excluded | render ms | rrc ms | post ms | reference ms "
         "|\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const FrameRecord& r : run.frames)
        f << "| " << r.index << " | " << fmt("%.1f", 100.0 * r.hits.ratio()) << " | " << fmt("%.2f", 100.0 * r.visibility.recall()) << " | "
          << r.visibility.false_hits << " | " << r.visibility.straddling << " | " << r.visibility.excluded << " | "
          << fmt("%.2f", r.timings.render()) << " | " << fmt("%.2f", r.timings.rrc) << " | " << fmt("%.2f", r.timings.post) << " | "
          << (r.checkpoint ? fmt("%.0f", r.timings.reference) : std::string("")) << " |\n";
}

}  // namespace rrc_sample
