#include "bias_output.h"

#include "exr_io.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rrc_sweep {
namespace {

std::string num(double v, const char* format = "%.6g") {
    if (!std::isfinite(v)) return "nan";
    char b[48];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

std::filesystem::path maps_dir(const SweepOptions& o) {
    const std::filesystem::path d = std::filesystem::path(o.out) / "bias_maps";
    std::filesystem::create_directories(d);
    return d;
}

// The columns a row shares with sweep_<app>.csv, then its label.
std::string config_columns(const char* method, uint32_t signal, uint32_t pattern, int k, const rrc_sample::ChannelSettings* c,
                           const std::string& label) {
    std::string s = std::string(method) + "," + (signal == 1u ? (pattern ? "rotated" : "disk") : "-") + "," + std::to_string(k) + ",";
    if (!c) return s + "-,-,-,-," + label;
    const bool mean = c->blend == RRC_BLEND_RUNNING_MEAN;
    return s + (mean ? std::string("-") : num(c->lambda, "%.4g")) + "," + blend_label(c->blend) + "," + filter_label(*c) + "," +
           (c->age_cap ? std::to_string(c->age_cap) : std::string("-")) + "," + label;
}

void region_lines(std::ofstream& f, const std::string& config, const RegionParts& p, const Metrics& m) {
    double bias2 = 0.0, variance = 0.0;
    for (int r = 0; r < kRegionCount; ++r) bias2 += p.bias2[r], variance += p.variance[r];
    for (int r = 0; r <= kRegionCount; ++r) {
        const bool total = r == kRegionCount;
        const double share = total ? 1.0 : p.pixel_share[r], raw = total ? 1.0 : p.raw_share[r];
        const double b = total ? bias2 : p.bias2[r], v = total ? variance : p.variance[r];
        f << config << "," << (total ? "total" : region_name(r)) << "," << num(share) << "," << num(raw) << "," << num(b) << "," << num(v)
          << "," << num(bias2 != 0.0 ? b / bias2 : NAN) << "," << num(share > 0.0 ? b / share : NAN) << ","
          << num(share > 0.0 ? v / share : NAN) << "," << num(m.rmse) << "," << num(m.bias2) << "," << num(m.variance) << "\n";
    }
}

}  // namespace

std::string row_label(const RrcRow& row) {
    const rrc_sample::ChannelSettings& c = row.config.channel;
    std::string s = std::string(row.config.app.name) + "_rrc_k" + std::to_string(row.k) + (row.pattern ? "_rotated" : "") + "_" +
                    blend_label(c.blend);
    if (c.blend != RRC_BLEND_RUNNING_MEAN) s += "_l" + num(c.lambda, "%.4g");
    s += "_" + filter_label(c);
    if (c.blend == RRC_BLEND_RUNNING_MEAN && c.age_cap) s += "_cap" + std::to_string(c.age_cap);
    for (char& ch : s)
        if (ch == '+') ch = '-';
    return s;
}

std::string row_label(const BruteRow& row) {
    return std::string(row.config.app.name) + "_brute_k" + std::to_string(row.config.k) + (row.config.pattern ? "_rotated" : "");
}

void write_bias_map(const SweepOptions& o, const std::string& label, const std::vector<std::vector<float>>& maps) {
    rrc_exr::ExrImage img;
    img.width = (int)o.width, img.height = (int)o.height;
    const std::vector<int> cps = o.checkpoints();
    for (size_t c = 0; c < maps.size() && c < cps.size(); ++c) img.channels["bias.cp" + std::to_string(cps[c])] = maps[c];
    img.attributes["rrc_sweep_row"] = label;
    rrc_exr::write_exr((maps_dir(o) / (label + ".exr")).string(), img);
}

void write_region_images(const SweepOptions& o, const char* app, const std::vector<std::vector<uint8_t>>& regions,
                         const std::vector<std::vector<uint16_t>>& ages, const std::vector<std::vector<float>>& targets) {
    rrc_exr::ExrImage img;
    img.width = (int)o.width, img.height = (int)o.height;
    const std::vector<int> cps = o.checkpoints();
    for (size_t c = 0; c < regions.size() && c < cps.size(); ++c) {
        const std::string t = ".cp" + std::to_string(cps[c]);
        // As floats (exact for these small integers): a reader need not know how its library scales UINT channels.
        img.channels["region" + t] = std::vector<float>(regions[c].begin(), regions[c].end());
        if (c < ages.size()) img.channels["age" + t] = std::vector<float>(ages[c].begin(), ages[c].end());
        if (c < targets.size()) img.channels["target" + t] = targets[c];
    }
    rrc_exr::write_exr((maps_dir(o) / (std::string(app) + "_regions.exr")).string(), img);
}

void write_region_tables(const SweepOptions& o, const SweepResult& r) {
    for (const App& app : apps_of(r.signals)) {
        const std::filesystem::path p = std::filesystem::path(o.out) / ("bias_regions_" + std::string(app.name) + ".csv");
        std::ofstream f(p);
        if (!f) throw std::runtime_error("cannot write " + p.string());
        f << "method,pattern,k,lambda,blend,filter,age_cap,label,region,pixel_share,raw_pixel_share,bias2,variance,bias2_share,"
             "bias2_per_pixel,variance_per_pixel,rmse,row_bias2,row_variance\n";
        for (const BruteRow& b : r.brute)
            if (b.config.app.signal == app.signal && b.has_regions)
                region_lines(f, config_columns("brute", app.signal, b.config.pattern, b.config.k, nullptr, row_label(b)), b.regions, b.metrics);
        for (const RrcRow& row : r.rrc)
            if (row.config.app.signal == app.signal && row.has_regions)
                region_lines(f, config_columns("rrc", app.signal, row.pattern, row.k, &row.config.channel, row_label(row)), row.regions,
                             row.metrics);
    }
}

}  // namespace rrc_sweep
