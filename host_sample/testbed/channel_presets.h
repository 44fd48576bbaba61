// The sample's rrc channel settings, one per application: what the command
// line sets (--lambda, --blend, --history-filter, --soft-age-cap) and what
// rrc_stage.cpp turns into rrc_channel_desc.
#pragma once

#include <rrc/rrc.h>

#include "shaders/signal_modes.h"

namespace rrc_sample {

/** One signal's rrc channel (include/rrc/rrc.h, rrc_channel_desc). */
struct ChannelSettings {
    float lambda = 0.6f;
    rrc_blend blend = RRC_BLEND_FIXED;
    rrc_history_filter filter = RRC_HISTORY_FILTER_BILINEAR;
    uint32_t age_cap = 0;  // 0: the library's default
    // 0.4 finishing steps (docs/CONVENTIONS.md, "Finishing steps"); zero = off / the library's default.
    uint32_t confidence = 0;          // the signal pass writes a per-sample confidence
    uint32_t rectify = 0;             // history rectification
    float rectify_gamma = 0.0f;
    float blur_sigma = 0.0f;          // RRC_HISTORY_FILTER_GAUSSIAN
    uint32_t fill_age = 0;            // the spatial fill for pixels younger than this
    uint32_t fill_radius = 0;
    float fill_depth_tolerance = 0.0f;
    float fill_prior = 0.0f;          // the fallback's weight in samples (needs a fallback image)
    // 0.5 the lag detector (docs/CONVENTIONS.md, "The lag detector"); zero = off / the library's default.
    uint32_t antilag = 0;
    float antilag_gamma = 0.0f;
    float antilag_threshold = 0.0f;
    // 0.6 the blur bound (docs/CONVENTIONS.md, "The blur bound"), px^2; 0 = off.
    float blur_bound = 0.0f;
    // 0.7 the view-dependent history (docs/CONVENTIONS.md, "The view-dependent history"), radians; 0 = off.
    float view_lobe = 0.0f;
    // 0.9 the residual (docs/CONVENTIONS.md, "The residual"): the channel accumulates the sample
    // less the fallback image, its base, and shows the result plus the base.  The sample's bases:
    // soft's stable PCSS estimate (README.md, "The soft residual"), which is then also the fill's
    // prior; pcf's kSamplePcfBaseTaps bilinear compares (README.md, "The pcf residual"); env's
    // filtered reflections (kSampleEnvBase; README.md, "The env residual").
    uint32_t residual = 0;
};

/** The env residual's base the preset takes (rrc-sample's --env-residual default, `filtered`;
 *  README.md, "The env residual"). */
constexpr uint32_t kSampleEnvBase = SAMPLE_ENV_BASE_FILTERED;

/** env's view lobe before the env residual (2026-12-05; now --env-view-lobe-px's value in the
 *  rectification study's rows, not a preset's) (docs/CONVENTIONS.md, "The view-dependent
 *  history"), in pixels of the camera's vertical angle: alpha = kEnvViewLobePixels * fov_y / height radians (0.0245 at
 *  1024x640, 0.098 at 256x160).  A bump-mapped mirror's signal at a pixel averages the
 *  reflection over the pixel's footprint, so its angular width scales with the footprint: at
 *  1024x640 the lobe caps the sphere's history at age 1 (the camera turns the view to its
 *  points by 0.012-0.022 rad a frame), at 256x160 at 4 to 7, which changes nothing at lambda
 *  0.8.  Measured
 *  in docs/PERFORMANCE.md, "The view lobe in the kernel (0.7), measured". */
constexpr float kEnvViewLobePixels = 18.0f;

/** The env preset's view lobe (docs/CONVENTIONS.md, "The view-dependent history"), in radians of
 *  the view's or the lighting's turn, the same at every size: with the residual the history holds
 *  only the filtered base's error, which moves with the reflection as the lighting turns, so a
 *  lighting that turned by phi a frame leaves it good for about 0.08 / phi frames.  At the
 *  rectification study's 1 degree a frame the age is capped at 4 (lambda 0.9 -> 0.8): the moving
 *  light's lag bias^2 0.48x the preset without its cures, against 0.68x for the residual alone
 *  (README.md, "The env residual's view lobe"); under the sample's moving camera (0.012-0.022 rad a
 *  frame on the sphere) it caps at 3 to 6, which costs 0.0437 against 0.0429 at 256x160 and
 *  0.0311 against 0.0310 at 1024x640.  A lobe in pixels (as kEnvViewLobePixels) would cap the
 *  history at age 1 at 1024x640, where the base carries the view at the pixel's scale. */
constexpr float kEnvResidualViewLobe = 0.08f;
/** The bilinear shadow compares of pcf's residual base (rrc-sample's --pcf-residual default;
 *  README.md, "The pcf residual"): as many as the per-frame signal's k = 4 taps, so that on a
 *  GPU, whose filtered depth-compare sampler returns a bilinear compare in one fetch, the frame
 *  fetches 8 times against brute force's 16 (16 + 4 texel reads here, the sample's shader
 *  reading each texel).  At 256x160: 3 compares 0.0311, 5 0.0262, 8 0.0204, against 0.0259;
 *  with 8 the base alone (0.0190) already beats the 16-tap brute force (0.0265), so more
 *  compares buy a better estimator, not a better history. */
constexpr uint32_t kSamplePcfBaseTaps = 4;

/** The PCSS fallback's weight in soft's fill, in samples (rrc_channel_desc.fill_prior): rrc-sample's
 *  --fill-prior default, and the sweep's soft preset row's (host_sample/studies/sweep/README.md). */
constexpr float kSampleFillPrior = 4.0f;

/** rrc-sample's B where --blur-bound names a channel without --blur-bound-px2: the best of
 *  docs/PERFORMANCE.md, "The blur bound: what it buys, measured" (pcf bilinear and soft, 256x160). */
constexpr float kSampleBlurBound = 0.5f;

/** The sample's presets, one per application, chosen at the sample's own k (4 taps for pcf
 *  and env, one light point for soft) on its default moving-camera scene: the lowest RMSE
 *  against the fixed target (docs/PERFORMANCE.md, "Presets chosen from the fronts", where
 *  each value's figure is), a cure or finishing step only where it wins at 256x160 and at
 *  1024x640 (rrc-sample's accumulated RMSE, mean over seeds 0..3).  pcf: lambda 0.9, the
 *  residual against kSamplePcfBaseTaps bilinear compares (README.md, "The pcf residual"), the
 *  spatial fill below age 4 in the library's 5x5 window, a bilinear history, no lag detector,
 *  no blur bound, not rectified: 0.0259 at 256x160 and 0.0196 at 1024x640 (the same section),
 *  against 0.0338 and 0.0212 for the pcf preset before 2026-12-05 (no residual; the lag
 *  detector with a narrow box, gamma_a 0.25 and T 0.25; B = 0.25 px^2; a 3x3 window below 320
 *  rows),
 *  which with the residual drop right histories (the detector's box is the residual's, narrow:
 *  0.0320 with it at 256x160) or cost variance the residual no longer needs (the bound: 0.0285),
 *  and 0.0387 and 0.0242 for 0.5's (Catmull-Rom, rectified).
 *  soft with the spatial fill (the sample
 *  passes its PCSS estimate as the fallback, --fill-prior); the lag detector makes soft
 *  worse and changes nothing on env, which stay without.  AGE_AWARE everywhere: the same as
 *  FIXED on old pixels, the running mean on new ones.  The blur bound (0.6) wins at both sizes
 *  together with the fill (docs/PERFORMANCE.md, "The blur bound: what it buys, measured"; it
 *  never acts on Catmull-Rom): soft with B = 0.5 px^2 (0.0572 against 0.0606, 0.0577
 *  against 0.0595).  Since 0.8's sample soft accumulates the residual against the stable
 *  PCSS estimate (ChannelSettings::residual, README.md "The soft residual"), which takes
 *  away most of its lag, and with it a longer history, lambda 0.9 and B = 1 px^2 (0.0488 at
 *  256x160 and 0.0456 at 1024x640, against 0.0572 and 0.0577; docs/PERFORMANCE.md, "The soft
 *  residual: what it buys, measured"); since 0.9's sample, when the residual is rrc's own
 *  option, with a Catmull-Rom history, which the residual's smoother input lets win at both
 *  sizes (0.0471 and 0.0435; the blur bound never acts on it, so B is 0), and lambda 0.95,
 *  which wins by a little at both (0.0467 and 0.0429; docs/PERFORMANCE.md, "Catmull-Rom with
 *  the residual").  env (since 2026-12-05) with lambda 0.9, the residual against its filtered
 *  base (kSampleEnvBase: four reflections into the environment box-filtered over their
 *  footprints; README.md, "The env residual"), and the spatial fill below age 2:
 *  0.0429 at 256x160 and 0.0310 at 1024x640, against 0.0435 and 0.0486 for the env preset before
 *  it (lambda 0.8, the view lobe of kEnvViewLobePixels, the fill below age 2, no residual).  The
 *  base is this frame's view of the reflection, so the history holds only the base's error and
 *  the lobe of kEnvViewLobePixels, which cut the history to age 1 on the sphere at 1024x640,
 *  costs more than it buys (0.0422 with it); since 2026-12-05 16:00 UTC with the wider lobe of
 *  kEnvResidualViewLobe radians, which halves the lag behind a turning environment for 0.0437 and
 *  0.0311. */
struct ChannelPresets {
    ChannelSettings pcf{0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, /*confidence*/ 0, /*rectify*/ 0,
                        /*rectify_gamma*/ 0.0f, /*blur_sigma*/ 0.0f, /*fill_age*/ 4, /*fill_radius*/ 0,
                        /*fill_depth_tolerance*/ 0.0f, /*fill_prior*/ 0.0f, /*antilag*/ 0, /*antilag_gamma*/ 0.0f,
                        /*antilag_threshold*/ 0.0f, /*blur_bound*/ 0.0f, /*view_lobe*/ 0.0f, /*residual*/ 1};
    ChannelSettings env{0.9f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0, /*confidence*/ 0, /*rectify*/ 0,
                        /*rectify_gamma*/ 0.0f, /*blur_sigma*/ 0.0f, /*fill_age*/ 2, /*fill_radius*/ 0,
                        /*fill_depth_tolerance*/ 0.0f, /*fill_prior*/ 0.0f, /*antilag*/ 0, /*antilag_gamma*/ 0.0f,
                        /*antilag_threshold*/ 0.0f, /*blur_bound*/ 0.0f, /*view_lobe*/ kEnvResidualViewLobe, /*residual*/ 1};
    ChannelSettings soft{0.95f, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM, 64, /*confidence*/ 0, /*rectify*/ 0,
                         /*rectify_gamma*/ 0.0f, /*blur_sigma*/ 0.0f, /*fill_age*/ 8, /*fill_radius*/ 0,
                         /*fill_depth_tolerance*/ 0.0f, /*fill_prior*/ 0.0f, /*antilag*/ 0, /*antilag_gamma*/ 0.0f,
                         /*antilag_threshold*/ 0.0f, /*blur_bound*/ 0.0f, /*view_lobe*/ 0.0f, /*residual*/ 1};
};

}  // namespace rrc_sample
