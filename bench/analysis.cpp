#include "analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rrc_bench {
namespace {

const Row* find(const std::vector<Row>& rows, const std::string& name) {
    for (const Row& r : rows)
        if (r.config.name == name) return &r;
    return nullptr;
}

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
    char s[160];
    std::snprintf(s, sizeof s, f, a, b, c);
    return s;
}

// "met"/"missed" with the margin relative to the limit: value <= limit is met.
Target upper_bound(const std::string& name, const std::string& goal, double value, double limit, const std::string& measured) {
    Target t{name, goal, measured, value <= limit ? "met" : "missed", ""};
    t.margin = value <= limit ? fmt("%.1f%% inside", 100.0 * (limit - value) / limit) : fmt("over by %.1f%%", 100.0 * (value - limit) / limit);
    return t;
}

Target absent(const std::string& name, const std::string& goal, const std::string& needs) {
    return Target{name, goal, "", "not measured", "needs " + needs};
}


// Every row ran once in each round of repetitions (rep-major, main.cpp), so
// rows are compared round by round and the median taken over the rounds:
// the load of a shared machine then cancels as it does for kernel/roof.
size_t rounds(const std::vector<const Row*>& rows) {
    size_t n = rows.empty() ? 0 : rows[0]->interop.kernel_ms.size();
    for (const Row* r : rows) n = std::min(n, r->interop.kernel_ms.size());
    return n;
}

bool at_1080p(const Row* r) { return r && r->config.width == 1920 && r->config.height == 1080; }

double paired_ratio(const Row& a, const Row& b) {
    std::vector<double> q;
    for (size_t i = 0; i < rounds({&a, &b}); ++i) q.push_back(a.interop.kernel_ms[i] / b.interop.kernel_ms[i]);
    return summarize(q).median;
}

}  // namespace

Linearity analyze_linearity(const std::vector<Row>& rows) {
    Linearity l;
    std::vector<const Row*> res, big;
    for (const Row& r : rows)
        if (r.config.factor == "resolution" || r.config.factor == "base") res.push_back(&r);
    for (const Row* r : res)
        if (r->config.height >= 720) big.push_back(r);
    const size_t n = rounds(res);
    if (big.size() >= 2 && n > 0) {
        // Round i: k_i = least squares through 0 of ms against megapixels.
        std::vector<double> k(n);
        for (size_t i = 0; i < n; ++i) {
            double sxy = 0, sxx = 0;
            for (const Row* r : big) {
                sxy += r->megapixels() * r->interop.kernel_ms[i];
                sxx += r->megapixels() * r->megapixels();
            }
            k[i] = sxy / sxx;
        }
        auto share = [&](const Row* r) {
            std::vector<double> q;
            for (size_t i = 0; i < n; ++i) q.push_back(r->interop.kernel_ms[i] / (k[i] * r->megapixels()));
            return summarize(q).median;
        };
        l.measured = true;
        l.ms_per_mpixel = summarize(k).median;
        for (const Row* r : big) {
            const double d = share(r) - 1.0;
            l.deviation.push_back({r->config.name, d});
            l.max_abs_deviation = std::max(l.max_abs_deviation, std::abs(d));
        }
        for (const Row* r : res)
            if (r->config.height < 720) {
                l.small_measured = true;
                l.small_share = share(r);
            }
    }
    if (res.size() >= 2) {  // ordinary least squares with an intercept: the fixed cost of a frame
        double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (const Row* r : res) {
            const double x = r->megapixels(), y = r->kernel().median;
            n += 1;
            sx += x;
            sy += y;
            sxx += x * x;
            sxy += x * y;
        }
        l.slope_ms = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        l.intercept_ms = (sy - l.slope_ms * sx) / n;
    }
    return l;
}

