#include "metrics.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rrc_sample {

std::string fmt(const char* format, double value) {
    char b[64];
    std::snprintf(b, sizeof b, format, value);
    return b;
}

HitStats hit_stats(const std::vector<uint8_t>& mask) {
    HitStats s;
    for (uint8_t m : mask) {
        if (m & RRC_MASK_BACKGROUND)
            ++s.background;
        else if (m & RRC_MASK_HIT)
            ++s.hits;
        else
            ++s.misses;
        if (m & RRC_MASK_REFRESHED) ++s.refreshed;
    }
    return s;
}

ErrorStats error_against(const std::vector<float>& v, const std::vector<float>& ref, int components, int compare,
                         const std::vector<uint8_t>& valid) {
    ErrorStats e;
    double sum = 0.0;
    for (size_t i = 0; i < valid.size(); ++i) {
        if (!valid[i]) continue;
        for (int c = 0; c < compare; ++c) {
            const double d = (double)v[i * components + c] - (double)ref[i * components + c];
            sum += d * d;
        }
        ++e.pixels;
    }
    if (!e.pixels) return e;
    const double mse = sum / (double)(e.pixels * (uint64_t)compare);
    e.rmse = std::sqrt(mse);
    e.psnr = mse > 0.0 ? -10.0 * std::log10(mse) : 99.0;
    return e;
}

std::vector<SignalErrors> frame_errors(const FrameOutput& f) {
    std::vector<SignalErrors> out;
    if (!f.checkpoint) return out;
    const size_t n = f.mask.size();
    std::vector<uint8_t> surface(n), hits(n);
    for (size_t i = 0; i < n; ++i) {
        surface[i] = !(f.mask[i] & RRC_MASK_BACKGROUND);
        hits[i] = (f.mask[i] & RRC_MASK_HIT) != 0;
    }
    auto add = [&](const char* name, const SignalData& s, const std::vector<uint8_t>& valid, int compare) {
        if (s.reference.empty()) return;
        SignalErrors e;
        e.signal = name;
        e.raw = error_against(s.raw, s.reference, s.components, compare, valid);
        e.accumulated = error_against(s.accumulated, s.reference, s.components, compare, valid);
        if (!s.brute_force.empty()) e.brute_force = error_against(s.brute_force, s.reference, s.components, compare, valid);
        std::vector<uint8_t> valid_hits(n);
        for (size_t i = 0; i < n; ++i) valid_hits[i] = valid[i] && hits[i];
        e.raw_hits = error_against(s.raw, s.reference, s.components, compare, valid_hits);
        e.accumulated_hits = error_against(s.accumulated, s.reference, s.components, compare, valid_hits);
        if (!s.shown.empty()) {
            e.shown = error_against(s.shown, s.reference, 1, 1, valid);
            e.fallback = error_against(s.pcss, s.reference, 1, 1, valid);
        }
        if (!s.base.empty()) e.fallback = error_against(s.base, s.reference, s.components, compare, valid);
        out.push_back(e);
    };
    add("pcf", f.pcf, surface, 1);
    if (!f.env.reference.empty()) {
        std::vector<uint8_t> sphere(n);  // the env signal lives on the mirror sphere (alpha 1)
        for (size_t i = 0; i < n; ++i) sphere[i] = f.env.raw[i * 4 + 3] > 0.5f;
        add("env", f.env, sphere, 3);
    }
    add("soft", f.soft, surface, 1);
    return out;
}

}  // namespace rrc_sample
