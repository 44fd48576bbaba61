// The per-channel recursive filter: the table of docs/CONVENTIONS.md
// (background / miss / hit cases, blend modes, age cap, confidence).
#ifndef RRC_REFERENCE_FILTER_H
#define RRC_REFERENCE_FILTER_H

#include "params.h"

namespace rrc_ref {

enum class PixelCase { background, miss, hit };

struct Sample {
    double s[4] = {0, 0, 0, 0};
    double w = 1.0;     // confidence, clamped to [0, 1]; 1 without confidence
    bool valid = true;  // every component (and the confidence) finite
};

// What the hit case reads from the previous frame at uv_prev.
struct Resampled {
    double h[4] = {0, 0, 0, 0};  // history, with the channel's filter
    double weight = 0.0;         // W, same filter (confidence channels)
    unsigned age = 0;            // n_prev, nearest
    // Rectification (finish.h): the clamped H, which only the blend formula
    // uses; every other case keeps h.
    bool rectified = false;
    double h_rect[4] = {0, 0, 0, 0};
    // The lag detector (finish.h): the age n_a the blend row uses in place of
    // `age` (n_a <= age; lambda_eff capped at n_a/(n_a + 1) where n_a < age).
    bool antilag = false;
    unsigned age_antilag = 0;
    // The blur bound (finish.h): the age cap N; the blend row uses min(n_a, N)
    // the same way (docs/CONVENTIONS.md, "The blur bound").
    bool blur_bounded = false;
    unsigned age_blur = 0;
    // The view lobe (view_lobe.h): the cap n_v, the same way
    // (docs/CONVENTIONS.md, "The view-dependent history").
    bool view_capped = false;
    unsigned age_view = 0;
    // The deviation gate (gate.h): the cap N_g, the same way
    // (docs/CONVENTIONS.md, "The deviation gate").
    bool gated = false;
    unsigned age_gate = 0;
};

struct Update {
    double out[4] = {0, 0, 0, 0};  // before any fp16 rounding
    unsigned age = 0;
    double weight = 0.0;  // W' (confidence channels)
};

// `prev` is read only for PixelCase::hit.
Update filter_update(const ChannelParams& ch, PixelCase pc, const Sample& s, const Resampled& prev);

}  // namespace rrc_ref

#endif
