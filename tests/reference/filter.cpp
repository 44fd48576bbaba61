#include "filter.h"

#include <algorithm>
#include <cfloat>

namespace rrc_ref {

namespace {

double lambda_eff(const ChannelParams& ch, unsigned n_prev) {
    double mean = static_cast<double>(n_prev) / (n_prev + 1.0);  // exact mean weight
    switch (ch.blend) {
        case RRC_BLEND_AGE_AWARE: return std::min(ch.lambda, mean);
        case RRC_BLEND_RUNNING_MEAN: return mean;
        default: return ch.lambda;
    }
}

Update take_sample(const ChannelParams& ch, const Sample& s, unsigned age) {
    Update u;
    for (unsigned c = 0; c < ch.components; ++c) u.out[c] = s.s[c];
    u.age = age;
    u.weight = s.w;
    return u;
}

Update keep_history(const ChannelParams& ch, const Resampled& prev, double weight) {
    Update u;
    for (unsigned c = 0; c < ch.components; ++c) u.out[c] = prev.h[c];
    u.age = prev.age;
    u.weight = weight;
    return u;
}

}  // namespace

Update filter_update(const ChannelParams& ch, PixelCase pc, const Sample& s, const Resampled& prev) {
    if (pc != PixelCase::hit) {
        // background: age 0; miss: age 1.  An invalid sample leaves 0, 0, 0.
        if (!s.valid) return Update{};
        return take_sample(ch, s, pc == PixelCase::miss ? 1u : 0u);
    }
    if (!s.valid) return keep_history(ch, prev, prev.weight);
    if (prev.age == 0) return take_sample(ch, s, 1u);

    double lam = lambda_eff(ch, prev.age);
    const double* h = prev.rectified ? prev.h_rect : prev.h;  // only the blend formula uses the clamped H
    unsigned age = std::min(prev.age + 1u, ch.age_cap);
    // The lag detector, the blur bound, the view lobe and the deviation gate
    // shorten the age of the blend row only (docs/CONVENTIONS.md, "The lag
    // detector", "The blur bound", "The deviation gate"): the smallest age wins.
    unsigned shortened = prev.age;
    if (prev.antilag) shortened = std::min(shortened, prev.age_antilag);
    if (prev.blur_bounded) shortened = std::min(shortened, prev.age_blur);
    if (prev.view_capped) shortened = std::min(shortened, prev.age_view);
    if (prev.gated) shortened = std::min(shortened, prev.age_gate);
    if (shortened < prev.age) {
        const double na = shortened;
        lam = std::min(lam, na / (na + 1.0));
        age = std::min(shortened + 1u, ch.age_cap);
    }
    Update u;
    u.age = age;
    if (!ch.confidence) {
        for (unsigned c = 0; c < ch.components; ++c) u.out[c] = lam * h[c] + (1.0 - lam) * s.s[c];
        return u;
    }
    // Confidence-weighted mean; reduces to the line above when w == W == 1.
    // An accumulated weight under the fp32 normal range counts as none.
    double w_new = lam * prev.weight + (1.0 - lam) * s.w;
    if (w_new < FLT_MIN) return keep_history(ch, prev, 0.0);
    for (unsigned c = 0; c < ch.components; ++c) u.out[c] = (lam * prev.weight * h[c] + (1.0 - lam) * s.w * s.s[c]) / w_new;
    u.weight = w_new;
    return u;
}

}  // namespace rrc_ref
