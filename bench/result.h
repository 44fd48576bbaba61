// What one configuration measured: its interop timings, the standalone
// round trip where the configuration asks for it, and the roof's bytes as
// the API implies them.  The report (report.h) derives every figure from this.
#pragma once

#include "config.h"
#include "interop_run.h"
#include "roof.h"
#include "stats.h"
#include "standalone_run.h"

#include <string>
#include <vector>

namespace rrc_bench {

struct Row {
    Config config;
    InteropResult interop;
    bool has_standalone = false;
    StandaloneResult standalone;
    RoofBytes api_bytes;  // roof_bytes_from_api(config)

    Summary kernel() const { return summarize(interop.kernel_ms); }
    Summary roof() const { return summarize(interop.roof_ms); }
    Summary ratio() const { return summarize(interop.ratio); }
    Summary wall() const { return summarize(interop.wall_ms); }
    double megapixels() const { return (double)config.width * config.height * 1e-6; }
    double hit_fraction() const { return interop.stats.pixels ? (double)interop.stats.hits / interop.stats.pixels : 0.0; }
    /** Young pixels (surface, age < kYoungAge) over all pixels of the statistics frame. */
    double young_fraction() const { return interop.stats.pixels ? (double)interop.young / interop.stats.pixels : 0.0; }
    /** The same over the surface (non-background) pixels. */
    double young_surface_fraction() const {
        const double surface = (double)interop.stats.pixels - interop.stats.background;
        return surface > 0 ? (double)interop.young / surface : 0.0;
    }
    /** Split shading cache: listed quads x 4 over the pixels (the share classify asks the host to shade). */
    double listed_fraction() const { return interop.stats.pixels ? 4.0 * interop.listed_quads / interop.stats.pixels : 0.0; }
    /** A count of the statistics frame's rrc_vulkan_io_counts over its pixels (the kernel's
     *  image operations a pixel, docs/measurements/PERFORMANCE.md "What a pixel moves"). */
    double io_per_pixel(uint64_t count) const { return interop.stats.pixels ? (double)count / interop.stats.pixels : 0.0; }
    /** The roof's bytes a pixel, read or written. */
    double roof_per_pixel(uint64_t bytes) const { return (double)bytes / ((double)config.width * config.height); }
    /** Bytes of the roof / its median time, in GB/s (1e9 bytes). */
    double roof_gbps() const { return (double)api_bytes.total() / (roof().median * 1e6); }
    /** The same bytes over the kernel's median time: the kernel's effective bandwidth. */
    double kernel_gbps() const { return (double)api_bytes.total() / (kernel().median * 1e6); }
    /** Standalone round trip / (interop kernel median + memcpy of the standalone bytes). */
    double round_trip_ratio() const {
        return summarize(standalone.frame_ms).median / (kernel().median + summarize(standalone.memcpy_ms).median);
    }
};

struct RunInfo {
    std::string command, device, commit, date, cpu, mesa;
    int reps = 0, warmup = 0;
    bool validation = false;
    bool size_override = false;  // --size: resolution rows are not at their nominal sizes
    uint64_t validation_messages = 0;
    double load_start = 0, load_end = 0;  // 1-minute load average before and after the run
};

}  // namespace rrc_bench
