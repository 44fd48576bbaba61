#include "cache_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rrc_cache {
namespace {

std::string fmt(const char* format, double a, double b = 0, double c = 0) {
    char s[256];
    std::snprintf(s, sizeof s, format, a, b, c);
    return s;
}

bool single_frame_cache(const CacheConfig& c) { return c.cache && !c.stereo && c.subframes <= 1; }

}  // namespace

std::vector<CostPoint> cost_curve(const std::vector<Figures>& fs) {
    std::vector<CostPoint> out;
    for (const Figures& f : fs) {
        const CacheConfig& c = f.config;
        if (!single_frame_cache(c) || c.policy != RRC_REFRESH_TILED || c.period != kCostPeriod || c.lifetime) continue;
        if (std::any_of(out.begin(), out.end(), [&](const CostPoint& p) { return p.octaves == c.octaves; })) continue;
        CostPoint p;
        p.octaves = c.octaves, p.run = f.name, p.shade_ms = f.full_shade_ms, p.full_ms = f.full_ms, p.speedup = f.speedup;
        p.bound = f.bound, p.of_bound = f.of_bound, p.c = f.c, p.shaded_fraction = f.shaded_fraction, p.rmse = f.rmse;
        out.push_back(p);
    }
    std::sort(out.begin(), out.end(), [](const CostPoint& a, const CostPoint& b) { return a.octaves < b.octaves; });
    return out;
}

BreakEven break_even(const std::vector<CostPoint>& curve) {
    BreakEven b;
    if (curve.empty()) return b;
    for (size_t i = 0; i < curve.size(); ++i) {
        if (curve[i].speedup < 1.0) continue;
        if (i == 0) {
            b.kind = BreakEven::kAtOrBelow, b.octaves = curve[0].octaves, b.shade_ms = curve[0].shade_ms;
            return b;
        }
        const CostPoint &lo = curve[i - 1], &hi = curve[i];
        const double t = (1.0 - lo.speedup) / (hi.speedup - lo.speedup);  // lo < 1 <= hi: t in (0, 1]
        b.kind = BreakEven::kBetween;
        b.octaves = lo.octaves + t * ((double)hi.octaves - lo.octaves);
        b.shade_ms = lo.shade_ms + t * (hi.shade_ms - lo.shade_ms);
        return b;
    }
    b.kind = BreakEven::kNotReached;
    return b;
}

std::vector<Verdict> verdicts(const std::vector<Figures>& fs, const Settings& s) {
    std::vector<Verdict> out;
    const bool target_size = s.width == kTargetWidth && s.height == kTargetHeight;
    const std::string size_note =
        target_size ? "" : fmt("; measured at %.0fx%.0f, the target is stated at ", s.width, s.height) + fmt("%.0fx%.0f", kTargetWidth, kTargetHeight);

    {  // classify + resolve over the full frame, 8 octaves: the worst cached run, and TILED n = 4's
        Verdict v;
        v.target = fmt("classify + resolve <= %.2f of the full frame (640x360, 8 octaves)", kTargetCacheShare);
        const Figures* worst = nullptr;
        const Figures* tiled4 = nullptr;
        for (const Figures& f : fs) {
            if (!f.config.cache || f.config.octaves != kDefaultOctaves || f.full_ms <= 0) continue;
            if (!worst || f.c > worst->c) worst = &f;
            if (!tiled4 && single_frame_cache(f.config) && f.config.policy == RRC_REFRESH_TILED && f.config.period == kCostPeriod &&
                !f.config.lifetime)
                tiled4 = &f;
        }
        if (!worst) {
            v.measured = "-";
            v.verdict = "not measured (no cached run at 8 octaves)";
        } else {
            v.measured = fmt("worst %.3f", worst->c) + " (" + worst->name + ")" + (tiled4 ? fmt("; tiled_4 %.3f", tiled4->c) : "");
            v.met = worst->c <= kTargetCacheShare;
            v.verdict = v.met ? "met" : fmt("missed by %.3f (%.2fx the target)", worst->c - kTargetCacheShare, worst->c / kTargetCacheShare);
            v.verdict += size_note;
        }
        out.push_back(v);
    }
    {  // the break-even shader at TILED n = 4
        Verdict v;
        v.target = fmt("break-even shader at TILED n = 4 <= %.0f octaves", kTargetBreakEvenOctaves);
        const std::vector<CostPoint> curve = cost_curve(fs);
        const BreakEven b = break_even(curve);
        switch (b.kind) {
            case BreakEven::kUnmeasured:
                v.measured = "-";
                v.verdict = "not measured (no TILED n = 4 run)";
                break;
            case BreakEven::kAtOrBelow:
                v.measured = fmt("<= %.0f octaves (speed-up %.2f there)", b.octaves, curve.front().speedup);
                v.met = b.octaves <= kTargetBreakEvenOctaves;
                v.verdict = v.met ? "met" : fmt("not measured below %.0f octaves (--octaves)", b.octaves);
                break;
            case BreakEven::kBetween:
                v.measured = fmt("%.1f octaves (%.1f ms of full shading a frame)", b.octaves, b.shade_ms);
                v.met = b.octaves <= kTargetBreakEvenOctaves;
                v.verdict = v.met ? "met" : fmt("missed by %.1f octaves (%.2fx the target)", b.octaves - kTargetBreakEvenOctaves,
                                                b.octaves / kTargetBreakEvenOctaves);
                break;
            case BreakEven::kNotReached: {
                const CostPoint& top = curve.back();
                v.measured = fmt("not reached: speed-up %.2f at %.0f octaves, the dearest measured", top.speedup, top.octaves);
                v.verdict = fmt("missed: the speed-up stays %.2f short of 1 at %.0f octaves", 1.0 - top.speedup, top.octaves);
                if (curve.size() < 2) v.verdict += " (one octave count measured: --octaves 8,16,32,64)";
                break;
            }
        }
        v.verdict += size_note;
        out.push_back(v);
    }
    {  // speed-up / bound in every cached run
        Verdict v;
        v.target = fmt("speed-up >= %.2f x the Amdahl bound in every cached run", kTargetOfBound);
        const Figures* worst = nullptr;
        int runs = 0;
        for (const Figures& f : fs) {
            if (!f.config.cache || f.of_bound <= 0) continue;  // 0: not measured
            ++runs;
            if (!worst || f.of_bound < worst->of_bound) worst = &f;
        }
        if (!worst) {
            v.measured = "-";
            v.verdict = "not measured";
        } else {
            v.measured = fmt("worst %.2f", worst->of_bound) + " (" + worst->name + fmt(", of %.0f runs)", runs);
            v.met = worst->of_bound >= kTargetOfBound;
            v.verdict = v.met ? "met" : fmt("missed by %.2f", kTargetOfBound - worst->of_bound);
        }
        out.push_back(v);
    }
    return out;
}

}  // namespace rrc_cache
