// Reverse reprojection and the epsilon-depth hit test (docs/CONVENTIONS.md).
// A function library of the per-pixel passes (compute/rrc_module_frame.comp):
// it reads the geometry inputs (RRC_BINDING_DEPTH..RRC_BINDING_NOCACHE and
// the interop bindings, declared by the pass: rrc_bindings.glsl) and declares
// the specialization constants that select the source, so a configuration
// compiles only the path it uses; the depth mode and the push constants are
// rrc_depth.glsl's.  Built with
// -DRRC_WITHOUT_<FEATURE>, a feature's constant is a plain `false` instead:
// tests/spirv compares that build with the specialised one (docs/measurements/PERFORMANCE.md).
#ifndef RRC_REPROJECT_GLSL
#define RRC_REPROJECT_GLSL

#include "rrc_values.glsl"  // rrc_reprojection, rrc_depth_mode, RRC_EPS_*, ids
#include "rrc_depth.glsl"   // DEPTH_MODE, pc, u_prev_depth, rrc_store, background and invalid depth
#include "rrc_io.glsl"      // RRC_LOAD, rrc_io_store

// ---- Specialization constants (ids: rrc_kernel_interface.h) ---------------
layout(constant_id = RRC_SPEC_SOURCE) const uint SOURCE = RRC_REPROJECTION_PREV_CLIP;
layout(constant_id = RRC_SPEC_EPS_KIND) const uint EPS_KIND = RRC_EPS_ULP;  // RRC_EPS_ABSOLUTE, _ULP, _RELATIVE
// An optional feature's constant: built with -DRRC_WITHOUT_<FEATURE>
// (tests/spirv), its layout qualifier goes and it is a plain `false`.
#ifndef RRC_WITHOUT_NOCACHE
layout(constant_id = RRC_SPEC_HAS_NOCACHE)
#endif
const bool HAS_NOCACHE = false;
// Interop: the host's images are read through samplers (any format, depth
// formats included), the library keeps its own copy of depth for the next
// frame and writes each channel to the host's output image too.
#ifndef RRC_WITHOUT_INTEROP
layout(constant_id = RRC_SPEC_INTEROP)
#endif
const bool INTEROP = false;
// Interop with rrc_vulkan_frame_desc.storage_inputs: the host's input
// images are bound where the standalone path binds its own copies and read
// with storage loads (a sampler fetch costs several of them on lavapipe).
layout(constant_id = RRC_SPEC_STORAGE_INPUTS) const bool STORAGE_INPUTS = false;
const bool SAMPLED_INPUTS = INTEROP && !STORAGE_INPUTS;  // the inputs come through samplers
// The ADAPTIVE test (docs/CONVENTIONS.md): every source but plain MOTION.
#ifndef RRC_WITHOUT_ADAPTIVE
layout(constant_id = RRC_SPEC_ADAPTIVE)
#endif
const bool ADAPTIVE = false;

// The frame's pass (RRC_PASS_*): resolve takes hit and miss from the mask
// classify wrote, so it skips the hit test (and the copies kept for the next
// frame, which classify made) and computes only where to resample history.
layout(constant_id = RRC_SPEC_PASS) const uint PASS = RRC_PASS_FUSED;
const bool RRC_TEST = PASS != RRC_PASS_RESOLVE;
// Object ids (docs/CONVENTIONS.md, "Previous depth fetch and the hit test"): a hit also needs every
// previous-depth tap with a non-zero weight to carry the pixel's id.
#ifndef RRC_WITHOUT_OBJECT_ID
layout(constant_id = RRC_SPEC_OBJECT_ID)
#endif
const bool OBJECT_ID = false;