std::vector<Target> evaluate_targets(const std::vector<Row>& rows, const Linearity& lin) {
    std::vector<Target> t;
    const Row* base = find(rows, "base");
    const bool nominal = base && base->config.width == 1920 && base->config.height == 1080;
    const std::string base_goal = "kernel / roof <= 1.45 (lavapipe, 1080p, one fp16 channel, PREV_CLIP)";
    if (nominal)
        t.push_back(upper_bound("base ratio", base_goal, base->ratio().median, 1.45, fmt("%.3f", base->ratio().median)));
    else
        t.push_back(absent("base ratio", base_goal, "base at 1920x1080"));

    const Row* three = find(rows, "ch_3x1");
    const std::string three_goal = "three channels' ratio <= one channel's";
    if (base && three)
        t.push_back(upper_bound("three channels", three_goal, three->ratio().median, base->ratio().median,
                                fmt("%.3f vs %.3f", three->ratio().median, base->ratio().median)));
    else
        t.push_back(absent("three channels", three_goal, "base and ch_3x1"));

    for (const char* src : {"src_camera", "src_motion"}) {
        const Row* r = find(rows, src);
        const std::string who = src == std::string("src_camera") ? "CAMERA" : "MOTION";
        const std::string g1 = who + " kernel time <= PREV_CLIP's", g2 = who + " ratio <= PREV_CLIP's + 0.05";
        if (base && r) {
            const double q = paired_ratio(*r, *base);
            t.push_back(upper_bound(who + " time", g1, q, 1.0,
                                    fmt("%.3f of PREV_CLIP's, round by round (medians %.2f vs %.2f ms)", q, r->kernel().median,
                                        base->kernel().median)));
            t.push_back(upper_bound(who + " ratio", g2, r->ratio().median, base->ratio().median + 0.05,
                                    fmt("%.3f vs %.3f + 0.05", r->ratio().median, base->ratio().median)));
        } else {
            t.push_back(absent(who + " time", g1, "base and " + std::string(src)));
            t.push_back(absent(who + " ratio", g2, "base and " + std::string(src)));
        }
    }

    const std::string lin_goal = "kernel time linear in pixels within +-10%, 720p to 4K";
    if (lin.measured && lin.deviation.size() >= 3)
        t.push_back(upper_bound("linearity", lin_goal, lin.max_abs_deviation, 0.10, fmt("max |deviation| %.1f%%", 100.0 * lin.max_abs_deviation)));
    else
        t.push_back(absent("linearity", lin_goal, "at least three of 720p, 1080p, 1440p, 4K"));
    const std::string small_goal = "256x160 <= 2x its linear share";
    if (lin.small_measured)
        t.push_back(upper_bound("small frames", small_goal, lin.small_share, 2.0, fmt("%.2fx its share", lin.small_share)));
    else
        t.push_back(absent("small frames", small_goal, "res_256x160 and the large sizes"));

    const Row* sa = nullptr;
    for (const Row& r : rows)
        if (r.has_standalone) sa = &r;
    const std::string sa_goal = "standalone 1080p round trip <= 1.5x (kernel time + memcpy of its bytes)";
    if (sa && sa->config.width == 1920 && sa->config.height == 1080)
        t.push_back(upper_bound("standalone", sa_goal, sa->round_trip_ratio(), 1.5,
                                fmt("%.2fx: %.1f ms vs (%.1f ms kernel", sa->round_trip_ratio(),
                                    summarize(sa->standalone.frame_ms).median, sa->kernel().median) +
                                    fmt(" + %.1f ms memcpy)", summarize(sa->standalone.memcpy_ms).median)));
    else
        t.push_back(absent("standalone", sa_goal, "the standalone configuration at 1920x1080"));

    // The shading cache (docs/measurements/PERFORMANCE.md, "The shading cache's cost").
    const Row* cache = find(rows, "cache_1x4");
    const std::string cache_goal = "classify + resolve / roof <= 1.6 (1080p, one REUSE rgba16f channel)";
    if (cache && cache->config.width == 1920 && cache->config.height == 1080) {
        std::string measured = fmt("%.3f", cache->ratio().median);
        const Row* fused = find(rows, "cache_1x4_fused");
        const Row* cf = find(rows, "cache_1x4_classify_fused");
        if (fused && cf) {
            const double classify = cf->kernel().median - fused->kernel().median;
            measured += fmt(" (classify ~%.1f ms, resolve ~%.1f ms, ", classify, cache->kernel().median - classify) +
                        fmt("the same channel fused %.1f ms)", fused->kernel().median);
        }
        t.push_back(upper_bound("shading cache", cache_goal, cache->ratio().median, 1.6, measured));
    } else {
        t.push_back(absent("shading cache", cache_goal, "cache_1x4 at 1920x1080"));
    }

    // A row's time against another's, round by round, both at 1080p:
    // "<q> of <label>, round by round (medians ...)" and `extra`.
    auto paired_target = [&](const char* name, const std::string& goal, const Row* row, const Row* against, const char* label, double limit,
                             const std::string& extra, const char* needs) {
        if (!at_1080p(row) || !at_1080p(against)) return t.push_back(absent(name, goal, needs));
        const double q = paired_ratio(*row, *against);
        t.push_back(upper_bound(name, goal, q, limit,
                                fmt("%.3f of ", q) + label +
                                    fmt(", round by round (medians %.2f vs %.2f ms)", row->kernel().median, against->kernel().median) + extra));
    };

    // Splitting the frame in two (classify + resolve) against the fused
    // frame on the same channel, with the share classify lists beside it.
    const Row* fused = find(rows, "cache_1x4_fused");
    paired_target("cache split", "classify + resolve time <= 1.10x the fused frame's (1080p, one REUSE rgba16f channel)", cache, fused,
                  "fused", 1.10, cache ? fmt("; listed %.1f%% of pixels", 100.0 * cache->listed_fraction()) : "",
                  "cache_1x4 and cache_1x4_fused at 1920x1080");

    // The fill at a stated young fraction (docs/measurements/PERFORMANCE.md, "What is
    // timed"): young12_fill against its twin without the fill.
    const Row* young = find(rows, "young12");
    const Row* fill = find(rows, "young12_fill");
    std::string young_text;
    if (fill) young_text = fmt("; young %.1f%% of pixels (%.1f%% of surface)", 100.0 * fill->young_fraction(), 100.0 * fill->young_surface_fraction());
    for (const char* other : {"young12_fill_r1", "young12_fill_r4"}) {
        const Row* r = find(rows, other);
        if (at_1080p(r) && at_1080p(young)) young_text += "; " + std::string(other) + fmt(" %.3f", paired_ratio(*r, *young));
    }
    paired_target("fill (young)", "fill (fill_age 8) time <= 1.20x its twin's without it, ~12% of pixels young (1080p)", fill, young, "young12",
                  1.20, young_text, "young12 and young12_fill at 1920x1080");

    // ADAPTIVE (base's default depth test) against FIXED.
    paired_target("ADAPTIVE", "ADAPTIVE depth test (base) time <= 1.15x FIXED's (depth_fixed), 1080p", base, find(rows, "depth_fixed"),
                  "FIXED's", 1.15, "", "base and depth_fixed at 1920x1080");
    return t;
}

}  // namespace rrc_bench
