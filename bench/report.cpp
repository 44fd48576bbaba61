#include "report.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rrc_bench {
namespace {

const char* source_name(rrc_reprojection s) {
    switch (s) {
        case RRC_REPROJECTION_PREV_CLIP: return "prev_clip";
        case RRC_REPROJECTION_MOTION: return "motion";
        case RRC_REPROJECTION_MOTION_DEPTH: return "motion_depth";
        case RRC_REPROJECTION_CAMERA: return "camera";
        default: return "?";
    }
}

std::string num(double v, int digits = 4) {
    char s[64];
    std::snprintf(s, sizeof s, "%.*f", digits, v);
    return s;
}

std::string json_string(const std::string& s) {
    std::string o = "\"";
    for (char ch : s) {
        if (ch == '"' || ch == '\\') o += '\\';
        if ((unsigned char)ch < 0x20) {
            o += ' ';
            continue;
        }
        o += ch;
    }
    return o + "\"";
}

double mb(uint64_t bytes) { return (double)bytes / 1e6; }

// One row as (column, value, is-text) triples: CSV and JSON share the columns.
struct Field {
    std::string key, value;
    bool text;
};

// A summary's median, min and max as the columns <name>_median, _min, _max.
void add_spread(std::vector<Field>& f, const std::string& name, const Summary& s) {
    f.push_back({name + "_median", num(s.median), false});
    f.push_back({name + "_min", num(s.min), false});
    f.push_back({name + "_max", num(s.max), false});
}

std::vector<Field> fields(const Row& r) {
    const Config& c = r.config;
    const Summary k = r.kernel(), t = r.roof(), q = r.ratio(), w = r.wall();
    std::vector<Field> f = {
        {"name", c.name, true},
        {"factor", c.factor, true},
        {"width", std::to_string(c.width), false},
        {"height", std::to_string(c.height), false},
        {"megapixels", num(r.megapixels()), false},
        {"channels", std::to_string(c.channels.size()), false},
        {"channel_layout", channels_text(c), true},
        {"source", source_name(c.source), true},
    };
    add_spread(f, "kernel_ms", k);
    add_spread(f, "roof_ms", t);
    add_spread(f, "ratio", q);
    f.insert(f.end(), {
                          {"ratio_q1", num(q.q1), false},
                          {"ratio_q3", num(q.q3), false},
                          {"roof_gbps", num(r.roof_gbps(), 3), false},
                          {"kernel_gbps", num(r.kernel_gbps(), 3), false},
                          {"bytes_read", std::to_string(r.api_bytes.read), false},
                          {"bytes_written", std::to_string(r.api_bytes.written), false},
                          {"bytes", std::to_string(r.api_bytes.total()), false},
                          {"bound_bytes_read", std::to_string(r.interop.roof_bytes_bound.read), false},
                          {"bound_bytes_written", std::to_string(r.interop.roof_bytes_bound.written), false},
                          {"memory_bytes", std::to_string(r.interop.memory_bytes), false},
                      });
    // The kernel's image operations a pixel (count_io), beside the roof's.
    const bool io = r.interop.io_counted;
    const rrc_vulkan_io_counts& n = r.interop.io;
    f.insert(f.end(), {
                          {"loads_per_pixel", io ? num(r.io_per_pixel(n.loads), 3) : "", false},
                          {"texels_loaded_per_pixel", io ? num(r.io_per_pixel(n.texels_loaded), 3) : "", false},
                          {"bytes_loaded_per_pixel", io ? num(r.io_per_pixel(n.bytes_loaded), 3) : "", false},
                          {"stores_per_pixel", io ? num(r.io_per_pixel(n.stores), 3) : "", false},
                          {"bytes_stored_per_pixel", io ? num(r.io_per_pixel(n.bytes_stored), 3) : "", false},
                          {"roof_loads_per_pixel", std::to_string(r.api_bytes.loads_per_pixel), false},
                          {"roof_bytes_loaded_per_pixel", num(r.roof_per_pixel(r.api_bytes.read), 3), false},
                          {"roof_stores_per_pixel", std::to_string(r.api_bytes.stores_per_pixel), false},
                          {"roof_bytes_stored_per_pixel", num(r.roof_per_pixel(r.api_bytes.written), 3), false},
                      });
    add_spread(f, "wall_ms", w);
    f.insert(f.end(), {
                          {"hit_fraction", num(r.hit_fraction()), false},
                          {"background_fraction",
                           num(r.interop.stats.pixels ? (double)r.interop.stats.background / r.interop.stats.pixels : 0.0), false},
                          {"nocache_share", c.nocache ? num(c.nocache_share) : "", false},
                          {"young_fraction", num(r.young_fraction()), false},
                          {"young_surface_fraction", num(r.young_surface_fraction()), false},
                          {"listed_quads", c.shading_cache == Config::Cache::Split ? std::to_string(r.interop.listed_quads) : "", false},
                          {"listed_fraction", c.shading_cache == Config::Cache::Split ? num(r.listed_fraction()) : "", false},
                          {"reps", std::to_string(r.interop.kernel_ms.size()), false},
                          {"timer", r.interop.timestamps ? "timestamps" : "wall", true},
                          {"roof_check",
                           r.interop.roof_check == "skipped" ? "skipped"
                           : r.interop.roof_check.empty()    ? "exact"
                                                             : r.interop.roof_check,
                           true},
                      });
    if (r.has_standalone) {
        const Summary s = summarize(r.standalone.frame_ms), m = summarize(r.standalone.memcpy_ms);
        f.push_back({"standalone_fps", num(1000.0 / s.median, 2), false});
        add_spread(f, "standalone_ms", s);
        f.push_back({"memcpy_ms_median", num(m.median), false});
        f.push_back({"standalone_bytes", std::to_string(r.standalone.bytes), false});
        f.push_back({"round_trip_ratio", num(r.round_trip_ratio()), false});
        f.push_back({"standalone_memory_bytes", std::to_string(r.standalone.memory_bytes), false});
    } else {
        for (const char* k : {"standalone_fps", "standalone_ms_median", "standalone_ms_min", "standalone_ms_max", "memcpy_ms_median",
                              "standalone_bytes", "round_trip_ratio", "standalone_memory_bytes"})
            f.push_back({k, "", false});
    }
    return f;
}

// What a pixel moves: the kernel's counted image operations of the statistics frame
// (rrc_vulkan_frame_desc.count_io) beside the roof's, a row per configuration that
// runs rrc_vulkan_record_frame (classify and resolve count nothing).
std::string io_table(const std::vector<Row>& rows, bool markdown) {
    std::string o;
    char line[512];
    if (markdown)
        o += "| config | loads/px | texels/px | bytes loaded/px | stores/px | bytes stored/px | roof loads/px | roof bytes loaded/px | roof "
             "stores/px | roof bytes stored/px |\n|---|---|---|---|---|---|---|---|---|---|\n";
    else {
        std::snprintf(line, sizeof line, "%-18s %8s %8s %9s %8s %9s | %6s %9s %6s %9s\n", "what a pixel moves", "loads", "texels",
                      "bytes in", "stores", "bytes out", "roof:", "bytes in", "stores", "bytes out");
        o += line;
    }
    for (const Row& r : rows) {
        if (!r.interop.io_counted) continue;
        const rrc_vulkan_io_counts& n = r.interop.io;
        const char* fmt = markdown ? "| %s | %.2f | %.2f | %.1f | %.2f | %.1f | %u | %.1f | %u | %.1f |\n"
                                   : "%-18s %8.2f %8.2f %9.1f %8.2f %9.1f | %6u %9.1f %6u %9.1f\n";
        std::snprintf(line, sizeof line, fmt, r.config.name.c_str(), r.io_per_pixel(n.loads), r.io_per_pixel(n.texels_loaded),
                      r.io_per_pixel(n.bytes_loaded), r.io_per_pixel(n.stores), r.io_per_pixel(n.bytes_stored), r.api_bytes.loads_per_pixel,
                      r.roof_per_pixel(r.api_bytes.read), r.api_bytes.stores_per_pixel, r.roof_per_pixel(r.api_bytes.written));
        o += line;
    }
    return o;
}

void print_io_table(const std::vector<Row>& rows) {
    bool any = false;
    for (const Row& r : rows) any = any || r.interop.io_counted;
    if (any) std::printf("\n%s", io_table(rows, false).c_str());
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

void print_table(const std::vector<Row>& rows) {
    std::printf("\n%-18s %9s %-9s %22s %9s %19s %7s %7s %8s %8s %5s %5s\n", "config", "size", "channels", "kernel ms (min-max)", "roof ms",
                "ratio (IQR)", "roof", "kernel", "memory", "wall ms", "hits", "young");
    std::printf("%-18s %9s %-9s %22s %9s %19s %7s %7s %8s %8s %5s %5s\n", "", "", "", "median", "median", "median", "GB/s", "GB/s", "MB",
                "median", "%", "%");
    for (const Row& r : rows) {
        const Summary k = r.kernel(), t = r.roof(), q = r.ratio();
        char size[32], kern[64], ratio[64];
        std::snprintf(size, sizeof size, "%ux%u", r.config.width, r.config.height);
        std::snprintf(kern, sizeof kern, "%.2f (%.2f-%.2f)", k.median, k.min, k.max);
        std::snprintf(ratio, sizeof ratio, "%.3f (%.2f-%.2f)", q.median, q.q1, q.q3);
        std::printf("%-18s %9s %-9s %22s %9.2f %19s %7.2f %7.2f %8.1f %8.2f %5.1f %5.1f\n", r.config.name.c_str(), size,
                    channels_text(r.config).c_str(), kern, t.median, ratio, r.roof_gbps(), r.kernel_gbps(), mb(r.interop.memory_bytes),
                    r.wall().median, 100.0 * r.hit_fraction(), 100.0 * r.young_fraction());
    }
    print_io_table(rows);
    for (const Row& r : rows)
        if (r.has_standalone) {
            const Summary s = summarize(r.standalone.frame_ms), m = summarize(r.standalone.memcpy_ms);
            std::printf(
                "\nstandalone %s %ux%u: %.2f ms a frame (%.1f fps, min %.2f max %.2f), memcpy of its %.1f MB %.2f ms, "
                "round trip / (kernel + memcpy) = %.2f, memory %.1f MB\n",
                r.config.name.c_str(), r.config.width, r.config.height, s.median, 1000.0 / s.median, s.min, s.max, mb(r.standalone.bytes),
                m.median, r.round_trip_ratio(), mb(r.standalone.memory_bytes));
        }
    std::printf("\npublished, not measured: NRD SIGMA %.1f MB at 1080p, FSR 2 %.0f MB at 1080p quality\n", kNrdSigmaMb1080p,
                kFsr2Mb1080pQuality);
}

void write_csv(const std::string& path, const std::vector<Row>& rows) {
    std::ostringstream o;
    for (size_t i = 0; !rows.empty() && i < fields(rows[0]).size(); ++i) o << (i ? "," : "") << fields(rows[0])[i].key;
    o << "\n";
    for (const Row& r : rows) {
        const auto f = fields(r);
        for (size_t i = 0; i < f.size(); ++i) o << (i ? "," : "") << (f[i].text ? json_string(f[i].value) : f[i].value);
        o << "\n";
    }
    write_file(path, o.str());
}

void write_json(const std::string& path, const RunInfo& info, const std::vector<Row>& rows, const Linearity& lin,
                const std::vector<Target>& targets) {
    std::ostringstream o;
    o << "{\n  \"command\": " << json_string(info.command) << ",\n  \"device\": " << json_string(info.device)
      << ",\n  \"commit\": " << json_string(info.commit) << ",\n  \"date\": " << json_string(info.date)
      << ",\n  \"cpu\": " << json_string(info.cpu) << ",\n  \"load_average\": [" << num(info.load_start, 2) << ", " << num(info.load_end, 2)
      << "],\n  \"reps\": " << info.reps << ",\n  \"warmup\": " << info.warmup
      << ",\n  \"validation\": " << (info.validation ? "true" : "false") << ",\n  \"validation_messages\": " << info.validation_messages
      << ",\n  \"published_memory_mb\": {\"nrd_sigma_1080p\": " << kNrdSigmaMb1080p << ", \"fsr2_1080p_quality\": " << kFsr2Mb1080pQuality
      << "},\n  \"rows\": [\n";
    for (size_t i = 0; i < rows.size(); ++i) {
        const auto f = fields(rows[i]);
        o << "    {";
        for (size_t j = 0; j < f.size(); ++j)
            o << (j ? ", " : "") << json_string(f[j].key) << ": "
              << (f[j].text            ? json_string(f[j].value)
                  : f[j].value.empty() ? "null"
                                       : f[j].value);
        o << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    o << "  ],\n  \"linearity\": {\"measured\": " << (lin.measured ? "true" : "false")
      << ", \"ms_per_megapixel\": " << num(lin.ms_per_mpixel) << ", \"intercept_ms\": " << num(lin.intercept_ms)
      << ", \"slope_ms_per_megapixel\": " << num(lin.slope_ms) << ", \"max_abs_deviation\": " << num(lin.max_abs_deviation)
      << ", \"small_share\": " << (lin.small_measured ? num(lin.small_share) : "null") << ", \"deviation\": {";
    for (size_t i = 0; i < lin.deviation.size(); ++i)
        o << (i ? ", " : "") << json_string(lin.deviation[i].first) << ": " << num(lin.deviation[i].second);
    o << "}},\n  \"targets\": [\n";
    for (size_t i = 0; i < targets.size(); ++i) {
        const Target& t = targets[i];
        o << "    {\"name\": " << json_string(t.name) << ", \"goal\": " << json_string(t.goal)
          << ", \"measured\": " << json_string(t.measured) << ", \"status\": " << json_string(t.status)
          << ", \"margin\": " << json_string(t.margin) << "}" << (i + 1 < targets.size() ? "," : "") << "\n";
    }
    o << "  ]\n}\n";
    write_file(path, o.str());
}

void write_markdown(const std::string& path, const RunInfo& info, const std::vector<Row>& rows, const Linearity& lin,
                    const std::vector<Target>& targets) {
    std::ostringstream o;
    o << "Measured on commit `" << info.commit << "`, " << info.date << ", " << info.device << " on " << info.cpu
      << " (1-minute load average " << num(info.load_start, 2) << " before the run, " << num(info.load_end, 2)
      << " after, the bench's own threads included).\n\n"
      << "Command: `" << info.command << "` (" << info.reps << " timed repetitions after " << info.warmup << " warm-up frames"
      << (info.validation ? ", under validation: timings not representative" : "") << ").\n\n";
    o << "| config | size | channels | source | kernel ms median (min–max) | roof ms median (min–max) | kernel/roof median (IQR; min–max) "
         "| roof GB/s | "
         "kernel GB/s | roof MB/frame | memory MB | wall ms/frame | hits % | young % |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    char line[1024];
    for (const Row& r : rows) {
        const Summary k = r.kernel(), t = r.roof(), q = r.ratio();
        std::snprintf(line, sizeof line,
                      "| %s | %ux%u | %s | %s | %.2f (%.2f–%.2f) | %.2f (%.2f–%.2f) | %.3f (%.2f–%.2f; %.2f–%.2f) | %.2f | %.2f | %.1f | "
                      "%.1f | %.2f | %.1f | %.1f |\n",
                      r.config.name.c_str(), r.config.width, r.config.height, channels_text(r.config).c_str(), source_name(r.config.source),
                      k.median, k.min, k.max, t.median, t.min, t.max, q.median, q.q1, q.q3, q.min, q.max, r.roof_gbps(), r.kernel_gbps(),
                      mb(r.api_bytes.total()), mb(r.interop.memory_bytes), r.wall().median, 100.0 * r.hit_fraction(),
                      100.0 * r.young_fraction());
        o << line;
    }
    // What the young column counts (docs/measurements/PERFORMANCE.md, "What is timed"): the fill's workload.
    o << "\nyoung %: surface pixels of age < " << kYoungAge << " (channel 0; the fill's pixels at fill_age " << kYoungAge
      << ") over all pixels of the untimed statistics frame.";
    for (const Row& r : rows)
        if (r.config.young)
            o << " " << r.config.name << ": nocache share " << num(100.0 * r.config.nocache_share, 1) << " %, young "
              << num(100.0 * r.young_fraction(), 1) << " % of pixels (" << num(100.0 * r.young_surface_fraction(), 1)
              << " % of surface pixels).";
    for (const Row& r : rows)
        if (r.config.shading_cache == Config::Cache::Split)
            o << " " << r.config.name << ": " << r.interop.listed_quads << " quads listed, " << num(100.0 * r.listed_fraction(), 1)
              << " % of pixels.";
    o << "\n";
    bool any_io = false;
    for (const Row& r : rows) any_io = any_io || r.interop.io_counted;
    if (any_io)
        o << "\nWhat a pixel moves: the kernel's image loads (a gather's four texels counted as texels) and stores in the untimed "
             "statistics frame (`rrc_vulkan_frame_desc.count_io`), over its pixels, beside the roof's, which loads and stores each "
             "image once (docs/measurements/PERFORMANCE.md, \"What a pixel moves\").\n\n"
          << io_table(rows, true);
    for (const Row& r : rows)
        if (r.has_standalone) {
            const Summary s = summarize(r.standalone.frame_ms), m = summarize(r.standalone.memcpy_ms);
            o << "\nStandalone path (`" << r.config.name << "`, " << r.config.width << "x" << r.config.height << ", " << r.standalone.device
              << "):\n\n| rrc_frame_run ms median (min–max) | fps | its bytes MB (in + out) | memcpy of them ms | interop kernel ms | "
                 "round trip / (kernel + memcpy) | memory MB (staging included) |\n|---|---|---|---|---|---|---|\n";
            std::snprintf(line, sizeof line, "| %.2f (%.2f–%.2f) | %.1f | %.1f | %.2f | %.2f | %.2f | %.1f |\n", s.median, s.min, s.max,
                          1000.0 / s.median, mb(r.standalone.bytes), m.median, r.kernel().median, r.round_trip_ratio(),
                          mb(r.standalone.memory_bytes));
            o << line;
        }
    o << "\nMemory beside published figures (not measured here): NRD's SIGMA shadow denoiser " << kNrdSigmaMb1080p << " MB at 1080p, FSR 2 "
      << kFsr2Mb1080pQuality << " MB at 1080p (quality mode).";
    for (const Row& r : rows)
        if (r.config.name == "base")
            o << " rrc, base (" << r.config.width << "x" << r.config.height << "): " << num(mb(r.interop.memory_bytes), 1) << " MB.";
    o << "\n\nLinearity (kernel median time against pixels): ";
    if (lin.measured) {
        o << num(lin.ms_per_mpixel, 2)
          << " ms per megapixel (least squares through 0 over 720p and above, fitted in each round of repetitions; medians over the "
             "rounds); deviations:";
        for (const auto& d : lin.deviation) o << " " << d.first << " " << num(100.0 * d.second, 1) << "%";
        o << "; max |deviation| " << num(100.0 * lin.max_abs_deviation, 1) << "%.";
        if (lin.small_measured) o << " 256x160: " << num(lin.small_share, 2) << "x its linear share.";
        o << " Fit with an intercept over every resolution row: ms = " << num(lin.intercept_ms, 2) << " + " << num(lin.slope_ms, 2)
          << " * MP.\n";
    } else {
        o << "not measured (needs at least two resolutions of 720p and above).\n";
    }
    o << "\n| target | goal | measured | status | margin |\n|---|---|---|---|---|\n";
    for (const Target& t : targets)
        o << "| " << t.name << " | " << t.goal << " | " << t.measured << " | " << t.status << " | " << t.margin << " |\n";
    write_file(path, o.str());
}

}  // namespace rrc_bench