ivec2 rrc_size() { return SAMPLED_INPUTS ? textureSize(s_depth, 0) : imageSize(u_depth); }
// Every load and store counted (rrc_io.glsl): the host's sampled inputs at the bytes
// of the formats the storage path reads (depth R32F, reprojection RGBA32F, nocache R8UI),
// as rrc-bench's roof counts them.
float rrc_load_depth(ivec2 px) { return RRC_LOAD(1u, 4u, SAMPLED_INPUTS ? texelFetch(s_depth, px, 0).r : imageLoad(u_depth, px).r); }
// (A MOTION host image is read through a sampler as RG32F: 8 bytes.)
vec4 rrc_load_reprojection(ivec2 px) {
    return RRC_LOAD(1u, SAMPLED_INPUTS && SOURCE == RRC_REPROJECTION_MOTION ? 8u : 16u, SAMPLED_INPUTS ? texelFetch(s_reproj, px, 0) : imageLoad(u_reproj, px));
}
bool rrc_load_nocache(ivec2 px) { return RRC_LOAD(1u, 1u, (SAMPLED_INPUTS ? texelFetch(s_nocache, px, 0).r : imageLoad(u_nocache, px).r) != 0u); }

// ulp of an fp32 value whose exponent field, in place (bits & 0x7F800000),
// is `exponent`: 2^(floor(log2|e|) - 23), 2^-149 in the denormal range.
float rrc_ulp_of_exponent(uint exponent) {
    const uint k23 = 23u << 23;
    return uintBitsToFloat(exponent > k23 ? exponent - k23 : (exponent == 0u ? 1u : (1u << ((exponent >> 23) - 1u))));
}
float rrc_ulp(float e) { return rrc_ulp_of_exponent(floatBitsToUint(e) & 0x7F800000u); }

// The four bilinear taps at the previous frame's sample coordinate q.  The
// same taps and weights serve the depth test and the history fetch.
struct RrcTaps {
    ivec2 p00, p10, p01, p11;
    vec4 w;        // (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx*fy
    ivec2 nearest; // clamp(floor(q))
    ivec2 base;    // floor(q - 0.5), unclamped (Catmull-Rom needs its neighbours)
    vec2 f;        // fractional part of q - 0.5
};

RrcTaps rrc_taps(vec2 q, ivec2 size) {
    RrcTaps t;
    vec2 p = q - 0.5;
    vec2 i0f = floor(p);
    t.f = p - i0f;
    t.base = ivec2(i0f);
    ivec2 hi = size - 1;
    ivec2 a = clamp(t.base, ivec2(0), hi);
    ivec2 b = clamp(t.base + 1, ivec2(0), hi);
    t.p00 = a;
    t.p10 = ivec2(b.x, a.y);
    t.p01 = ivec2(a.x, b.y);
    t.p11 = b;
    t.w = vec4((1.0 - t.f.x) * (1.0 - t.f.y), t.f.x * (1.0 - t.f.y), (1.0 - t.f.x) * t.f.y, t.f.x * t.f.y);
    t.nearest = clamp(ivec2(floor(q)), ivec2(0), hi);
    return t;
}

// The quantity the bilinear fetch interpolates: z, or 1/d for LINEAR.
float rrc_interpolated(float z) { return DEPTH_MODE == RRC_DEPTH_MODE_LINEAR ? 1.0 / z : z; }

