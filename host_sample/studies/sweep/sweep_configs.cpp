#include "sweep_configs.h"

#include "scene.h"

#include <cstdio>

namespace rrc_sweep {

std::vector<App> apps_of(uint32_t signals) {
    std::vector<App> a;
    if (signals & rrc_sample::kSignalPcf) a.push_back({rrc_sample::kSignalPcf, "pcf"});
    if (signals & rrc_sample::kSignalEnv) a.push_back({rrc_sample::kSignalEnv, "env"});
    if (signals & rrc_sample::kSignalSoft) a.push_back({rrc_sample::kSignalSoft, "soft"});
    return a;
}

std::vector<RrcRun> rrc_runs(const SweepOptions& o, uint32_t signals) {
    const rrc_sample::ChannelPresets presets;  // the library's (rrc_channel_preset), with their bases
    std::vector<rrc_history_filter> filters = {RRC_HISTORY_FILTER_BILINEAR};
    if (o.catmull_rom) filters.push_back(RRC_HISTORY_FILTER_CATMULL_ROM);
    std::vector<RrcRun> runs;
    for (int k : o.rrc_taps) {
        RrcRun run;
        run.k = k;
        for (const App& app : apps_of(signals)) {
            for (rrc_history_filter f : filters) {
                for (rrc_blend b : {RRC_BLEND_FIXED, RRC_BLEND_AGE_AWARE})
                    for (float lambda : o.lambdas) run.configs.push_back({app, {lambda, b, f, 0}});
                // Soft shadows: the running mean of all samples since the last miss, up to the cap.
                if (app.signal == rrc_sample::kSignalSoft)
                    for (uint32_t cap : o.soft_caps) run.configs.push_back({app, {0.0f, RRC_BLEND_RUNNING_MEAN, f, cap}});
            }
            // The finishing steps (docs/CONVENTIONS.md, "Finishing steps"), on the
            // presets' blend: rectification (pcf, env; gamma 1), the Gaussian
            // history (pcf, the chapter's blur), the spatial fill (soft, T = 8,
            // no fallback; the soft preset row below adds rrc-sample's).
            if (o.finishing)
                for (float lambda : o.lambdas) {
                    rrc_sample::ChannelSettings c{lambda, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0};
                    if (app.signal != rrc_sample::kSignalSoft) {
                        rrc_sample::ChannelSettings r = c;
                        r.rectify = 1;
                        run.configs.push_back({app, r});
                    }
                    if (app.signal == rrc_sample::kSignalPcf) {
                        rrc_sample::ChannelSettings g = c;
                        g.filter = RRC_HISTORY_FILTER_GAUSSIAN;
                        run.configs.push_back({app, g});
                    }
                    if (app.signal == rrc_sample::kSignalSoft) {
                        rrc_sample::ChannelSettings fl = c;
                        fl.age_cap = presets.soft.age_cap;  // the soft preset's cap and fill
                        fl.fill_age = presets.soft.fill_age;
                        run.configs.push_back({app, fl});
                    }
                }
            // The lag detector (docs/CONVENTIONS.md, "The lag detector"), on the presets'
            // blend at the settings docs/measurements/PERFORMANCE.md ("The lag detector (0.5): what it
            // buys, measured") found best: pcf rectified as its preset is, env without;
            // never on soft (a block of nine binary samples agrees by chance, and the
            // detector then drops right histories: worse at every setting tried).
            if (o.antilag)
                for (float lambda : o.lambdas) {
                    if (app.signal == rrc_sample::kSignalSoft) continue;
                    rrc_sample::ChannelSettings a{lambda, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0};
                    a.rectify = app.signal == rrc_sample::kSignalPcf ? 1u : 0u;
                    a.antilag = 1;
                    a.antilag_gamma = kSweepAntilagGamma;
                    a.antilag_threshold = kSweepAntilagThreshold;
                    run.configs.push_back({app, a});
                }
            // The blur bound (docs/CONVENTIONS.md, "The blur bound"), each row the twin of
            // a row without it: pcf the rectified finishing row, env the plain age-aware
            // bilinear row, soft the fill row (age cap 64, T = 8).
            if (o.blur_bound)
                for (float lambda : o.lambdas) {
                    rrc_sample::ChannelSettings b{lambda, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0};
                    if (app.signal == rrc_sample::kSignalPcf) b.rectify = 1;
                    if (app.signal == rrc_sample::kSignalSoft) b.age_cap = 64, b.fill_age = 8;
                    b.blur_bound = kSweepBlurBound;
                    run.configs.push_back({app, b});
                }
            // The view lobe (docs/CONVENTIONS.md, "The view-dependent history"), env only
            // (the one view-dependent signal): each row the twin of the plain age-aware
            // bilinear row.
            if (o.view_lobe && app.signal == rrc_sample::kSignalEnv)
                for (float lambda : o.lambdas) {
                    rrc_sample::ChannelSettings v{lambda, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_BILINEAR, 0};
                    v.view_lobe = kSweepViewLobe;
                    run.configs.push_back({app, v});
                }
            // rrc-sample's pcf and soft presets (testbed/channel_presets.h), which no row above
            // spells: the targets under motion are theirs (docs/measurements/PERFORMANCE.md, "Targets under
            // motion").  pcf's: the residual against kSamplePcfBaseTaps bilinear compares (its
            // base pass is timed with its rrc pass; testbed README.md, "The pcf residual").  soft's: Catmull-Rom, the fill with rrc-sample's PCSS estimate as its
            // prior (the library preset's fill_prior), and the residual against the stable estimate
            // (README.md, "The soft preset rows": its centre-light map and PCSS pass are timed
            // with its rrc pass).  env's preset (the view lobe scaled to the size) is not a row.
            if (o.finishing && app.signal == rrc_sample::kSignalPcf) run.configs.push_back({app, presets.pcf});
            if (o.finishing && app.signal == rrc_sample::kSignalSoft) {
                const rrc_sample::ChannelSettings preset = presets.soft;
                run.configs.push_back({app, preset});
                // The preset with its cure off: the same channel fed the sample itself, the PCSS
                // estimate as the fill's fallback (README.md, "The soft residual").
                rrc_sample::ChannelSettings plain = preset;
                plain.residual = 0;
                if (preset.residual) run.configs.push_back({app, plain});
            }
        }
        runs.push_back(run);
    }
    if (o.rotated && (signals & rrc_sample::kSignalPcf)) {
        RrcRun run;
        run.k = kRotatedBaseTaps;
        run.pattern = 1;
        for (rrc_blend b : {RRC_BLEND_FIXED, RRC_BLEND_AGE_AWARE})
            for (float lambda : o.lambdas)
                run.configs.push_back({{rrc_sample::kSignalPcf, "pcf"}, {lambda, b, RRC_HISTORY_FILTER_BILINEAR, 0}});
        runs.push_back(run);
    }
    return runs;
}

std::vector<BruteConfig> brute_configs(const SweepOptions& o, uint32_t signals) {
    std::vector<BruteConfig> c;
    for (const App& app : apps_of(signals))
        for (int k : o.brute_taps) c.push_back({app, k, 0});
    if (o.rotated && (signals & rrc_sample::kSignalPcf))
        for (int k : {kRotatedBaseTaps, 4 * kRotatedBaseTaps, 16 * kRotatedBaseTaps}) c.push_back({{rrc_sample::kSignalPcf, "pcf"}, k, 1});
    return c;
}

const char* blend_label(rrc_blend b) {
    return b == RRC_BLEND_FIXED ? "fixed" : b == RRC_BLEND_AGE_AWARE ? "age-aware" : "running-mean";
}
const char* filter_label(rrc_history_filter f) {
    return f == RRC_HISTORY_FILTER_BILINEAR      ? "bilinear"
           : f == RRC_HISTORY_FILTER_CATMULL_ROM ? "catmull-rom"
           : f == RRC_HISTORY_FILTER_GAUSSIAN    ? "gaussian"
                                                 : "nearest";
}

std::string filter_label(const rrc_sample::ChannelSettings& c) {
    std::string s = filter_label(c.filter);
    if (c.rectify) s += "+rectify";
    if (c.fill_age) s += "+fill" + std::to_string(c.fill_age);
    if (c.fill_age && c.fill_radius) s += "r" + std::to_string(c.fill_radius);  // a window other than the library's
    if (c.fill_prior > 0.0f) {  // the fill's fallback: rrc-sample's PCSS estimate, worth this many samples
        char b[32];
        std::snprintf(b, sizeof b, "+pcss%g", (double)c.fill_prior);
        s += b;
    }
    if (c.residual) s += "+residual";  // rrc's residual: soft's against the stable PCSS estimate, pcf's against its bilinear compares
    if (c.antilag) s += "+antilag";
    // A detector other than the sweep's own rows' (the pcf preset's narrow box): its gamma_a/T.
    if (c.antilag && (c.antilag_gamma != kSweepAntilagGamma || c.antilag_threshold != kSweepAntilagThreshold)) {
        char b[48];
        std::snprintf(b, sizeof b, "_g%g_t%g", (double)c.antilag_gamma, (double)c.antilag_threshold);
        s += b;
    }
    if (c.blur_bound > 0.0f) {
        char b[32];
        std::snprintf(b, sizeof b, "+blur%g", (double)c.blur_bound);
        s += b;
    }
    if (c.view_lobe > 0.0f) {
        char b[32];
        std::snprintf(b, sizeof b, "+lobe%g", (double)c.view_lobe);
        s += b;
    }
    return s;
}

}  // namespace rrc_sweep
