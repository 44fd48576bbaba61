// One frame of the reference: classify each pixel, run the hit test, update
// every channel, and collect the diagnostics tests need.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cache.h"
#include "fetch.h"
#include "filter.h"
#include "finish.h"
#include "gate.h"
#include "hit_test.h"
#include "params.h"
#include "reproject.h"
#include "rrc_reference.h"
#include "view_lobe.h"

namespace rrc_ref {

namespace {

Sample read_sample(const ChannelParams& ch, const rrc_channel_input& in, size_t pixel) {
    Sample s;
    for (unsigned c = 0; c < ch.components; ++c) {
        s.s[c] = in.samples[pixel * ch.components + c];
        s.valid = s.valid && std::isfinite(s.s[c]);
    }
    if (ch.confidence) {
        double w = in.confidence[pixel];
        s.valid = s.valid && std::isfinite(w);
        s.w = std::fmin(std::fmax(w, 0.0), 1.0);
        if (s.w < FLT_MIN) s.w = 0.0;  // CONVENTIONS: weights under the fp32 normal range are 0
    }
    return s;
}

Resampled read_previous(const ChannelParams& ch, const ChannelHistory& h, int width, int height, const HitTest& t) {
    Resampled r;
    resample(Image{h.history.data(), width, height, ch.components}, ch.filter, t.qx.v, t.qy.v, r.h, ch.blur_g);
    if (ch.confidence) resample(Image{h.weight.data(), width, height, 1}, ch.filter, t.qx.v, t.qy.v, &r.weight, ch.blur_g);
    int x = nearest_index(t.qx.v, width), y = nearest_index(t.qy.v, height);
    r.age = h.age[static_cast<size_t>(y) * width + x];
    return r;
}

// The kernel's nearest texel may differ when q is within its error of a texel edge.
bool near_edge(const Bounded& q, int size, double scale) {
    double d = q.err * scale;
    if (!std::isfinite(d)) return true;
    return nearest_index(q.v - d, size) != nearest_index(q.v + d, size);
}

FrameResult allocate(const Params& p) {
    size_t n = static_cast<size_t>(p.width) * p.height;
    FrameResult r;
    r.mask.assign(n, 0);
    r.near_threshold.assign(n, 0);
    r.near_nearest_edge.assign(n, 0);
    for (auto* v : {&r.diff, &r.eps, &r.diff_err, &r.expected, &r.fetched, &r.uv_prev_x, &r.uv_prev_y}) v->assign(n, NAN);
    for (const ChannelParams& ch : p.channels) {
        ChannelResult c;
        c.out.assign(n * ch.components, 0.0);
        c.exact.assign(n * ch.components, 0.0);
        c.age.assign(n, 0);
        if (ch.confidence) c.weight.assign(n, 0.0);
        c.rectify_err.assign(n * ch.components, 0.0);
        c.rectified.assign(n, 0);
        c.antilag_age.assign(n, 0);
        c.antilag_uncertain.assign(n, 0);
        c.antilag_c.assign(n, 1.0);
        c.blur_age.assign(n, RRC_MAX_AGE_CAP);
        c.blur_uncertain.assign(n, 0);
        c.blur_capped.assign(n, 0);
        c.blur_b.assign(n, 0.0);
        c.view_age.assign(n, RRC_MAX_AGE_CAP);
        c.view_capped.assign(n, 0);
        c.view_uncertain.assign(n, 0);
        c.view_theta.assign(n, 0.0);
        for (auto* v : {&c.gate_beta, &c.gate_sq, &c.gate_beta_err, &c.gate_sq_err, &c.gate_d}) v->assign(n, 0.0);
        c.gate_age.assign(n, RRC_MAX_AGE_CAP);
        c.gate_capped.assign(n, 0);
        c.gate_uncertain.assign(n, 0);
        c.gate_age_lo.assign(n, 0);
        c.gate_age_hi.assign(n, 0);
        r.channels.push_back(std::move(c));
    }
    return r;
}

// The reference reads raw arrays: refuse inputs whose sizes it can check.
void check_inputs(const Params& p, const PreviousFrame& prev, const rrc_frame_desc& frame) {
    const size_t n = static_cast<size_t>(p.width) * p.height;
    auto require = [](bool ok, const char* what) {
        if (!ok) throw std::invalid_argument(std::string("rrc_ref::run_frame: ") + what);
    };
    require(frame.depth != nullptr, "frame.depth is NULL");
    require(frame.channel_count == p.channels.size() && frame.channels, "frame channels");
    require(p.source == RRC_REPROJECTION_CAMERA || frame.reprojection, "frame.reprojection is NULL");
    require(!p.nocache || frame.nocache, "frame.nocache is NULL");
    require(!p.object_id || frame.object_id, "frame.object_id is NULL");
    for (size_t c = 0; c < p.channels.size(); ++c) {
        require(frame.channels[c].samples != nullptr, "channel samples are NULL");
        require(!p.channels[c].confidence || frame.channels[c].confidence, "confidence is NULL");
        require(!((p.channels[c].fill_age > 0 && p.channels[c].fill_prior > 0.0) || p.channels[c].residual) || frame.channels[c].fallback,
                "fallback is NULL");
    }
    if (!prev.valid) return;
    require(prev.depth.size() == n, "previous depth size");
    require(!p.object_id || prev.object_id.size() == n, "previous object id size");
    require(prev.channels.size() == p.channels.size(), "previous channel count");
    for (size_t c = 0; c < p.channels.size(); ++c) {
        const ChannelHistory& h = prev.channels[c];
        require(h.history.size() == n * p.channels[c].components, "previous history size");
        require(h.age.size() == n, "previous age size");
        require(!p.channels[c].confidence || h.weight.size() == n, "previous weight size");
        for (const auto* v : {&h.gate_beta, &h.gate_sq, &h.gate_beta_err, &h.gate_sq_err})
            require(v->empty() || v->size() == n, "previous gate state size");
        require(h.gate_beta.empty() == h.gate_sq.empty(), "previous gate state: beta and varsigma");
    }
}

void count(FrameResult& r) {
    for (uint8_t m : r.mask) {
        if (m & RRC_MASK_BACKGROUND)
            ++r.stats.background;
        else if (m & RRC_MASK_HIT)
            ++r.stats.hits;
        else if (m & RRC_MASK_REFRESHED)
            ++r.refreshed;
        else
            ++r.stats.misses;
        if (m & RRC_MASK_INVALID_SAMPLE) ++r.stats.invalid_samples;
        if (m & RRC_MASK_INVALID_GEOMETRY) ++r.stats.invalid_geometry;
    }
}

// docs/CONVENTIONS.md "The shading cache": a pixel that passed the hit test
// is refreshed when the policy picks it, when a REUSE value reached the
// maximum lifetime, or when a REUSE history is empty there.
bool refreshed(const Params& p, const PreviousFrame& prev, const rrc_frame_desc& frame, int i, int j, const HitTest& t) {
    if (!p.has_reuse()) return false;
    const int x = nearest_index(t.qx.v, p.width), y = nearest_index(t.qy.v, p.height);
    unsigned amin = ~0u, amax = 0;
    for (size_t c = 0; c < p.channels.size(); ++c) {
        if (p.channels[c].blend != RRC_BLEND_REUSE) continue;
        const unsigned a = prev.channels[c].age[(size_t)y * p.width + x];
        amin = std::min(amin, a);
        amax = std::max(amax, a);
    }
    return refresh_due(p, i, j, frame.frame_index) || amin == 0 || (p.max_lifetime > 0 && amax >= p.max_lifetime);
}

// The deviation gate on a hit (docs/CONVENTIONS.md, "The deviation gate"):
// the previous state at the bilinear taps; on the blend row the update and
// the cap N_g (r.gated), composed with the other caps by filter_update.
void apply_gate(const ChannelParams& ch, const ChannelHistory& h, int width, int height, const HitTest& t, const Sample& s, double scale,
                Resampled& r, ChannelResult& out, size_t px) {
    const double q_err = std::max(t.qx.err, t.qy.err) * scale;
    const GateState prev = gate_previous(h.gate_beta, h.gate_sq, h.gate_beta_err, h.gate_sq_err, width, height, t.qx.v, t.qy.v, q_err);
    GateState stored;
    if (!s.valid) {
        stored = prev;  // the history is kept, and so is the state
    } else if (r.age >= 1) {
        double h_err[4] = {0, 0, 0, 0};
        resample_error(Image{h.history.data(), width, height, ch.components}, t.qx.v, t.qy.v, q_err, h_err);
        const Deviation dv = gate_deviation(ch.components, s.s, r.h, h_err);  // H before rectification
        const Gate g = gate_update(ch.gate_kappa, prev, dv, r.age, scale);
        stored = g.state;
        r.gated = true;
        r.age_gate = g.age;
        out.gate_age[px] = static_cast<uint16_t>(std::min<unsigned>(g.age, RRC_MAX_AGE_CAP));
        out.gate_capped[px] = g.age < r.age;
        out.gate_d[px] = dv.d;
        // The stored age min(n', cap) + 1 may differ where N_g is uncertain.
        unsigned other = r.age;
        if (r.antilag) other = std::min(other, r.age_antilag);
        if (r.blur_bounded) other = std::min(other, r.age_blur);
        if (r.view_capped) other = std::min(other, r.age_view);
        out.gate_uncertain[px] = std::min(other, g.age_lo) != std::min(other, g.age_hi);
        // The stored age for a cap N (as filter_update stores it); it grows with N.
        const auto stored_age = [&](unsigned cap) {
            const unsigned shortened = std::min(other, cap);
            return std::min((shortened < r.age ? shortened : r.age) + 1u, ch.age_cap);
        };
        out.gate_age_lo[px] = static_cast<uint16_t>(stored_age(g.age_lo));
        out.gate_age_hi[px] = static_cast<uint16_t>(stored_age(g.age_hi));
    }
    stored = gate_stored(stored);  // as the kernel stores it: fp16 (beta, sqrt(varsigma))
    out.gate_beta[px] = stored.beta;
    out.gate_sq[px] = stored.sq;
    out.gate_beta_err[px] = stored.beta_err;
    out.gate_sq_err[px] = stored.sq_err;
}

}  // namespace

FrameResult run_frame(const rrc_context_desc& ctx, const PreviousFrame& prev, const rrc_frame_desc& frame, const Options& options) {
    const Params p = resolve(ctx);
    check_inputs(p, prev, frame);
    const double scale = options.error_scale;
    const bool prev_valid = prev.valid && !frame.reset;
    const Camera cam = p.source == RRC_REPROJECTION_CAMERA ? make_camera(frame) : Camera{};
    FrameResult res = allocate(p);

    // The residual (docs/CONVENTIONS.md, "The residual"): a channel's samples
    // are s - b, formed in fp32 as the kernel forms them (one correctly
    // rounded subtraction: exact in double, then rounded), so every use of the
    // sample (the filter, the rectification and lag-detector boxes) reads the
    // residual.  A b that is not finite makes a sample that is not.
    const size_t n = static_cast<size_t>(p.width) * p.height;
    std::vector<rrc_channel_input> inputs(frame.channels, frame.channels + p.channels.size());
    std::vector<std::vector<float>> residuals(p.channels.size());
    for (size_t c = 0; c < p.channels.size(); ++c) {
        if (!p.channels[c].residual) continue;
        const size_t m = n * p.channels[c].components;
        residuals[c].resize(m);
        for (size_t e = 0; e < m; ++e)
            residuals[c][e] = static_cast<float>(static_cast<double>(frame.channels[c].samples[e]) - frame.channels[c].fallback[e]);
        inputs[c].samples = residuals[c].data();
    }

    for (int j = 0; j < p.height; ++j) {
        for (int i = 0; i < p.width; ++i) {
            const size_t px = static_cast<size_t>(j) * p.width + i;
            const double d = frame.depth[px];
            uint8_t mask = 0;
            PixelCase pc = PixelCase::miss;
            HitTest t;
            if (is_invalid_depth(p, d)) {
                mask |= RRC_MASK_INVALID_GEOMETRY;
            } else if (is_background(p, d)) {
                mask |= RRC_MASK_BACKGROUND;
                pc = PixelCase::background;
            } else if (!reprojection_data_finite(p, frame, px)) {
                mask |= RRC_MASK_INVALID_GEOMETRY;
            } else {
                Reprojected r = reproject(p, frame, cam, i, j, d);
                res.uv_prev_x[px] = r.uv_x.v;
                res.uv_prev_y[px] = r.uv_y.v;
                res.expected[px] = r.e.v;
                bool cacheable = !(p.nocache && frame.nocache[px]);
                if (prev_valid && cacheable) {
                    const CurrentPixel cur{frame.depth, i, j, frame.object_id, &prev.object_id};
                    t = hit_test(p, prev.depth, frame.prev_jitter, r, cur, scale);
                    res.near_threshold[px] = !t.hit.sure;
                    res.diff[px] = t.diff;
                    res.eps[px] = t.eps;
                    res.diff_err[px] = t.diff_err;
                    res.fetched[px] = t.fetched;
                    bool may_hit = t.hit.value || !t.hit.sure;
                    res.near_nearest_edge[px] = may_hit && (near_edge(t.qx, p.width, scale) || near_edge(t.qy, p.height, scale));
                    if (t.hit.value) {
                        pc = PixelCase::hit;  // the hit test passed: accumulating channels take it as a hit
                        mask |= refreshed(p, prev, frame, i, j, t) ? RRC_MASK_REFRESHED : RRC_MASK_HIT;
                    }
                }
            }

            for (size_t c = 0; c < p.channels.size(); ++c) {
                const ChannelParams& ch = p.channels[c];
                Sample s = read_sample(ch, inputs[c], px);
                Resampled r;
                if (pc == PixelCase::hit) r = read_previous(ch, prev.channels[c], p.width, p.height, t);
                Update u;
                if (ch.blend == RRC_BLEND_REUSE && (mask & RRC_MASK_HIT)) {
                    // A REUSE hit keeps the resampled cached value; its sample is not read.
                    for (unsigned k = 0; k < ch.components; ++k) u.out[k] = r.h[k];
                    u.age = std::min(r.age + 1u, ch.age_cap);
                } else {
                    if (!s.valid) mask |= RRC_MASK_INVALID_SAMPLE;
                    // Rectification: only where the table blends (a hit, a valid
                    // sample, a non-empty history), and only the blend formula uses
                    // the clamped H (W' underflowing keeps the resampled H).
                    if (ch.rectify && ch.blend != RRC_BLEND_REUSE && pc == PixelCase::hit && s.valid && r.age >= 1) {
                        const RectifyBox box = rectify_box(ch, inputs[c], p.width, p.height, i, j);
                        std::copy(r.h, r.h + 4, r.h_rect);
                        r.rectified = true;
                        rectify_history(box, ch.components, r.h_rect, &res.channels[c].rectify_err[px * ch.components]);
                        res.channels[c].rectified[px] = !std::equal(r.h, r.h + ch.components, r.h_rect);
                    }
                    // The lag detector: the same case, from the unclamped H.
                    if (ch.antilag && ch.blend != RRC_BLEND_REUSE && pc == PixelCase::hit && s.valid && r.age >= 1) {
                        const RectifyBox box = rectify_box(ch, inputs[c], p.width, p.height, i, j);
                        const Antilag a = antilag_age(ch, box, r.h, r.age);
                        r.antilag = true;
                        r.age_antilag = a.age;
                        res.channels[c].antilag_age[px] = static_cast<uint16_t>(a.age);
                        res.channels[c].antilag_uncertain[px] = a.age_lo != a.age_hi;
                        res.channels[c].antilag_c[px] = a.c;
                    }
                    // The blur bound: the same case, from the fetch's fraction.
                    if (ch.blur_bound > 0.0 && ch.blend != RRC_BLEND_REUSE && pc == PixelCase::hit && s.valid && r.age >= 1) {
                        const BlurBound bb = blur_bound_age(ch, t.qx.v, t.qy.v, std::max(t.qx.err, t.qy.err) * scale);
                        r.blur_bounded = true;
                        r.age_blur = bb.age;
                        res.channels[c].blur_age[px] = static_cast<uint16_t>(bb.age);
                        res.channels[c].blur_b[px] = bb.b;
                        res.channels[c].blur_capped[px] = bb.age < r.age;
                        // The stored age min(min(n_a, N), n_prev) + 1 may differ where N is uncertain.
                        const unsigned other = r.antilag ? r.age_antilag : r.age;
                        res.channels[c].blur_uncertain[px] = std::min(other, bb.age_lo) != std::min(other, bb.age_hi);
                    }
                    // The view lobe: the same case, from the view turn at the pixel's surface point.
                    if (ch.view_lobe > 0.0 && ch.blend != RRC_BLEND_REUSE && pc == PixelCase::hit && s.valid && r.age >= 1) {
                        const ViewTurn vt = view_turn(p, frame, i, j, d);
                        const ViewLobe vl = view_lobe_cap(ch.view_lobe, vt, r.age);
                        r.view_capped = true;
                        r.age_view = vl.age;
                        res.channels[c].view_age[px] = static_cast<uint16_t>(std::min<unsigned>(vl.age, RRC_MAX_AGE_CAP));
                        res.channels[c].view_theta[px] = vt.theta;
                        res.channels[c].view_capped[px] = vl.age < r.age;
                        unsigned other = r.age;
                        if (r.antilag) other = std::min(other, r.age_antilag);
                        if (r.blur_bounded) other = std::min(other, r.age_blur);
                        res.channels[c].view_uncertain[px] = std::min(other, vl.age_lo) != std::min(other, vl.age_hi);
                    }
                    // The deviation gate: the blend case updates the state and caps
                    // the age; a hit with an invalid sample keeps the previous state;
                    // every other case stores (0, 0) (allocate's zeros).
                    if (ch.gate_kappa > 0.0 && ch.blend != RRC_BLEND_REUSE && pc == PixelCase::hit)
                        apply_gate(ch, prev.channels[c], p.width, p.height, t, s, scale, r, res.channels[c], px);
                    // A pixel whose case or n_prev the kernel may have taken otherwise:
                    // its state may be anything the table allows.
                    if (ch.gate_kappa > 0.0 && (res.near_threshold[px] || res.near_nearest_edge[px]))
                        res.channels[c].gate_beta_err[px] = res.channels[c].gate_sq_err[px] = INFINITY;
                    // REUSE: a refresh is a miss.
                    const PixelCase reuse_case = pc == PixelCase::hit ? PixelCase::miss : pc;
                    u = filter_update(ch, ch.blend == RRC_BLEND_REUSE ? reuse_case : pc, s, r);
                }
                ChannelResult& out = res.channels[c];
                for (unsigned k = 0; k < ch.components; ++k) {
                    out.exact[px * ch.components + k] = u.out[k];
                    // fp32 stores are clamped to the finite range (a no-op in exact arithmetic).
                    out.out[px * ch.components + k] = ch.fp16 ? fp16_round(u.out[k]) : std::fmin(std::fmax(u.out[k], -FLT_MAX), FLT_MAX);
                }
                out.age[px] = static_cast<uint16_t>(u.age);
                if (ch.confidence) out.weight[px] = u.weight;
            }
            res.mask[px] = mask;
        }
    }
    count(res);
    // The spatial fill: a second pass over the frame's stored outputs.
    for (size_t c = 0; c < p.channels.size(); ++c) {
        const ChannelParams& ch = p.channels[c];
        ChannelResult& out = res.channels[c];
        if (ch.fill_age != 0) {
            const std::vector<float> stored(out.out.begin(), out.out.end());  // fp32 store (fp16 values are exact)
            // A residual's prior is its base: a residual of 0.
            const std::vector<float> zero(ch.residual ? n * ch.components : 0, 0.0f);
            FillInputs in{stored.data(), out.age.data(), frame.depth, ch.residual ? zero.data() : frame.channels[c].fallback};
            // The gate weighs the neighbours by the state this frame's pass stored
            // (docs/CONVENTIONS.md, "The deviation gate", "With a spatial fill").
            if (ch.gate_kappa > 0.0) {
                in.gate_beta = out.gate_beta.data();
                in.gate_sq = out.gate_sq.data();
                in.gate_beta_err = out.gate_beta_err.data();
                in.gate_sq_err = out.gate_sq_err.data();
            }
            FillOptions fo;
            fo.error_scale = scale;
            out.shown = spatial_fill(p, c, in, fo).shown;
        }
        // The residual's displayed value: plus this frame's base (a b that is not finite adds 0).
        if (ch.residual) {
            if (out.shown.empty()) out.shown.assign(out.out.begin(), out.out.end());
            for (size_t q = 0; q < n; ++q) {
                bool finite = true;
                for (unsigned k = 0; k < ch.components; ++k) finite = finite && std::isfinite(frame.channels[c].fallback[q * ch.components + k]);
                for (unsigned k = 0; k < ch.components && finite; ++k) out.shown[q * ch.components + k] += frame.channels[c].fallback[q * ch.components + k];
            }
        }
    }
    return res;
}

PreviousFrame as_previous(const rrc_context_desc& ctx, const rrc_frame_desc& frame, const FrameResult& result) {
    const size_t n = static_cast<size_t>(ctx.width) * ctx.height;
    PreviousFrame prev;
    prev.valid = true;
    prev.depth.assign(frame.depth, frame.depth + n);
    if (ctx.use_object_id && frame.object_id) prev.object_id.assign(frame.object_id, frame.object_id + n);
    for (const ChannelResult& c : result.channels) {
        ChannelHistory h;
        h.history.assign(c.out.begin(), c.out.end());  // fp32 store (fp16 values are exact)
        h.age = c.age;
        h.weight.assign(c.weight.begin(), c.weight.end());
        prev.channels.push_back(std::move(h));
    }
    carry_gate_state(prev, result);
    return prev;
}

void carry_gate_state(PreviousFrame& prev, const FrameResult& own) {
    if (prev.channels.size() != own.channels.size()) throw std::invalid_argument("rrc_ref::carry_gate_state: channel count");
    for (size_t c = 0; c < own.channels.size(); ++c) {
        ChannelHistory& h = prev.channels[c];
        const ChannelResult& r = own.channels[c];
        h.gate_beta = r.gate_beta;
        h.gate_sq = r.gate_sq;
        h.gate_beta_err = r.gate_beta_err;
        h.gate_sq_err = r.gate_sq_err;
    }
}

}  // namespace rrc_ref