// One axis of the ADAPTIVE test (docs/CONVENTIONS.md, "The ADAPTIVE test")
// on five taps of the current depth's interpolated quantity a2, a, c, b, b2
// (left/up to right/down, clamped to the image; `edge`: c is on the image's
// first or last column/row).  x: the curvature estimate less its fp32 and
// quantisation noise: the centre's second difference s, or at a step of its
// own (a neighbour n of the other sign with |s| or the one-sided difference
// towards n at least STEP_OWN of |n|: +h next to -h, or c on the step's ramp)
// the smooth side's (a neighbour not of the other sign and at most
// SMOOTH_SIDE of |s|), 0 if there is none; 0 on the image's first and last
// column/row and for non-finite taps.  y: the slope, for the clamped fetch
// beyond the outermost texel centres and the fp32 position term (the smaller
// one-sided difference; at the image edge, the one that exists).  z: beside
// a step (a neighbour of the other sign and at least STEP_RATIO of |s|, |s|
// above the noise) the larger such |n|, else 0.
//
// Written for lavapipe, which pays every operation
// (docs/design/inside-the-kernel.md); each shortcut gives the same bits as
// the plain formula.  Finite s, s-, s+ imply finite a, c, b (a non-finite tap makes s
// inf or NaN), and the result is 0 otherwise, so finiteness is |x| < inf on
// the magnitudes the step test needs anyway, and ulp(max(|a|, |b|, |c|))
// takes the largest of their exponent fields (an integer max).  At the
// image's first or last column/row one one-sided difference is exactly 0
// (the clamped neighbour is c itself), so the larger one is their sum.
vec3 rrc_axis(float a2, float a, float c, float b, float b2, bool edge, float step) {
    float dp = b - c, dm = c - a, s = dp - dm;
    float sm = dm - (a - a2), sp = (b2 - b) - dp;  // the neighbours' second differences
    float a_s = abs(s), a_sm = abs(sm), a_sp = abs(sp), adp = abs(dp), adm = abs(dm);
    const uint kExp = 0x7F800000u;
    uint exponent = max(max(floatBitsToUint(a) & kExp, floatBitsToUint(b) & kExp), floatBitsToUint(c) & kExp);
    float noise = RRC_ADAPTIVE_NOISE_ULPS * rrc_ulp_of_exponent(exponent) + RRC_ADAPTIVE_NOISE_STEPS * step;
    float ratio_s = RRC_ADAPTIVE_STEP_RATIO * a_s;
    bool opp_m = sm * s < 0.0 && a_sm >= ratio_s, opp_p = sp * s < 0.0 && a_sp >= ratio_s;
    bool own = (opp_m && max(a_s, adm) >= RRC_ADAPTIVE_STEP_OWN * a_sm) || (opp_p && max(a_s, adp) >= RRC_ADAPTIVE_STEP_OWN * a_sp);
    float cut = RRC_ADAPTIVE_SMOOTH_SIDE * a_s;
    float side = max(!opp_m && a_sm <= cut ? a_sm : 0.0, !opp_p && a_sp <= cut ? a_sp : 0.0);
    float curvature = max((own ? side : a_s) - noise, 0.0);
    float beside = a_s > noise ? max(opp_m ? a_sm : 0.0, opp_p ? a_sp : 0.0) : 0.0;
    const float kInf = uintBitsToFloat(kExp);
    bool finite = a_s < kInf && a_sm < kInf && a_sp < kInf;
    float slope = edge ? adp + adm : min(adp, adm);
    return finite ? vec3(edge ? 0.0 : curvature, slope, edge ? 0.0 : beside) : vec3(0.0);
}

