// One channel slot's update in the per-pixel passes (rrc_module_frame.comp):
// the function rrc_channel_<slot>, defined once per slot by including this
// file with RRC_CH defined to a literal (0..RRC_MAX_CHANNELS-1): storage-image
// arrays may only be indexed by constants, and the slot's feature word
// (rrc_channel_slots.glsl) compiles out every format, filter and blend the
// channel does not use.  Its parameters (lambda, the age cap, gammas,
// thresholds, widths) come from its parameter block, read once.
//
// In: px, g (RrcGeometry: where to resample), hit_any (the hit test passed:
// HIT or REFRESHED), hit_cached (HIT: a REUSE channel keeps its value),
// channel_store (this pass writes this pixel's channels), view_theta (the
// view and lighting turn, rrc_view_lobe.glsl); in/out: mask (INVALID_SAMPLE)
// and young (set where the channel has a fill and is younger than its fill
// age here).  CLASSIFY (ALL_REUSE) writes only HITs, so it loads no sample;
// RESOLVE_LISTED writes only the rest, so it resamples no history.

#define CH_(name) ch_##name(RRC_CH)
#define COMPONENTS_ (CH_(components) ? 4u : 1u)
#define FP16_ CH_(precision)  // the precision field is on for an fp16 history
// A 1-component fp16 channel keeps value and age in one R32_UINT word
// (docs/design/inside-the-kernel.md): one load per tap brings both,
// and one store writes both.
#define PACKED_ (FP16_ && COMPONENTS_ == 1u)
#define UNPACK_H(word) vec4(unpackHalf2x16(word).x, 0.0, 0.0, 0.0)
#define REUSE_ (CH_(blend) == RRC_BLEND_REUSE)
#define RESIDUAL_ CH_(residual)
#define CONFIDENCE_ CH_(confidence)

// This frame's sample and confidence at texel t (the pixel, or a neighbour for rectification).
// Every load and store counted (rrc_io.glsl): bytes in the format read or written, the
// host's sampled inputs as fp32 (samples 4 a component, confidence 4, a base 4 a component).
#define LOAD_RAW(t) (SAMPLED_INPUTS      ? RRC_LOAD(1u, 4u * COMPONENTS_, texelFetch(s_samples[RRC_CH], t, 0))      \
                     : COMPONENTS_ == 1u ? vec4(RRC_LOAD(1u, 4u, imageLoad(u_sample1[RRC_CH], t).r), 0.0, 0.0, 0.0) \
                                         : RRC_LOAD(1u, 16u, imageLoad(u_sample4[RRC_CH], t)))
// The residual (docs/CONVENTIONS.md, "The residual"): the channel's sample is
// s - b, b the host's base (the fallback image) at the same texel.
#define LOAD_B(t) (RESIDUAL_ ? RRC_LOAD(1u, 4u * COMPONENTS_, texelFetch(s_fallback[RRC_CH], t, 0)) : vec4(0.0))
#define LOAD_S(t) (RESIDUAL_ ? LOAD_RAW(t) - LOAD_B(t) : LOAD_RAW(t))
#define LOAD_C(t)                                                                                              \
    (!CONFIDENCE_     ? 1.0                                                                                    \
     : SAMPLED_INPUTS ? RRC_LOAD(1u, 4u, texelFetch(s_confidence[RRC_CH], t, 0).r)                            \
                      : RRC_LOAD(1u, 4u, imageLoad(u_confidence[RRC_CH], t).r))
#define VALUE_BYTES_ ((FP16_ ? 2u : 4u) * COMPONENTS_)  // a value at the channel's precision

