#include "finish.h"

#include "oracle.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rrc_sample {
namespace {

void dump(const std::string& dir, const char* what, int frame, const std::vector<float>& v) {
    if (v.empty()) return;
    char name[128];
    std::snprintf(name, sizeof name, "%s_%04d.f32", what, frame);
    std::ofstream f(std::filesystem::path(dir) / name, std::ios::binary);
    f.write((const char*)v.data(), (std::streamsize)(v.size() * sizeof(float)));
}

}  // namespace

FinishErrors finish_errors(const FrameOutput& f) {
    FinishErrors e;
    if (!f.checkpoint || f.pcf.reference.empty()) return e;
    std::vector<uint8_t> surface(f.mask.size());  // as frame_errors: pcf over every surface pixel
    for (size_t i = 0; i < f.mask.size(); ++i) surface[i] = !(f.mask[i] & RRC_MASK_BACKGROUND);
    if (!f.pcf.display.empty()) e.pcf_display = error_against(f.pcf.display, f.pcf.reference, 1, 1, surface);
    if (!f.pcf.weighted_target.empty()) {
        e.pcf_vs_weighted = error_against(f.pcf.accumulated, f.pcf.weighted_target, 1, 1, surface);
        e.weighted_vs_target = error_against(f.pcf.weighted_target, f.pcf.reference, 1, 1, surface);
    }
    return e;
}

const char* FinishReport::name(Display d) {
    static const char* names[kDisplayCount] = {"raw", "accumulated", "shown", "pcss"};
    return names[d];
}

double FinishReport::Sum::rmse() const { return n ? std::sqrt(sq / (double)n) : 0.0; }

FinishReport::FinishReport(const Options& o, uint32_t signals) : o_(o) {
    enabled_ = (signals & kSignalSoft) != 0;
    by_age_[0].resize(o.young_ages);
    by_age_[1].resize(o.young_ages);
    if (o.dump_soft && enabled_) std::filesystem::create_directories(std::filesystem::path(o.out) / "finish");
}

void FinishReport::add(const FrameOutput& f, const std::vector<uint8_t>& verdict) {
    if (o_.dump_soft && f.checkpoint && !f.pcf.reference.empty()) {
        const std::string dir = (std::filesystem::path(o_.out) / "finish").string();
        std::filesystem::create_directories(dir);
        dump(dir, "pcf_reference", f.index, f.pcf.reference);
        dump(dir, "pcf_raw", f.index, f.pcf.raw);
        dump(dir, "pcf_accumulated", f.index, f.pcf.accumulated);
        dump(dir, "pcf_shown", f.index, f.pcf.display);
        dump(dir, "pcf_confidence", f.index, f.pcf.confidence);
        dump(dir, "pcf_weighted_target", f.index, f.pcf.weighted_target);
        dump(dir, "age", f.index, std::vector<float>(f.age.begin(), f.age.end()));
        std::ofstream m(std::filesystem::path(dir) / "size.txt");
        m << f.width << " " << f.height << "\n";
    }
    if (!enabled_) return;
    {  // the start of each track: as age.comp carries the age
        const size_t n = f.mask.size();
        std::vector<uint8_t> kind(n, 0);
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const size_t i = (size_t)y * f.width + x;
                if (f.mask[i] & RRC_MASK_BACKGROUND) continue;
                if (!(f.mask[i] & RRC_MASK_HIT)) {
                    const bool visible = verdict.size() == n && (verdict[i] & (kVerdictVisible | kVerdictStraddling));
                    kind[i] = f.index == 0 || visible || verdict.size() != n ? 2 : 1;
                } else if (kind_.size() == n) {
                    const float* c = &f.prev_clip[i * 4];
                    const int qx = std::clamp((int)std::floor((c[0] / c[3] + 1.0f) * 0.5f * f.width), 0, f.width - 1);
                    const int qy = std::clamp((int)std::floor((c[1] / c[3] + 1.0f) * 0.5f * f.height), 0, f.height - 1);
                    kind[i] = kind_[(size_t)qy * f.width + qx];
                }
            }
        kind_ = std::move(kind);
    }
    if (!f.checkpoint || f.soft.reference.empty()) return;
    const SignalData& s = f.soft;
    const std::vector<float>* d[kDisplayCount] = {&s.raw, &s.accumulated, &s.shown, &s.pcss};
    std::array<Sum, kDisplayCount> all{};
    for (size_t i = 0; i < f.mask.size(); ++i) {
        if (f.mask[i] & RRC_MASK_BACKGROUND) continue;
        const uint32_t a = f.age[i];
        // Young: age a at frame t means the pixel missed at t - a + 1 and hit since; the reset
        // (frame 0, every pixel misses) is not a disocclusion.
        const bool young = a >= 1 && a <= o_.young_ages && f.index - (int)a + 1 >= 1;
        for (int k = 0; k < kDisplayCount; ++k) {
            if (d[k]->empty()) continue;
            const double e = (double)(*d[k])[i] - (double)s.reference[i];
            all[k].sq += e * e, all[k].n++;
            for (int set = 0; set < 2; ++set)
                if (young && (set == 0 || kind_[i] == 1)) {
                    by_age_[set][a - 1][k].sq += e * e, by_age_[set][a - 1][k].n++;
                    young_[set][k].sq += e * e, young_[set][k].n++;
                }
        }
    }
    Row row{f.index, {}};
    for (int k = 0; k < kDisplayCount; ++k) row.rmse[k] = all[k].n ? all[k].rmse() : NAN;
    curve_.push_back(row);
    if (o_.dump_soft) {
        const std::string dir = (std::filesystem::path(o_.out) / "finish").string();
        dump(dir, "soft_reference", f.index, s.reference);
        for (int k = 0; k < kDisplayCount; ++k) dump(dir, (std::string("soft_") + name((Display)k)).c_str(), f.index, *d[k]);
        std::vector<float> age(f.age.begin(), f.age.end());
        dump(dir, "age", f.index, age);
        std::ofstream m(std::filesystem::path(dir) / "size.txt");
        m << f.width << " " << f.height << "\n";
    }
}

