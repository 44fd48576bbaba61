// The cached procedural shader of rrc-cache: kOctaves (8 unless the host
// specialises it; README.md, `--octaves`) octaves of 3-D gradient noise at
// the pixel's world position, as a marble-like albedo, lit by the sun
// (Lambert) and a constant ambient.  About 60 ALU operations an octave: at 8
// a few hundred a pixel, like the paper's 215-instruction Perlin shader;
// more octaves make the same shader dearer, to find where the cache pays.
// View-independent, so a reused value is the value the pixel would be shaded
// with (up to the object's motion).
#ifndef RRC_CACHE_PERLIN_GLSL
#define RRC_CACHE_PERLIN_GLSL

layout(set = 0, binding = 0) uniform sampler2D g_position;  // world position, w: object index + 1 (0: sky)
layout(set = 0, binding = 1) uniform sampler2D g_normal;    // world normal

// The octave count: a specialization constant, so the loop below has a
// constant trip count for the compiler at every count (Vulkan spec,
// "Specialization Constants": the module's default is used when the pipeline
// gives none; the host rewrites that default, spec_constant.h).
layout(constant_id = 0) const int kOctaves = 8;

uint perlin_hash(ivec3 p) {
    uint h = uint(p.x) * 73856093u ^ uint(p.y) * 19349663u ^ uint(p.z) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h;
}

vec3 perlin_gradient(ivec3 corner) {
    uint h = perlin_hash(corner);
    return vec3(float(h & 1023u), float((h >> 10) & 1023u), float((h >> 20) & 1023u)) * (2.0 / 1023.0) - 1.0;
}

// The lattice cell of p, its integer coordinates taken modulo 2^32.  Each
// octave scales p by 2.03, so past about 25 octaves floor(p) leaves int's
// range and ivec3(floor(p)) is undefined (SPIR-V, OpConvertFToS: "behavior
// is undefined if Result Type is not wide enough").  Wrapping the cell into [-2^31, 2^31) first is
// exact in float (|c| < 2^31 is left as it is; larger c are multiples of
// 256), leaves every cell of 8 octaves where it was (the same noise as
// before), and keeps the noise continuous: the corners below add 1 with
// int's wrap-around (GLSL 4.50, 4.1.3: the low-order 32 bits) and
// perlin_hash reads them as uint, so the lattice is the integers mod 2^32
// everywhere and a cell's far corner is its wrapped neighbour's near one.
// (Past 2^23 a float has no fraction left: such octaves add 0, at
// amplitudes below 2^-20, and still cost their full work.)
ivec3 perlin_cell(vec3 p) {
    const float period = 4294967296.0;  // 2^32
    vec3 c = floor(p);
    c -= period * round(c / period);
    c -= period * vec3(greaterThanEqual(c, vec3(2147483648.0)));  // round() may leave +2^31: take -2^31
    return ivec3(c);
}

float perlin_noise(vec3 p) {
    ivec3 i = perlin_cell(p);
    vec3 f = fract(p);
    vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    float n000 = dot(perlin_gradient(i), f);
    float n100 = dot(perlin_gradient(i + ivec3(1, 0, 0)), f - vec3(1, 0, 0));
    float n010 = dot(perlin_gradient(i + ivec3(0, 1, 0)), f - vec3(0, 1, 0));
    float n110 = dot(perlin_gradient(i + ivec3(1, 1, 0)), f - vec3(1, 1, 0));
    float n001 = dot(perlin_gradient(i + ivec3(0, 0, 1)), f - vec3(0, 0, 1));
    float n101 = dot(perlin_gradient(i + ivec3(1, 0, 1)), f - vec3(1, 0, 1));
    float n011 = dot(perlin_gradient(i + ivec3(0, 1, 1)), f - vec3(0, 1, 1));
    float n111 = dot(perlin_gradient(i + ivec3(1, 1, 1)), f - vec3(1, 1, 1));
    return mix(mix(mix(n000, n100, u.x), mix(n010, n110, u.x), u.y), mix(mix(n001, n101, u.x), mix(n011, n111, u.x), u.y), u.z);
}

// kOctaves octaves of fractional Brownian motion.
float perlin_fbm(vec3 p) {
    float sum = 0.0, amplitude = 0.5;
    for (int o = 0; o < kOctaves; ++o) {
        sum += amplitude * perlin_noise(p);
        p = p * 2.03 + vec3(17.1, 5.3, 11.7);
        amplitude *= 0.5;
    }
    return sum;
}

vec4 perlin_shade(ivec2 px) {
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w == 0.0) return vec4(0.45, 0.6, 0.85, 1.0);  // the sky
    vec3 n = normalize(texelFetch(g_normal, px, 0).xyz);
    float m = perlin_fbm(pos.xyz * 2.5);
    float veins = 0.5 + 0.5 * sin(pos.x * 3.0 + 12.0 * m);
    vec3 albedo = mix(vec3(0.85, 0.82, 0.76), vec3(0.35, 0.28, 0.22), veins);
    float sun = max(dot(n, normalize(vec3(0.4, 0.8, 0.3))), 0.0);
    return vec4(albedo * (0.25 + 0.75 * sun), 1.0);
}

#endif