#define RRC_SLOT_PASTE2(a, b) a##b
#define RRC_SLOT_PASTE(a, b) RRC_SLOT_PASTE2(a, b)
void RRC_SLOT_PASTE(rrc_channel_, RRC_CH)(ivec2 px, RrcGeometry g, bool hit_any, bool hit_cached, bool channel_store, float view_theta,
                                         inout uint mask, inout bool young) {
    if (RRC_CH >= CH_COUNT) return;
    const RrcChannelParams P = u_params.slot[RRC_CH];
    ivec2 size = rrc_size();
    // -- the new sample s and its confidence w
    const bool SAMPLE_ = PASS != RRC_PASS_CLASSIFY;
    // The residual's base at the pixel: subtracted from the sample, added to
    // the displayed value (a base that is not finite makes the sample invalid
    // and adds nothing).
    vec4 b_px = SAMPLE_ ? LOAD_B(px) : vec4(0.0);
    vec4 s = SAMPLE_ ? (RESIDUAL_ ? LOAD_RAW(px) - b_px : LOAD_RAW(px)) : vec4(0.0);
    if (COMPONENTS_ == 1u) s = vec4(s.x, 0.0, 0.0, 0.0);
    float w = SAMPLE_ ? LOAD_C(px) : 1.0;
    bool s_valid = rrc_finite4(s) && rrc_finite(w);
    w = clamp(w, 0.0, 1.0);
    w = w < RRC_FLT_MIN ? 0.0 : w;  // denormal weights count as 0 on every device (flushing or not)

    // -- history H, weight W (resampled) and age (nearest) at uv_prev
#define LOAD_WORD(t) RRC_LOAD(1u, 4u, imageLoad(u_hist_packed[RRC_CH], t).r)
#define LOAD_H(t) (PACKED_ ? UNPACK_H(LOAD_WORD(t)) : FP16_ ? RRC_LOAD(1u, 8u, imageLoad(u_hist_rgba16f[RRC_CH], t)) \
                   : (COMPONENTS_ == 1u ? RRC_LOAD(1u, 4u, imageLoad(u_hist_r32f[RRC_CH], t)) : RRC_LOAD(1u, 16u, imageLoad(u_hist_rgba32f[RRC_CH], t))))
