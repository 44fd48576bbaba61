// The lambda recursive filter's arithmetic, shared by every channel slot
// (docs/CONVENTIONS.md "The recursive filter").
#ifndef RRC_FILTER_GLSL
#define RRC_FILTER_GLSL

#include "rrc_values.glsl"  // rrc_blend, rrc_history_filter
#include "rrc_depth.glsl"   // rrc_finite4

// The largest finite fp32 value and the smallest normal one, exactly.
const float RRC_FLT_MAX = 3.4028234663852886e38;
const float RRC_FLT_MIN = 1.1754943508222875e-38;

// The residual's displayed value (docs/CONVENTIONS.md, "The residual"): the
// stored or filled value v plus this frame's base b, in fp32, clamped to the
// finite range; a base that is not finite adds nothing.
vec4 rrc_plus_base(vec4 v, vec4 b) { return clamp(v + (rrc_finite4(b) ? b : vec4(0.0)), vec4(-RRC_FLT_MAX), vec4(RRC_FLT_MAX)); }

// Clamp to the fp16 range and round to the nearest fp16 value, ties to even,
// so the store is exact whatever rounding the driver's conversion uses.
vec4 rrc_round_fp16(vec4 x) {
    x = clamp(x, vec4(-65504.0), vec4(65504.0));
    // Normal halves: round the fp32 mantissa to 10 bits (carry may bump the exponent).
    uvec4 b = floatBitsToUint(x);
    b = (b + 0xFFFu + ((b >> 13) & 1u)) & ~0x1FFFu;
    vec4 normal = uintBitsToFloat(b);
    // Subnormal halves (|x| < 2^-14) sit on a grid of 2^-24.
    vec4 sub = roundEven(x * 16777216.0) * 5.9604644775390625e-08;
    return mix(normal, sub, lessThan(abs(x), vec4(6.103515625e-05)));
}

// A deviation gate state texel as stored, one word: fp16 (beta, r) with
// r = sqrt(varsigma); read back as (beta, r^2), the square exact in fp32
// (docs/CONVENTIONS.md, "The deviation gate", "Storing the state").
vec2 rrc_gate_state(uint word) {
    const vec2 br = unpackHalf2x16(word);
    return vec2(br.x, br.y * br.y);
}

float rrc_lambda_eff(uint blend, float lambda, uint n_prev) {
    float n = float(n_prev);
    float running = n / (n + 1.0);
    if (blend == RRC_BLEND_FIXED) return lambda;
    if (blend == RRC_BLEND_AGE_AWARE) return min(lambda, running);
    return running;
}

// Catmull-Rom weights for fraction t (taps at -1, 0, +1, +2).
vec4 rrc_catmull_rom_weights(float t) {
    float t2 = t * t, t3 = t2 * t;
    return 0.5 * vec4(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
}

// The Gaussian history filter's weights for fraction t (taps at -1, 0, +1,
// +2): the 3-tap blur [g, 1 - 2g, g] convolved with the bilinear [1 - t, t].
vec4 rrc_blur_weights(float t, float g) {
    float c = 1.0 - 2.0 * g, u = 1.0 - t;
    return vec4(g * u, c * u + g * t, g * u + c * t, g * t);
}

#endif
