// The procedural environment map and the bump-mapped mirror sphere.
#ifndef RRC_SAMPLE_ENV_GLSL
#define RRC_SAMPLE_ENV_GLSL

// The environment's constants, read by env_radiance and its two smoothed forms below.
const vec3 ENV_SKY_HORIZON = vec3(0.78, 0.86, 1.0);  // the sky's colour at the horizon ...
const vec3 ENV_SKY_ZENITH = vec3(0.22, 0.42, 0.85);  // ... and overhead, mixed by sqrt(d.y)
const float ENV_BAND_TOP = 0.07;                     // the banners: 0 <= d.y < this
const float ENV_BAND_SECTORS = 12.0;                 // banners about the horizon, warm and cool alternating
const vec3 ENV_BAND_WARM = vec3(1.1, 0.55, 0.18);
const vec3 ENV_BAND_COOL = vec3(0.18, 0.6, 0.32);
const vec3 ENV_SUN = vec3(1.6, 1.4, 1.0);            // the sun's highlight: ENV_SUN * max(d . sun, 0)^ENV_SUN_POWER
const float ENV_SUN_POWER = 200.0;
const float ENV_CHECKER_SCALE = 1.5;                 // checkers a unit of the ground plane y = -1 (g = d.xz / -d.y)
const float ENV_GROUND_MIN_DEPTH = 0.05;             // -d.y is clamped to this before the ground is projected
const vec3 ENV_GROUND_DARK = vec3(0.12, 0.1, 0.09);
const vec3 ENV_GROUND_LIGHT = vec3(0.6, 0.56, 0.5);

// The map's own frame: the moving light (--light-speed) turns the map about +y by u.bump.z
// radians with the sun (frame_state.cpp), so a world direction is turned back by it.
vec3 env_map_frame(vec3 d_world) {
    if (u.bump.z == 0.0) return d_world;
    float c = cos(u.bump.z), s = sin(u.bump.z);
    return vec3(c * d_world.x - s * d_world.z, d_world.y, s * d_world.x + c * d_world.z);
}

// Radiance from direction d: a sky with a band of coloured banners along the
// horizon and a sun, over a checkered ground.  Hard edges on purpose: a
// bumpy mirror turns them into sub-pixel detail that one sample aliases.
// The sun's highlight follows u.sun_dir, already turned with the map.
vec3 env_radiance(vec3 d_world) {
    d_world = normalize(d_world);
    vec3 d = env_map_frame(d_world);
    if (d.y >= 0.0) {
        vec3 sky = mix(ENV_SKY_HORIZON, ENV_SKY_ZENITH, sqrt(d.y));
        float az = atan(d.z, d.x) * (ENV_BAND_SECTORS / (2.0 * PI));
        bool warm = fract(az) < 0.5;
        if (d.y < ENV_BAND_TOP) sky = warm ? ENV_BAND_WARM : ENV_BAND_COOL;
        float s = max(dot(d_world, u.sun_dir.xyz), 0.0);
        sky += ENV_SUN * pow(s, ENV_SUN_POWER);
        return sky;
    }
    vec2 g = d.xz / max(-d.y, ENV_GROUND_MIN_DEPTH);
    float c = mod(floor(g.x * ENV_CHECKER_SCALE) + floor(g.y * ENV_CHECKER_SCALE), 2.0);
    return mix(ENV_GROUND_DARK, ENV_GROUND_LIGHT, c);
}

// The environment without its hard edges: the sky's gradient, the banners'
// and the checkers' mean colours, blended across the horizon over 0.1 of d.y,
// no sun.  Smooth where env_radiance is not (the env residual's smooth base).
vec3 env_smooth(vec3 d_world) {
    vec3 d = normalize(d_world);  // the map's turn (u.bump.z) changes nothing here but the sun's
    vec3 sky = mix(ENV_SKY_HORIZON, ENV_SKY_ZENITH, sqrt(max(d.y, 0.0)));
    vec3 banners = 0.5 * (ENV_BAND_WARM + ENV_BAND_COOL);
    vec3 ground = 0.5 * (ENV_GROUND_DARK + ENV_GROUND_LIGHT);
    vec3 upper = mix(banners, sky, smoothstep(0.02, 0.12, d.y));
    return mix(ground, upper, smoothstep(-0.05, 0.05, d.y));
}

// The mean over [x - h, x + h] of the square wave that is 1 where fract(x) < 1/2 and 0
// elsewhere (its integral: floor(x)/2 + min(fract(x), 1/2)).
float square_wave_box(float x, float h) {
    if (h < 1e-5) return fract(x) < 0.5 ? 1.0 : 0.0;
    float a = x - h, b = x + h;
    float ia = floor(a) * 0.5 + min(fract(a), 0.5), ib = floor(b) * 0.5 + min(fract(b), 0.5);
    return (ib - ia) / (2.0 * h);
}

