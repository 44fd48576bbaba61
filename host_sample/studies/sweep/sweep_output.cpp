#include "sweep_output.h"

#include "sweep_time.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rrc_sweep {
namespace {

std::ofstream open(const std::filesystem::path& p) {
    std::ofstream f(p);
    if (!f) throw std::runtime_error("cannot write " + p.string());
    return f;
}

std::string num(double v, const char* format = "%.6g") {
    if (!std::isfinite(v)) return "nan";
    char b[48];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

const char* kHeader =
    "method,pattern,k,lambda,blend,filter,age_cap,signal_ms,rrc_ms,time_ms,rmse,psnr,bias2,variance,flicker,mse_measured,reference_noise,"
    "seeds,checkpoints,rrc_alone_ms\n";

void metrics_columns(std::ofstream& f, double signal_ms, double rrc_ms, const Metrics& m, double rrc_alone_ms) {
    f << num(signal_ms) << "," << num(rrc_ms) << "," << num(row_time_ms(signal_ms, rrc_ms)) << "," << num(m.rmse) << "," << num(m.psnr) << ","
      << num(m.bias2) << "," << num(m.variance) << "," << num(m.flicker) << "," << num(m.mse_measured) << "," << num(m.reference_noise)
      << "," << m.seeds << "," << m.checkpoints << "," << num(rrc_alone_ms) << "\n";
}

}  // namespace

void write_sweep_files(const SweepOptions& o, const SweepResult& r, const std::string& command_line) {
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);
    for (const App& app : apps_of(r.signals)) {
        std::ofstream f = open(dir / ("sweep_" + std::string(app.name) + ".csv"));
        f << kHeader;
        for (const BruteRow& b : r.brute) {
            if (b.config.app.signal != app.signal) continue;
            f << "brute," << (app.signal == 1u ? (b.config.pattern ? "rotated" : "disk") : "-") << "," << b.config.k << ",-,-,-,-,";
            metrics_columns(f, b.signal_ms, 0.0, b.metrics, 0.0);
        }
        for (const RrcRow& row : r.rrc) {
            if (row.config.app.signal != app.signal) continue;
            const rrc_sample::ChannelSettings& c = row.config.channel;
            const bool mean = c.blend == RRC_BLEND_RUNNING_MEAN;
            f << "rrc," << (app.signal == 1u ? (row.pattern ? "rotated" : "disk") : "-") << "," << row.k << ","
              << (mean ? std::string("-") : num(c.lambda, "%.4g")) << "," << blend_label(c.blend) << "," << filter_label(c) << ","
              << (c.age_cap ? std::to_string(c.age_cap) : std::string("-")) << ",";
            metrics_columns(f, row.signal_ms, row.rrc_ms, row.metrics, row.rrc_alone_ms);
        }
    }
    {
        std::ofstream f = open(dir / "hit_ratio.csv");
        f << "frame,hit_ratio\n";
        for (size_t i = 0; i < r.hit_ratio.size(); ++i) f << i << "," << num(r.hit_ratio[i]) << "\n";
    }
    std::ofstream f = open(dir / "sweep.md");
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    f << "# rrc-sweep\n\n"
      << "- command: `" << command_line << "`\n"
      << "- date: " << date << "; device: " << r.device << "; " << r.seconds << " s\n"
      << "- scene " << o.scene << ", " << o.width << "x" << o.height << ", frames 0.." << o.checkpoints().back() << " from a reset, "
      << o.seeds << " seeds, checkpoints";
    for (int t : o.checkpoints()) f << " " << t;
    f << " (each scored with its previous frame for the flicker)\n"
      << "- targets: pcf the exact disk mean; env " << o.reference_samples << " rays a pixel (its noise measured by a second, independent "
      << "estimate and subtracted); soft the " << o.reference_samples << "-point grid on the light\n"
      << "- motion: " << o.motion << "\n"
      << "- rows: " << r.brute.size() << " brute force, " << r.rrc.size() << " rrc\n"
      << "- time of a row: the application's signal pass at k samples plus its share of rrc, each pass in a submission of its own "
      << "(medians over frames 2.. of every seed; brute force timed one configuration a frame inside the rrc runs' frames, an rrc "
      << "row's signal pass = the brute-force pass at its k, its rrc time pooled over every run)\n"
      << "- pcf residual's base: "
      << (o.pcf_base_in_signal ? "written by the pcf signal pass (--pcf-base-in-signal): a residual row's signal time holds it and is "
                                 "that row's own pass, timed in its runs"
                               : "a pass of its own, timed with rrc")
      << "\n"
      << "- clock: " << r.clock << "; timestamps / wall clock (signal passes and rrc, median per frame): " << num(r.stamps_over_wall, "%.3f")
      << "\n"
      << "- rrc's sharing probe: the default channels alone " << num(r.rrc_alone_sum_ms, "%.3f") << " ms together, in one context "
      << num(r.rrc_together_ms, "%.3f") << " ms; a row's share = its channel alone less a third of the difference\n";
    if (o.validation) f << "- validation messages: " << r.validation_messages << "\n";
    f << "\nfronts.py writes fronts.md (the fronts, the fit t = F + k c + R, the targets' verdicts) and the plots.\n";
}

}  // namespace rrc_sweep
