// The view-dependent history's view turn (docs/CONVENTIONS.md, "The
// view-dependent history"): the angle theta between the directions from this
// frame's eye and from the previous eye to the pixel's surface point, from
// the view buffer (rrc_kernel_interface.h, RRC_BINDING_VIEW).  Each channel
// with a view lobe alpha caps its age at floor(alpha / (theta + phi)), phi
// the lighting's turn (the view buffer's d.w; rrc_module_frame.comp adds it,
// rrc_channel.glsl caps).  Included by rrc_module_frame.comp after rrc_reproject.glsl.
#ifndef RRC_VIEW_LOBE_GLSL
#define RRC_VIEW_LOBE_GLSL

// theta at pixel px, or 0 where it is undefined (background or invalid depth,
// the point on either eye, a non-finite result): 0 caps nothing.
float rrc_view_turn(ivec2 px, ivec2 size) {
    float d = rrc_load_depth(px);
    if (rrc_is_invalid_depth(d) || rrc_is_background(d)) return 0.0;
    // The pixel's sample position in clip space, as the CAMERA source forms it (rrc_reproject.glsl).
    vec2 ndc = 2.0 * ((vec2(px) + 0.5 + pc.jitter.xy) / vec2(size)) - 1.0;
    mat4 Q = u_view.Q;
    vec4 c;
    if (DEPTH_MODE == RRC_DEPTH_MODE_LINEAR) {
        // The point on the pixel's ray whose clip w is d; Q's row 3 is inverse(VP_cur)'s.
        vec4 row3 = vec4(Q[0][3], Q[1][3], Q[2][3], Q[3][3]);
        float a = dot(row3, vec4(ndc, 0.0, 1.0));
        c = vec4(ndc * d, (1.0 - d * a) / row3.z, d);
    } else {
        c = vec4(ndc, d, 1.0);
    }
    vec4 X = Q * c;
    vec3 a = X.xyz / X.w;       // P - C
    vec3 b = a - u_view.d.xyz;  // P - C_prev
    // atan2(|a x b|, a . b): accurate at the small angles that matter; |a x b| = |a x d|.
    float s = length(cross(a, u_view.d.xyz)), t = dot(a, b);
    bool defined = dot(a, a) > 0.0 && dot(b, b) > 0.0 && rrc_finite(s) && rrc_finite(t) && (s > 0.0 || t > 0.0);
    return defined && s > 0.0 ? atan(s, t) : 0.0;
}

#endif