// env_radiance box-filtered over an angular footprint of width w radians about d (the env
// residual's `filtered` base, README.md "The env residual"): each hard edge is averaged over
// the footprint, separably and to first order in w: the ground, the banners and the sky
// weighted by the share of [d.y - w/2, d.y + w/2] each covers; the banners' colours by the
// share of the footprint's azimuths that are warm; the checkers by the box means of their two
// square waves (on the ground plane, where the footprint widens by 1 + |g|^2); the sun as it is.
vec3 env_filtered(vec3 d_world, float w) {
    d_world = normalize(d_world);
    vec3 d = env_map_frame(d_world);
    float h = max(0.5 * w, 1e-5);
    float ground_share = clamp((h - d.y) / (2.0 * h), 0.0, 1.0);
    float sky_share = clamp((d.y + h - ENV_BAND_TOP) / (2.0 * h), 0.0, 1.0);
    float band_share = max(1.0 - ground_share - sky_share, 0.0);
    vec3 sky = mix(ENV_SKY_HORIZON, ENV_SKY_ZENITH, sqrt(max(d.y, 0.0)));
    float az = atan(d.z, d.x) * (ENV_BAND_SECTORS / (2.0 * PI));
    float az_h = h * ENV_BAND_SECTORS / (2.0 * PI * max(length(d.xz), 1e-3));
    vec3 band = mix(ENV_BAND_COOL, ENV_BAND_WARM, square_wave_box(az, az_h));
    vec2 g = d.xz / max(-d.y, ENV_GROUND_MIN_DEPTH);
    float g_h = ENV_CHECKER_SCALE * h * (1.0 + dot(g, g));
    // floor(s g) odd (s = ENV_CHECKER_SCALE): the square wave of s g / 2 is 0; the checker is the two waves' xor.
    vec2 odd = vec2(1.0 - square_wave_box(0.5 * ENV_CHECKER_SCALE * g.x, 0.5 * g_h),
                    1.0 - square_wave_box(0.5 * ENV_CHECKER_SCALE * g.y, 0.5 * g_h));
    float c = odd.x * (1.0 - odd.y) + (1.0 - odd.x) * odd.y;
    vec3 ground = mix(ENV_GROUND_DARK, ENV_GROUND_LIGHT, c);
    float s = max(dot(d_world, u.sun_dir.xyz), 0.0);
    vec3 above = (sky * sky_share + band * band_share) / max(sky_share + band_share, 1e-6) + ENV_SUN * pow(s, ENV_SUN_POWER);
    return mix(above, ground, ground_share);
}

// The bumped normal of the sphere at unit normal n: height h(p) =
// sin(Fx) sin(Fy) sin(Fz) / F on the object-space point p = n * radius.
vec3 bumped_normal(vec3 n) {
    float F = u.bump.x, k = u.bump.y;
    vec3 q = n * u.sphere.w * F;
    vec3 s = sin(q), c = cos(q);
    vec3 g = vec3(c.x * s.y * s.z, s.x * c.y * s.z, s.x * s.y * c.z);
    g -= dot(g, n) * n;  // tangential part
    return normalize(n - k * g);
}

// The colour the mirror sphere shows along a camera ray through ndc (sub-pixel
// position): the ray is intersected with the analytic sphere (rays that pass
// the silhouette are clamped to the grazing point), the bumped normal (or,
// bumped false, the sphere's own) reflects it into the environment (or, with
// the frozen mirror view, the direction from u.mirror_eye to the point).
vec3 sphere_reflection(vec2 ndc, bool bumped) {
    vec4 far_point = u.inv_view_proj * vec4(ndc, 0.5, 1.0);
    vec3 o = u.camera_pos.xyz;
    vec3 d = normalize(far_point.xyz / far_point.w - o);
    vec3 oc = o - u.sphere.xyz;
    float b = dot(oc, d);
    float disc = max(b * b - (dot(oc, oc) - u.sphere.w * u.sphere.w), 0.0);
    float t = -b - sqrt(disc);
    vec3 n = normalize(o + t * d - u.sphere.xyz);
    vec3 nb = bumped ? bumped_normal(n) : n;
    // The frozen mirror view (--frozen-mirror-view): reflect the direction from a fixed eye
    // to the surface point instead of the camera ray's, so the point's colour stays put.
    vec3 v = u.mirror_eye.w != 0.0 ? normalize(o + t * d - u.mirror_eye.xyz) : d;
    vec3 r = reflect(v, nb);
    if (dot(r, n) < 0.0) r = reflect(r, n);  // keep reflections above the geometric surface
    return r;
}
vec3 sphere_sample(vec2 ndc, bool bumped, bool smooth_env) {
    vec3 r = sphere_reflection(ndc, bumped);
    return smooth_env ? env_smooth(r) : env_radiance(r);
}
// The env residual's `filtered` base: the mean over the pixel's four quarter-pixel centres
// (offsets of +-1/4 pixel in x and y) of each one's reflection into env_filtered over its
// half-pixel cell, whose width is the reflection's turn to the neighbouring centre in x or in y
// (half a pixel away), the larger: four reflections, as many as the signal's k = 4 rays.
vec3 sphere_filtered(vec2 ndc, vec2 pixel) {
    vec3 r[4];
    for (int i = 0; i < 4; ++i)
        r[i] = sphere_reflection(ndc + 0.25 * pixel * vec2((i & 1) != 0 ? 1.0 : -1.0, (i & 2) != 0 ? 1.0 : -1.0), true);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        float wx = length(r[i ^ 1] - r[i]), wy = length(r[i ^ 2] - r[i]);
        sum += env_filtered(r[i], max(wx, wy));
    }
    return 0.25 * sum;
}
vec3 sphere_sample(vec2 ndc) { return sphere_sample(ndc, true, false); }

#endif