// This frame's depth at px and its eight cross neighbours, clamped to the
// image (the ADAPTIVE test's taps): h = (x-2, x-1, x+1, x+2), v = (y-2, y-1,
// y+1, y+2).  Through the host's sampler: five gathers instead of nine
// fetches (lavapipe pays a gather like one texelFetch).  Each returns the 2x2
// quad whose lower corner is i0 = (x0, y0), as (T(x0,y0+1), T(x0+1,y0+1),
// T(x0+1,y0), T(x0,y0)); it is sampled at that quad's centre, half a texel
// from any other quad's, and clamp-to-edge clamps its texels exactly as the
// storage path clamps its coordinates.
struct RrcCross {
    float c;
    vec4 h, v;
};
vec4 rrc_gather_depth(ivec2 i0, vec2 inv_size) { return RRC_LOAD(4u, 4u, textureGather(s_depth, (vec2(i0) + 1.0) * inv_size)); }
RrcCross rrc_depth_cross(ivec2 px, ivec2 size) {
    RrcCross r;
    if (SAMPLED_INPUTS) {
        vec2 inv = 1.0 / vec2(size);
        vec4 b = rrc_gather_depth(px, inv);                 // (x,y+1) (x+1,y+1) (x+1,y) (x,y)
        vec4 a = rrc_gather_depth(px + ivec2(-2, 0), inv);  // .w (x-2,y), .z (x-1,y)
        vec4 c = rrc_gather_depth(px + ivec2(2, 0), inv);   // .w (x+2,y)
        vec4 d = rrc_gather_depth(px + ivec2(0, -2), inv);  // .w (x,y-2), .x (x,y-1)
        vec4 e = rrc_gather_depth(px + ivec2(0, 2), inv);   // .w (x,y+2)
        r.c = b.w;
        r.h = vec4(a.w, a.z, b.z, c.w);
        r.v = vec4(d.w, d.x, b.x, e.w);
        return r;
    }
    ivec2 hi = size - 1;
    r.c = rrc_load_depth(px);
    r.h = vec4(rrc_load_depth(ivec2(max(px.x - 2, 0), px.y)), rrc_load_depth(ivec2(max(px.x - 1, 0), px.y)),
               rrc_load_depth(ivec2(min(px.x + 1, hi.x), px.y)), rrc_load_depth(ivec2(min(px.x + 2, hi.x), px.y)));
    r.v = vec4(rrc_load_depth(ivec2(px.x, max(px.y - 2, 0))), rrc_load_depth(ivec2(px.x, max(px.y - 1, 0))),
               rrc_load_depth(ivec2(px.x, min(px.y + 1, hi.y))), rrc_load_depth(ivec2(px.x, min(px.y + 2, hi.y))));
    return r;
}

// The tolerance the ADAPTIVE test adds to the paper's epsilon at pixel px
// (its depth and neighbours: cr) for the fetch at previous-frame sample
// coordinate q, expected depth e: GAIN * (the bilinear residual bound + the
// edge clamp's slope term), at most CAP of the linear depth
// (docs/CONVENTIONS.md, "The ADAPTIVE test").
float rrc_adaptive_widening(ivec2 px, ivec2 size, RrcCross cr, vec2 q, float e) {
    ivec2 hi = size - 1;
    float step = EPS_KIND == RRC_EPS_ABSOLUTE ? pc.eps : 0.0;  // ADAPTIVE takes no host epsilon: pc.eps is the format's step
    float c = rrc_interpolated(cr.c);
    vec3 ax = rrc_axis(rrc_interpolated(cr.h.x), rrc_interpolated(cr.h.y), c, rrc_interpolated(cr.h.z), rrc_interpolated(cr.h.w),
                       px.x == 0 || px.x == hi.x, step);
    vec3 ay = rrc_axis(rrc_interpolated(cr.v.x), rrc_interpolated(cr.v.y), c, rrc_interpolated(cr.v.z), rrc_interpolated(cr.v.w),
                       px.y == 0 || px.y == hi.y, step);
    vec2 p = q - 0.5;
    vec2 f = p - floor(p);
    vec2 overhang = max(max(-p, p - vec2(hi)), vec2(0.0));  // beyond the outermost texel centres: clamped taps
    // One estimate for both axes.  An axis beside a step (a silhouette) borrows
    // the other's only below BORROW of that step: a larger one is likely the
    // step seen obliquely; beside steps on both axes (a corner, a diagonal
    // silhouette) none is trusted.
    bool bx = ax.z > 0.0, by = ay.z > 0.0;
    float curvature = bx ? (by ? 0.0 : max(ax.x, ay.x <= RRC_ADAPTIVE_BORROW * ax.z ? ay.x : 0.0))
                         : (by ? max(ay.x, ax.x <= RRC_ADAPTIVE_BORROW * ay.z ? ax.x : 0.0) : max(ax.x, ay.x));
    float widening = RRC_ADAPTIVE_GAIN * (dot(f * (1.0 - f), vec2(curvature)) + dot(overhang, vec2(ax.y, ay.y)));
    // The kernel's own fp32 error of q (uv_prev's rounding, ~2^-24 of the image) times the slope.
    widening += RRC_ADAPTIVE_POSITION_ULPS * exp2(-24.0) * dot(vec2(size), vec2(ax.y, ay.y));
    if (DEPTH_MODE == RRC_DEPTH_MODE_LINEAR) return min(widening * e * e, RRC_ADAPTIVE_CAP * e);  // |dd| = d^2 |d(1/d)|
    float z_inf = DEPTH_MODE == RRC_DEPTH_MODE_STANDARD ? 1.0 : 0.0;
    return min(widening, RRC_ADAPTIVE_CAP * abs(e - z_inf));
}

