#include "cache_report.h"

#include "cache_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace rrc_cache {
namespace {

constexpr int kWarmFrames = 2;

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

Figures measure(const RunResult& r) {
    Figures f;
    f.name = r.config.name;
    f.config = r.config;
    f.list_matched = r.list_matched;
    std::vector<double> raster, shade, rrc, total, full_shade, full_total;
    int count = 0;
    for (size_t t = kWarmFrames; t < r.frames.size(); ++t) {
        const FrameRecord& fr = r.frames[t];
        raster.push_back(fr.raster_ms);
        shade.push_back(fr.shade_ms);
        rrc.push_back(fr.classify_ms + fr.resolve_ms);
        total.push_back(fr.total_ms());
        full_shade.push_back(fr.full_shade_ms);
        full_total.push_back(fr.full_total_ms());
        f.shaded_fraction += fr.shaded_fraction;
        f.rmse += fr.rmse;
        f.hit_fraction += fr.pixels ? (double)fr.hits / fr.pixels : 0.0;
        f.refreshed_fraction += fr.pixels ? (double)fr.refreshed / fr.pixels : 0.0;
        ++count;
    }
    if (count) f.shaded_fraction /= count, f.rmse /= count, f.hit_fraction /= count, f.refreshed_fraction /= count;
    f.raster_ms = median(raster), f.shade_ms = median(shade), f.rrc_ms = median(rrc), f.total_ms = median(total);
    f.full_shade_ms = median(full_shade), f.full_ms = median(full_total);
    return f;
}

}  // namespace

std::vector<Figures> figures(const std::vector<RunResult>& runs) {
    std::vector<Figures> out;
    for (const RunResult& r : runs) out.push_back(measure(r));
    // The baseline of a run: the one shading every pixel with the same eyes, sub-frames and shader.
    auto baseline = [&](const CacheConfig& c) -> const Figures* {
        for (size_t j = 0; j < runs.size(); ++j)
            if (!runs[j].config.cache && runs[j].config.stereo == c.stereo && runs[j].config.subframes == c.subframes &&
                runs[j].config.octaves == c.octaves) return &out[j];
        return nullptr;
    };
    for (size_t i = 0; i < runs.size(); ++i) {
        Figures& f = out[i];
        apply_time_model(f, runs[i].config.cache);  // against the paired baseline: the same frames, timed beside them
        const Figures* b = baseline(runs[i].config);
        if (b) f.speedup_separate = speedup_against(b->total_ms, f.total_ms);
    }
    return out;
}

double amdahl_bound(double p, double f, double c) {
    const double rest = (1.0 - p) + p * f + c;
    return rest > 0.0 ? 1.0 / rest : std::numeric_limits<double>::infinity();
}

void apply_time_model(Figures& f, bool cache) {
    f.p = f.c = f.bound = f.speedup = f.of_bound = 0.0;
    if (!(f.full_ms > 0.0 && f.total_ms > 0.0)) return;
    f.p = f.full_shade_ms / f.full_ms;
    f.c = cache ? f.rrc_ms / f.full_ms : 0.0;
    f.bound = amdahl_bound(f.p, f.shaded_fraction, f.c);
    f.speedup = f.full_ms / f.total_ms;
    f.of_bound = std::isfinite(f.bound) && f.bound > 0.0 ? f.speedup / f.bound : 0.0;
}

double speedup_against(double baseline_ms, double frame_ms) { return baseline_ms > 0.0 && frame_ms > 0.0 ? baseline_ms / frame_ms : 0.0; }

void write_csv(const std::string& path, const std::vector<Figures>& fs) {
    std::ofstream o(path);
    if (!o) throw std::runtime_error("rrc-cache: cannot write " + path);
    o << "name,raster_ms,shade_ms,rrc_ms,total_ms,full_shade_ms,full_ms,shaded_fraction,rmse,hit_fraction,refreshed_fraction,p,c,"
         "amdahl_bound,speedup,of_bound,speedup_separate,list_matched,octaves\n";
    for (const Figures& f : fs) {
        char line[512];
        std::snprintf(line, sizeof line, "%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.5f,%.6f,%.5f,%.5f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%u\n",
                      f.name.c_str(), f.raster_ms, f.shade_ms, f.rrc_ms, f.total_ms, f.full_shade_ms, f.full_ms, f.shaded_fraction, f.rmse,
                      f.hit_fraction, f.refreshed_fraction, f.p, f.c, f.bound, f.speedup, f.of_bound, f.speedup_separate,
                      f.list_matched ? 1 : 0, f.config.octaves);
        o << line;
    }
}

