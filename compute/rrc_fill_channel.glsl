// One channel slot of the spatial fill (the FILL pass of
// rrc_module_fill.comp, docs/CONVENTIONS.md "The spatial fill"): the function
// rrc_fill_channel_<slot>, defined once per slot by including this file with
// RRC_CH defined to a literal, as rrc_channel.glsl.  The dispatch is bound as
// the next frame: the history inputs (u_hist_*, u_age) hold this frame's
// results, u_prev_depth this frame's depth.
//
// In: size, px, store (the listed pixel is written), fill_here (p is not
// background), valid_p (p's depth is valid: else no neighbour counts), d_p
// (its depth).  Writes the slot's displayed value to u_host_out.

#define CH_(name) ch_##name(RRC_CH)
#define COMPONENTS_ (CH_(components) ? 4u : 1u)
#define FP16_ CH_(precision)  // the precision field is on for an fp16 history
#define PACKED_ (FP16_ && COMPONENTS_ == 1u)
#define RESIDUAL_ CH_(residual)

#define RRC_SLOT_PASTE2(a, b) a##b
#define RRC_SLOT_PASTE(a, b) RRC_SLOT_PASTE2(a, b)
void RRC_SLOT_PASTE(rrc_fill_channel_, RRC_CH)(ivec2 size, ivec2 px, bool store, bool fill_here, bool valid_p, float d_p) {
    if (RRC_CH >= CH_COUNT || !CH_(fill_age)) return;
    const RrcChannelParams P = u_params.slot[RRC_CH];
    // A packed channel's value and age come in one word (one load a tap).
// Every load and store counted (rrc_io.glsl): bytes in the format read or written.
#define LOAD_WORD(t) (PACKED_ ? RRC_LOAD(1u, 4u, imageLoad(u_hist_packed[RRC_CH], t).r) : 0u)
#define LOAD_V(t, word) (PACKED_ ? vec4(unpackHalf2x16(word).x, 0.0, 0.0, 0.0) \
                   : FP16_ ? RRC_LOAD(1u, 8u, imageLoad(u_hist_rgba16f[RRC_CH], t)) \
                   : (COMPONENTS_ == 1u ? vec4(RRC_LOAD(1u, 4u, imageLoad(u_hist_r32f[RRC_CH], t).r), 0.0, 0.0, 0.0) \
                                        : RRC_LOAD(1u, 16u, imageLoad(u_hist_rgba32f[RRC_CH], t))))
#define LOAD_N(t, word) (PACKED_ ? (word) >> 16 : RRC_LOAD(1u, 2u, imageLoad(u_age[RRC_CH], t).r))
#define VALUE_BYTES_ ((FP16_ ? 2u : 4u) * COMPONENTS_)  // a value at the channel's precision (the host's output)
    const uint T = P.fill_age;
    const int R = int(CH_(fill_radius));  // a loop bound, so a feature field, not a parameter
    uint word_p = LOAD_WORD(px);
    vec4 v_p = LOAD_V(px, word_p);
    if (COMPONENTS_ == 1u) v_p = vec4(v_p.x, 0.0, 0.0, 0.0);
    uint n_p = LOAD_N(px, word_p);
    vec4 shown = v_p;
    if (fill_here && n_p < T) {
        float phi = float(T - n_p) / float(T);
        // The deviation gate's noise weight (docs/CONVENTIONS.md, "The deviation
        // gate", "With a spatial fill"): where p's stored state estimates its
        // samples' noise (varsigma > 0), a neighbour further from v_p than kappa
        // standard deviations of p's deviations is left out.
        bool noise_test = false;
        float limit = 0.0;
        if (CH_(gate_kappa)) {
            const vec2 st = rrc_gate_state(RRC_LOAD(1u, 4u, texelFetch(s_gate[RRC_CH], px, 0).r));  // (beta, varsigma)
            noise_test = st.y > 0.0;
            limit = P.gate_kappa * P.gate_kappa * max(st.y - st.x * st.x, 0.0);
        }
        vec4 acc = vec4(0.0);
        float wsum = 0.0;
        for (int b = -R; b <= R; ++b)
            for (int a = -R; a <= R; ++a) {
                ivec2 q = px + ivec2(a, b);
                bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) && (a != 0 || b != 0);
                ivec2 t = clamp(q, ivec2(0), size - 1);
                uint word = LOAD_WORD(t);
                vec4 v_q = LOAD_V(t, word);
                if (COMPONENTS_ == 1u) v_q = vec4(v_q.x, 0.0, 0.0, 0.0);
                uint n_q = LOAD_N(t, word);
                float d_q = RRC_LOAD(1u, 4u, imageLoad(u_prev_depth, t).r);
                bool ok = valid_p && inside && n_q >= 1u && rrc_finite4(v_q) && !rrc_is_background(d_q) && rrc_fill_similar(d_q, d_p, P.fill_depth_tolerance);
                if (CH_(gate_kappa) && noise_test) {
                    const vec4 dv = v_q - v_p;
                    const float dq = COMPONENTS_ == 1u ? dv.x : ((dv.x + dv.y) + dv.z) * (1.0 / 3.0);
                    ok = ok && dq * dq <= limit;
                }
                float w_q = ok ? float(min(n_q, T)) : 0.0;
                acc += w_q * (ok ? v_q : vec4(0.0));
                wsum += w_q;
            }
        if (CH_(fill_prior)) {
            // With a residual the fallback is the base: the prior's residual is 0.
            vec4 f = RESIDUAL_ ? vec4(0.0) : RRC_LOAD(1u, 4u * COMPONENTS_, texelFetch(s_fallback[RRC_CH], px, 0));
            if (COMPONENTS_ == 1u) f = vec4(f.x, 0.0, 0.0, 0.0);
            bool f_ok = rrc_finite4(f);
            acc += f_ok ? P.fill_prior * f : vec4(0.0);
            wsum += f_ok ? P.fill_prior : 0.0;
        }
        float n = float(n_p);
        float den = n + phi * wsum;
        shown = den > 0.0 ? (n * v_p + phi * acc) / den : v_p;
    }
    if (RESIDUAL_) {
        // The residual's displayed value: plus this frame's base (docs/CONVENTIONS.md, "The residual").
        vec4 b = RRC_LOAD(1u, 4u * COMPONENTS_, texelFetch(s_fallback[RRC_CH], px, 0));
        if (COMPONENTS_ == 1u) b = vec4(b.x, 0.0, 0.0, 0.0);
        shown = rrc_plus_base(shown, b);
    }
    if (store) {
        rrc_io_store(VALUE_BYTES_);
        imageStore(u_host_out[RRC_CH], px, shown);
    }
#undef VALUE_BYTES_
#undef LOAD_WORD
#undef LOAD_V
#undef LOAD_N
}

#undef RESIDUAL_
#undef PACKED_
#undef FP16_
#undef COMPONENTS_
#undef CH_
#undef RRC_SLOT_PASTE
#undef RRC_SLOT_PASTE2