#define LOAD_W(t) (CONFIDENCE_ ? RRC_LOAD(1u, 4u, imageLoad(u_weight[RRC_CH], t).r) : 1.0)
#define LOAD_AGE(t) RRC_LOAD(1u, 2u, imageLoad(u_age[RRC_CH], t).r)
    vec4 H;
    float Wh;
    uint n_prev;
    if (PASS == RRC_PASS_RESOLVE_LISTED) {
        H = vec4(0.0), Wh = 0.0, n_prev = 0u;  // only pixels that are not HITs are written: their history is not used
    } else if (CH_(filter) == RRC_HISTORY_FILTER_NEAREST) {
        uint word = PACKED_ ? LOAD_WORD(g.taps.nearest) : 0u;
        H = PACKED_ ? UNPACK_H(word) : LOAD_H(g.taps.nearest);
        Wh = LOAD_W(g.taps.nearest);
        n_prev = PACKED_ ? word >> 16 : LOAD_AGE(g.taps.nearest);
    } else {
        vec4 h00, h10, h01, h11;
        if (PACKED_) {
            uvec4 words = uvec4(LOAD_WORD(g.taps.p00), LOAD_WORD(g.taps.p10), LOAD_WORD(g.taps.p01), LOAD_WORD(g.taps.p11));
            h00 = UNPACK_H(words.x), h10 = UNPACK_H(words.y), h01 = UNPACK_H(words.z), h11 = UNPACK_H(words.w);
            // The nearest texel clamp(floor(q)) is the tap clamp(floor(q - 0.5) + (f >= 0.5)): one of the four.
            bvec2 upper = greaterThanEqual(g.taps.f, vec2(0.5));
            uint nearest = upper.y ? (upper.x ? words.w : words.z) : (upper.x ? words.y : words.x);
            n_prev = nearest >> 16;
        } else {
            h00 = LOAD_H(g.taps.p00), h10 = LOAD_H(g.taps.p10), h01 = LOAD_H(g.taps.p01), h11 = LOAD_H(g.taps.p11);
            n_prev = LOAD_AGE(g.taps.nearest);
        }
        vec4 wt = g.taps.w;
        H = wt.x * h00 + wt.y * h10 + wt.z * h01 + wt.w * h11;
        Wh = CONFIDENCE_ ? dot(wt, vec4(LOAD_W(g.taps.p00), LOAD_W(g.taps.p10), LOAD_W(g.taps.p01), LOAD_W(g.taps.p11))) : 1.0;
        if (CH_(filter) == RRC_HISTORY_FILTER_CATMULL_ROM || CH_(filter) == RRC_HISTORY_FILTER_GAUSSIAN) {
            // 4x4 taps.  Catmull-Rom is clamped to the range of the bilinear
            // taps so it cannot ring; the Gaussian's weights are convex.
            const bool CR = CH_(filter) == RRC_HISTORY_FILTER_CATMULL_ROM;
            vec4 wx = CR ? rrc_catmull_rom_weights(g.taps.f.x) : rrc_blur_weights(g.taps.f.x, (P.blur_sigma * P.blur_sigma * 0.5));
            vec4 wy = CR ? rrc_catmull_rom_weights(g.taps.f.y) : rrc_blur_weights(g.taps.f.y, (P.blur_sigma * P.blur_sigma * 0.5));
            ivec2 hi = rrc_size() - 1;
            vec4 acc = vec4(0.0);
            float accw = 0.0;
            for (int j = 0; j < 4; ++j) {
                int y = clamp(g.taps.base.y - 1 + j, 0, hi.y);
                for (int i = 0; i < 4; ++i) {
                    ivec2 t = ivec2(clamp(g.taps.base.x - 1 + i, 0, hi.x), y);
                    acc += (wx[i] * wy[j]) * LOAD_H(t);
                    if (CONFIDENCE_) accw += (wx[i] * wy[j]) * LOAD_W(t);
                }
            }
            H = CR ? clamp(acc, min(min(h00, h10), min(h01, h11)), max(max(h00, h10), max(h01, h11))) : acc;
            if (CONFIDENCE_ && !CR) Wh = accw;
            if (CONFIDENCE_ && CR) {
                vec4 wq = vec4(LOAD_W(g.taps.p00), LOAD_W(g.taps.p10), LOAD_W(g.taps.p01), LOAD_W(g.taps.p11));
                Wh = clamp(accw, min(min(wq.x, wq.y), min(wq.z, wq.w)), max(max(wq.x, wq.y), max(wq.z, wq.w)));
            }
        }
    }