void write_cost_csv(const std::string& path, const std::vector<Figures>& fs) {
    std::ofstream o(path);
    if (!o) throw std::runtime_error("rrc-cache: cannot write " + path);
    o << "octaves,run,full_shade_ms,full_ms,speedup,amdahl_bound,of_bound,c,shaded_fraction,rmse\n";
    for (const CostPoint& p : cost_curve(fs)) {
        char line[320];  // full precision: plot_cost.py interpolates the break-even from these
        std::snprintf(line, sizeof line, "%u,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", p.octaves, p.run.c_str(), p.shade_ms,
                      p.full_ms, p.speedup, p.bound, p.of_bound, p.c, p.shaded_fraction, p.rmse);
        o << line;
    }
}

// Speed-up against shader cost: TILED n = 4 at each octave count, the break-even shader, the paper beside it.
static void write_cost_section(std::ofstream& o, const std::vector<Figures>& fs) {
    const std::vector<CostPoint> curve = cost_curve(fs);
    o << "\n## Speed-up against shader cost (TILED n = 4)\n\n"
         "Shader cost: the full shading pass a frame (the paired baseline's, the same frames). The paper's speed-up at n = 4: "
      << kPaperSpeedupLow << "-" << kPaperSpeedupHigh << "x (Nehab et al. 2007).\n\n"
      << "| octaves | run | full shading ms | full frame ms | speed-up | Amdahl bound | speed-up / bound | c | shaded f | RMSE | "
         "the paper's speed-up |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const CostPoint& p : curve) {
        char line[384];
        std::snprintf(line, sizeof line, "| %u | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | %.4f | %.1f-%.1f |\n", p.octaves,
                      p.run.c_str(), p.shade_ms, p.full_ms, p.speedup, p.bound, p.of_bound, p.c, p.shaded_fraction, p.rmse,
                      kPaperSpeedupLow, kPaperSpeedupHigh);
        o << line;
    }
    const BreakEven b = break_even(curve);
    char line[256];
    switch (b.kind) {
        case BreakEven::kUnmeasured: std::snprintf(line, sizeof line, "no TILED n = 4 run"); break;
        case BreakEven::kAtOrBelow:
            std::snprintf(line, sizeof line, "at or below %.0f octaves (%.2f ms), the cheapest measured", b.octaves, b.shade_ms);
            break;
        case BreakEven::kBetween:
            std::snprintf(line, sizeof line, "%.1f octaves, %.2f ms of full shading a frame (linear between the measured points)",
                          b.octaves, b.shade_ms);
            break;
        case BreakEven::kNotReached: std::snprintf(line, sizeof line, "not reached by the dearest shader measured"); break;
    }
    o << "\nBreak-even (speed-up = 1): " << line << ".\n";
}

void write_report(const std::string& path, const std::vector<Figures>& fs, const std::string& command, const std::string& device,
                  const Settings& s) {
    std::ofstream o(path);
    if (!o) throw std::runtime_error("rrc-cache: cannot write " + path);
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    o << "# rrc-cache: the shading cache on the temple scene\n\n"
      << "Command: `" << command << "`  \nDevice: " << device << ", " << date << "; " << s.width << "x" << s.height << ", " << s.frames
      << " frames (medians and means over frames " << kWarmFrames << ".." << s.frames - 1 << ").\n\n"
      << "Speed-up = full frame / this frame, where the full frame is the same frame's G-buffer shaded everywhere (the error "
         "target), timed in a submission of its own right after each cached frame (paired: the same load on a shared machine); "
         "bound = 1/((1 - p) + p f + c) with p the shading share of that full frame, f the shaded fraction, c classify + resolve "
         "over the full frame. `vs full run`: against the separate run that shades every pixel (same eyes and sub-frames), "
         "minutes apart. RMSE (RGB) against shading every pixel of the same frame. Octaves: of the shader (its cost).\n\n"
      << "| run | octaves | raster ms | shading ms | classify+resolve ms | frame ms | full frame ms | shaded f | hits | refreshed | RMSE | "
         "p | c = classify+resolve / full frame | Amdahl bound | speed-up | speed-up / bound | vs full run | miss shader = list |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Figures& f : fs) {
        char line[768];
        std::snprintf(
            line, sizeof line,
            "| %s | %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %.1f%% | %.1f%% | %.4f | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f | %s |\n",
            f.name.c_str(), f.config.octaves, f.raster_ms, f.shade_ms, f.rrc_ms, f.total_ms, f.full_ms, f.shaded_fraction, 100 * f.hit_fraction,
            100 * f.refreshed_fraction, f.rmse, f.p, f.c, f.bound, f.speedup, f.of_bound, f.speedup_separate,
            f.list_matched ? "yes" : "NO");
        o << line;
    }
    write_cost_section(o, fs);
    o << "\n## Targets\n\n| target | measured | verdict |\n|---|---|---|\n";
    for (const Verdict& v : verdicts(fs, s)) o << "| " << v.target << " | " << v.measured << " | " << v.verdict << " |\n";
    o << "\nThe paper (Nehab et al. 2007): refresh every 4 frames 1.7-1.9x, stereo +57%.\n";
}

}  // namespace rrc_cache