struct RrcGeometry {
    bool background;
    bool invalid;  // INVALID_GEOMETRY
    bool hit;
    RrcTaps taps;  // valid coordinates even on a miss (clamped), so loads stay in bounds
};

RrcGeometry rrc_reproject(ivec2 px, ivec2 size) {
    RrcGeometry g;
    vec2 fsize = vec2(size);
    RrcCross cr;  // ADAPTIVE: the depth's cross of neighbours, the centre among them
    if (ADAPTIVE && RRC_TEST) cr = rrc_depth_cross(px, size);
    float d = ADAPTIVE && RRC_TEST ? cr.c : rrc_load_depth(px);
    if (INTEROP && RRC_TEST && rrc_store) {
        rrc_io_store(4u);
        imageStore(u_depth_out, px, vec4(d));
    }
    // Invalid first: only LINEAR's +inf is a (background) depth, any other
    // non-finite depth is invalid geometry.
    g.invalid = rrc_is_invalid_depth(d);
    g.background = !g.invalid && rrc_is_background(d);

    vec2 uv_s = (vec2(px) + 0.5 + pc.jitter.xy) / fsize;
    vec2 uv_prev;
    float expected;  // in depth-mode units (linear for the relative tests)
    float expected_err = 0.0;  // ADAPTIVE, CAMERA on NDC depth: a bound on the fp32 error of `expected`
    float w = 1.0;
    if (SOURCE == RRC_REPROJECTION_MOTION) {
        vec2 m = rrc_load_reprojection(px).xy;
        g.invalid = g.invalid || !rrc_finite4(vec4(m, 0.0, 0.0));
        uv_prev = uv_s + m * pc.motion_scale;
        expected = d;
    } else if (SOURCE == RRC_REPROJECTION_MOTION_DEPTH) {
        vec4 m = rrc_load_reprojection(px);
        g.invalid = g.invalid || !rrc_finite4(vec4(m.xyz, 0.0));
        uv_prev = uv_s + m.xy * pc.motion_scale;
        expected = d + m.z;
    } else {
        vec4 c;
        if (SOURCE == RRC_REPROJECTION_PREV_CLIP) {
            c = rrc_load_reprojection(px);
            g.invalid = g.invalid || !rrc_finite4(c);
        } else {  // CAMERA: static geometry, matrices only
            vec2 ndc = 2.0 * uv_s - 1.0;
            if (DEPTH_MODE == RRC_DEPTH_MODE_LINEAR) {
                // The point on the pixel's ray whose clip w equals d.
                float a = dot(pc.inv_row3, vec4(ndc, 0.0, 1.0));
                c = pc.M * vec4(ndc * d, (1.0 - d * a) / pc.inv_row3.z, d);
            } else {
                vec4 p = vec4(ndc, d, 1.0);
                c = pc.M * p;
                // (M p).z sums four products that may cancel (reversed depth, finite far).
                if (ADAPTIVE) expected_err = RRC_ADAPTIVE_CAMERA_ULPS * exp2(-24.0) * dot(abs(vec4(pc.M[0][2], pc.M[1][2], pc.M[2][2], pc.M[3][2])), abs(p)) / abs(c.w);
            }
        }
        w = c.w;
        uv_prev = (c.xy / c.w + 1.0) * 0.5;
        expected = DEPTH_MODE == RRC_DEPTH_MODE_LINEAR ? c.w : c.z / c.w;
    }

    // Background wins over bad reprojection data: the sky has no history.
    g.invalid = g.invalid && !g.background;

    // Closed square; NaN fails every comparison.  Outside it the taps are
    // taken at the centre so every load stays in bounds.
    bool inside = all(greaterThanEqual(uv_prev, vec2(0.0))) && all(lessThanEqual(uv_prev, vec2(1.0)));
    vec2 q = (inside ? uv_prev : vec2(0.5)) * fsize - pc.jitter.zw;
    g.taps = rrc_taps(q, size);
    g.hit = false;
    if (!RRC_TEST) return g;  // a constant: folded, not a divergent return

#define LOAD_PREV_DEPTH(t) RRC_LOAD(1u, 4u, imageLoad(u_prev_depth, t).r)
    vec4 z = vec4(LOAD_PREV_DEPTH(g.taps.p00), LOAD_PREV_DEPTH(g.taps.p10), LOAD_PREV_DEPTH(g.taps.p01), LOAD_PREV_DEPTH(g.taps.p11));
#undef LOAD_PREV_DEPTH
    bool tap_background = rrc_is_background(z.x) || rrc_is_background(z.y) ||
                          rrc_is_background(z.z) || rrc_is_background(z.w);
    float fetched = DEPTH_MODE == RRC_DEPTH_MODE_LINEAR ? 1.0 / dot(g.taps.w, 1.0 / z) : dot(g.taps.w, z);

    float eps;
    if (EPS_KIND == RRC_EPS_RELATIVE) {
        if (SOURCE == RRC_REPROJECTION_MOTION && DEPTH_MODE != RRC_DEPTH_MODE_LINEAR) {
            fetched = rrc_linearize(fetched);
            expected = rrc_linearize(expected);
        }
        eps = pc.eps * expected;
    } else if (EPS_KIND == RRC_EPS_ULP) {
        eps = pc.eps * rrc_ulp(expected);
    } else {
        eps = pc.eps;
    }
    if (ADAPTIVE) {
        // NDC tests: never below the kernel's own fp32 noise (UNORM24 near z = 1 has ulp ~ step).
        if (EPS_KIND != RRC_EPS_RELATIVE) eps = max(eps, RRC_ADAPTIVE_FLOOR_ULPS * rrc_ulp(expected));
        eps += rrc_adaptive_widening(px, size, cr, q, expected) + expected_err;
    }
    bool nocache = HAS_NOCACHE && rrc_load_nocache(px);
    bool same_object = true;
    if (OBJECT_ID) {
        uint id = RRC_LOAD(1u, 4u, texelFetch(s_object_id, px, 0).r);
        if (INTEROP && rrc_store) {
            rrc_io_store(4u);
            imageStore(u_object_id_out, px, uvec4(id));
        }
#define LOAD_PREV_ID(t) RRC_LOAD(1u, 4u, imageLoad(u_prev_object_id, t).r)
        uvec4 taps = uvec4(LOAD_PREV_ID(g.taps.p00), LOAD_PREV_ID(g.taps.p10), LOAD_PREV_ID(g.taps.p01), LOAD_PREV_ID(g.taps.p11));
#undef LOAD_PREV_ID
        bvec4 foreign = notEqual(taps, uvec4(id)), weighted = greaterThan(g.taps.w, vec4(0.0));
        same_object = !any(bvec4(foreign.x && weighted.x, foreign.y && weighted.y, foreign.z && weighted.z, foreign.w && weighted.w));
    }

    g.hit = pc.prev_valid != 0u && !g.background && !g.invalid && !nocache && w > 0.0 && inside &&
            !tap_background && same_object && abs(fetched - expected) <= eps;
    return g;
}

#endif