#undef LOAD_WORD
#undef LOAD_H
#undef LOAD_W
#undef LOAD_AGE

    // -- the deviation gate (docs/CONVENTIONS.md, "The deviation gate"): the
    //    running mean beta and mean square varsigma of d = s - H (the first
    //    three components' mean), resampled with the bilinear taps; where beta,
    //    the history's bias, exceeds kappa standard errors of the deviations,
    //    the age is cut to N_g = floor(kappa^2 v / beta^2), at which they balance.
    const bool GATE_ = CH_(gate_kappa);
    vec2 gate_prev = vec2(0.0), gate_new = vec2(0.0);
    uint gate_cap = RRC_MAX_AGE_CAP;
    if (GATE_ && PASS != RRC_PASS_RESOLVE_LISTED && hit_any) {
        const vec4 wt = g.taps.w;
        // The four taps' states in one gather of their words, not four fetches
        // (on lavapipe each sampled fetch is a call): centred on the block's
        // shared corner base + 1, a gather picks texels base .. base + 1, and
        // the sampler's CLAMP_TO_EDGE clamps them as the taps are clamped.
        // Gather order: p01, p11, p10, p00.
        const uvec4 gw = RRC_LOAD(4u, 4u, textureGather(s_gate[RRC_CH], vec2(g.taps.base + 1) / vec2(size), 0));
        gate_prev = wt.x * rrc_gate_state(gw.w) + wt.y * rrc_gate_state(gw.z) + wt.z * rrc_gate_state(gw.x) + wt.w * rrc_gate_state(gw.y);
        if (s_valid && n_prev >= 1u) {
            const vec4 dv = s - H;
            const float d = COMPONENTS_ == 1u ? dv.x : ((dv.x + dv.y) + dv.z) * (1.0 / 3.0);
            const float a = max(1.0 / float(n_prev + 1u), 0.25);
            const float beta = (1.0 - a) * gate_prev.x + a * d, vs = (1.0 - a) * gate_prev.y + a * (d * d);
            // An fp32 overflow of huge deviations restarts the statistics and caps nothing.
            const bool finite = rrc_finite(beta) && rrc_finite(vs);
            gate_new = finite ? vec2(beta, vs) : vec2(0.0);
            const float b2 = beta * beta;
            if (finite && n_prev >= 2u && b2 >= RRC_FLT_MIN) {
                const float ratio = min(P.gate_kappa * P.gate_kappa * max(vs - b2, 0.0) / b2, float(RRC_MAX_AGE_CAP));
                gate_cap = uint(max(floor(ratio), 1.0));
            }
        }
    }

    // -- rectification: the blend's H clamped to mu +- gamma sigma of this
    //    frame's valid samples in the 3x3 block (docs/CONVENTIONS.md,
    //    "Rectification"); formed about the centre sample, which is valid
    //    wherever the blend uses it, so large magnitudes do not cancel.
    vec4 H_blend = H;
    // The lag detector (docs/CONVENTIONS.md, "The lag detector") reads the
    // same 3x3 moments with its own gamma: the age the blend uses, n_a.
    uint n_blend = n_prev;
    if (CH_(rectify) || CH_(antilag)) {
        ivec2 hi = size - 1;
        vec4 sum = vec4(0.0), sum2 = vec4(0.0);
        float m = 0.0;
        for (int b = -1; b <= 1; ++b)
            for (int a = -1; a <= 1; ++a) {
                ivec2 t = clamp(px + ivec2(a, b), ivec2(0), hi);
                vec4 q = LOAD_S(t);
                if (COMPONENTS_ == 1u) q = vec4(q.x, 0.0, 0.0, 0.0);
                float wq = LOAD_C(t);
                bool ok = rrc_finite4(q) && rrc_finite(wq);
                vec4 dq = ok ? q - s : vec4(0.0);
                sum += dq;
                sum2 += dq * dq;
                m += ok ? 1.0 : 0.0;
            }
        vec4 mean_d = sum / max(m, 1.0);
        vec4 sigma = sqrt(max(sum2 / max(m, 1.0) - mean_d * mean_d, vec4(0.0)));
        vec4 lo = s + mean_d - P.rectify_gamma * sigma, hi_v = s + mean_d + P.rectify_gamma * sigma;
        // A box an fp32 overflow made infinite or NaN clamps nothing.
        bvec4 box = bvec4(uvec4(not(isnan(lo))) & uvec4(not(isnan(hi_v))) & uvec4(not(isinf(lo))) & uvec4(not(isinf(hi_v))));
        if (CH_(rectify)) H_blend = mix(H, clamp(H, lo, hi_v), box);
        if (CH_(antilag)) {
            // The distance from H to mu +- gamma_a sigma, relative to the larger
            // of |H| and |mu| (plus the box and the darkness term): d.
            const float ga = P.antilag_gamma;
            vec4 gap = max(abs((H - s) - mean_d) - ga * sigma, vec4(0.0));
            vec4 d4 = gap / (max(abs(H), abs(s + mean_d)) + ga * sigma + float(RRC_ANTILAG_DARKNESS));
            float d = COMPONENTS_ == 1u ? d4.x : max(max(d4.x, d4.y), max(d4.z, d4.w));
            // Confidence c: 1 up to T/2, 0 from T; a d an fp32 overflow made NaN or infinite changes nothing.
            float c = clamp(2.0 - 2.0 * d / P.antilag_threshold, 0.0, 1.0);
            c = (isnan(d) || isinf(d)) ? 1.0 : c;
            n_blend = min(uint(floor(c * float(n_prev))), n_prev);
        }
    }

    // -- the blur bound (docs/CONVENTIONS.md, "The blur bound"): the fetch's
    //    blur b, the larger per-axis second moment of its weights about the
    //    fetch point (BILINEAR f(1 - f); GAUSSIAN adds its 2g = sigma_b^2),
    //    caps the age at floor(B / b), so the stationary blur n b stays within B.
    if (CH_(blur_bound)) {
        vec2 bxy = g.taps.f * (1.0 - g.taps.f);
        if (CH_(filter) == RRC_HISTORY_FILTER_GAUSSIAN) bxy += 2.0 * (P.blur_sigma * P.blur_sigma * 0.5);
        float b = max(bxy.x, bxy.y);
        // b below the fp32 normal range is no blur (and keeps B / b in the division's exact range).
        float ratio = b >= RRC_FLT_MIN ? P.blur_bound / b : RRC_FLT_MAX;
        n_blend = min(n_blend, uint(min(floor(ratio), float(RRC_MAX_AGE_CAP))));
    }

    // -- the view-dependent history (docs/CONVENTIONS.md, "The view-dependent
    //    history"): the pixel's view turn theta plus the lighting's turn phi
    //    (view_theta) caps the age at floor(alpha / (theta + phi)), so the
    //    history's mean offset in reflected direction stays within alpha.
    if (CH_(view_lobe) && view_theta >= RRC_FLT_MIN)
        n_blend = min(n_blend, uint(min(floor(P.view_lobe / view_theta), float(RRC_MAX_AGE_CAP))));
    if (GATE_) n_blend = min(n_blend, gate_cap);

    // -- the table of docs/CONVENTIONS.md
    float lambda = rrc_lambda_eff(CH_(blend), P.lambda, n_prev);
    // A shortened age caps lambda_eff at n_a/(n_a + 1) (0: the sample alone).
    const bool SHORTENED_ = CH_(antilag) || CH_(blur_bound) || CH_(view_lobe) || GATE_;
    if (SHORTENED_) lambda = n_blend < n_prev ? min(lambda, float(n_blend) / (float(n_blend) + 1.0)) : lambda;
    float W_new = lambda * Wh + (1.0 - lambda) * w;
    vec4 blended;
    if (CONFIDENCE_) {
        // Both weights normalised first: a weighted mean of H and s neither
        // underflows (w*s with a tiny w) nor overflows; each weight is formed
        // on its own (not as 1 - the other) so a tiny one is not cancelled.
        float inv = 1.0 / max(W_new, RRC_FLT_MIN);  // W_new < FLT_MIN keeps H below
        blended = (lambda * Wh * inv) * H_blend + ((1.0 - lambda) * w * inv) * s;
    } else {
        blended = lambda * H_blend + (1.0 - lambda) * s;
    }
    // REUSE: a refresh is a miss (docs/CONVENTIONS.md, "The shading cache").
    bool hit = REUSE_ ? hit_cached : hit_any;
    bool fresh = !hit || n_prev == 0u;  // a miss, or a hit on an empty history
    vec4 out_v;
    uint n_out;
    float W_out;
    if (REUSE_ && hit) {
        // The cached value, unchanged (n_prev >= 1: an empty history refreshes).
        out_v = H;
        n_out = min(n_prev + 1u, P.age_cap);
        W_out = 1.0;
    } else if (!s_valid) {
        out_v = hit ? H : vec4(0.0);
        n_out = hit ? n_prev : 0u;
        W_out = hit ? Wh : 0.0;
        mask |= RRC_MASK_INVALID_SAMPLE;
    } else if (fresh) {
        out_v = s;
        n_out = g.background ? 0u : 1u;
        W_out = w;
    } else if (CONFIDENCE_ && !(W_new >= RRC_FLT_MIN)) {
        out_v = H;
        n_out = n_prev;
        W_out = 0.0;
    } else {
        out_v = blended;
        n_out = min(n_blend + 1u, P.age_cap);
        W_out = W_new;
    }
    // fp32: resampling texels at +-FLT_MAX with weights that sum to 1 + ulp
    // rounds to +-Inf; no history value may be infinite.
    out_v = FP16_ ? rrc_round_fp16(out_v) : clamp(out_v, vec4(-RRC_FLT_MAX), vec4(RRC_FLT_MAX));
    if (CH_(fill_age) && n_out < P.fill_age) young = true;
    if (channel_store) {
        if (PACKED_) {
            // out_v is an fp16 value already (rrc_round_fp16): the conversion is exact.
            rrc_io_store(4u);
            imageStore(u_age_out[RRC_CH], px, uvec4(packHalf2x16(vec2(out_v.x, 0.0)) | (n_out << 16)));
        } else {
            rrc_io_store(FP16_ ? 8u : COMPONENTS_ == 1u ? 4u : 16u);  // RGBA16F, R32F or RGBA32F
            imageStore(u_hist_out[RRC_CH], px, out_v);
            rrc_io_store(2u);
            imageStore(u_age_out[RRC_CH], px, uvec4(n_out));
        }
        // The host's output (with a fill, its value where the fill does not
        // run: the fill shows a 1-component value as (v, 0, 0, 0)); with a
        // residual, the history's value plus this frame's base.
        vec4 shown_v = out_v;
        if (RESIDUAL_) {
            if (COMPONENTS_ == 1u) b_px = vec4(b_px.x, 0.0, 0.0, 0.0);
            shown_v = rrc_plus_base(out_v, b_px);
        }
        // Not where this channel's own age lists the pixel for the fill (rrc_module_frame.comp):
        // the fill's pass, later in the same call, writes every filled channel's displayed
        // value there, so this store would be overwritten unread.  (Classify stores anyway:
        // its list is filled in the resolve call.)
        const bool filled_later = CH_(fill_age) && PASS != RRC_PASS_CLASSIFY && n_out < P.fill_age && !g.background;
        if ((HOST_OUT_MASK & (1u << RRC_CH)) != 0u && !filled_later) {
            rrc_io_store(VALUE_BYTES_);
            imageStore(u_host_out[RRC_CH], px, (CH_(fill_age) || RESIDUAL_) && COMPONENTS_ == 1u ? vec4(shown_v.x, 0.0, 0.0, 0.0) : shown_v);
        }
        if (INTEROP && (HOST_AGE_MASK & (1u << RRC_CH)) != 0u) {
            rrc_io_store(2u);
            imageStore(u_host_age_out[RRC_CH], px, uvec4(n_out));
        }
        if (CONFIDENCE_) {
            rrc_io_store(4u);
            imageStore(u_weight_out[RRC_CH], px, vec4(W_out));
        }
        // The gate's state, by the case of the table: the blend's, a hit's
        // resampled state where the sample is invalid (the history is kept), else 0.
        // Stored as fp16 (beta, sqrt(varsigma)), (0, 0) where either is beyond the fp16 range.
        if (GATE_) {
            const vec2 gate_out = hit && !s_valid ? gate_prev : hit && s_valid && n_prev >= 1u ? gate_new : vec2(0.0);
            const vec2 stored = vec2(gate_out.x, sqrt(gate_out.y));
            const bool in_range = abs(stored.x) <= 65504.0 && stored.y <= 65504.0;
            rrc_io_store(4u);
            imageStore(u_weight_out[RRC_CH], px, in_range ? rrc_round_fp16(vec4(stored, 0.0, 0.0)) : vec4(0.0));
        }
    }
}

#undef VALUE_BYTES_
#undef LOAD_S
#undef LOAD_RAW
#undef LOAD_B
#undef LOAD_C
#undef UNPACK_H
#undef REUSE_
#undef PACKED_
#undef CONFIDENCE_
#undef RESIDUAL_
#undef FP16_
#undef COMPONENTS_
#undef CH_
#undef RRC_SLOT_PASTE
#undef RRC_SLOT_PASTE2