void FinishReport::write(const std::string& out_dir) const {
    if (!enabled_) return;
    std::ofstream y(std::filesystem::path(out_dir) / "young.csv");
    y << "tracks,age,pixels";
    for (int k = 0; k < kDisplayCount; ++k) y << ",rmse_" << name((Display)k);
    y << "\n";
    auto row = [&](const char* set, const std::string& label, const std::array<Sum, kDisplayCount>& s) {
        y << set << "," << label << "," << s[kRaw].n;
        for (int k = 0; k < kDisplayCount; ++k) y << "," << (s[k].n ? fmt("%.6f", s[k].rmse()) : "");
        y << "\n";
    };
    const char* sets[2] = {"all", "disoccluded"};
    for (int set = 0; set < 2; ++set) {
        for (size_t a = 0; a < by_age_[set].size(); ++a) row(sets[set], std::to_string(a + 1), by_age_[set][a]);
        row(sets[set], "1-" + std::to_string(by_age_[set].size()), young_[set]);
    }
    std::ofstream c(std::filesystem::path(out_dir) / "curve.csv");
    c << "frame,frames_since_reset";
    for (int k = 0; k < kDisplayCount; ++k) c << ",rmse_" << name((Display)k);
    c << "\n";
    for (const Row& r : curve_) {
        c << r.frame << "," << r.frame + 1;
        for (int k = 0; k < kDisplayCount; ++k) c << "," << (std::isnan(r.rmse[k]) ? "" : fmt("%.6f", r.rmse[k]));
        c << "\n";
    }
}

std::string FinishReport::table() const {
    if (!enabled_ || !young_[0][kRaw].n) return "";
    std::ostringstream s;
    const char* sets[2] = {"every young track", "tracks started by a true disocclusion"};
    for (int set = 0; set < 2; ++set) {
        const auto& y = young_[set];
        if (!y[kRaw].n) continue;
        s << "young soft pixels, " << sets[set] << " (ages 1-" << by_age_[set].size() << ", " << y[kRaw].n
          << " pixel-frames), RMSE against the reference:";
        for (int k = 0; k < kDisplayCount; ++k)
            if (y[k].n) s << " " << name((Display)k) << " " << fmt("%.4f", y[k].rmse());
        s << "\n";
    }
    return s.str();
}

}  // namespace rrc_sample
