// The peers' validity tests (peer_tests.h), each from its public source.
// Sources read (file, repository, commit):
//   NRD ReBLUR  Shaders/Include/REBLUR/REBLUR_DiffuseSpecular_TemporalAccumulation.hlsli and
//               Shaders/Include/REBLUR/REBLUR_Common.hlsli, NVIDIAGameWorks/RayTracingDenoiser
//               commit 0ad8056da40b89bcda372e17e4fd3fda47019007 (NRD 4.x); defaults from
//               Include/NRDSettings.h (CommonSettings::disocclusionThreshold = 0.01f,
//               no disocclusion-threshold mix, material masks off).
//   NRD ReLAX   Shaders/Include/RELAX/RELAX_DiffuseSpecular_TemporalAccumulation.hlsli, same
//               repository, commit 14037de2fa1780d16a4b7a6ca75a53cdd226ee5a
//               (loadSurfaceMotionBasedPrevData).
//   SVGF        Source/RenderPasses/SVGFPass/SVGFReproject.ps.slang (isReprjValid, loadPrevData),
//               NVIDIAGameWorks/Falcor commit 5e6842eed2d5a5692260204c908414cfb8303942; its
//               guides from Source/RenderPasses/GBuffer/GBuffer/GBufferRaster.3d.slang
//               (linearZ derivative max(|ddx|, |ddy|), normal fwidth length(fwidth(N))).
//   FSR2        src/ffx-fsr2-api/shaders/ffx_fsr2_depth_clip.h at GPUOpen-Effects/FidelityFX-FSR2
//               commit 4b5071f062db47b96eca915cedf2cc075f2ff229 (the 2.2 line: DepthClipBaseScale 4
//               ramped by saturate(diff^2), Ksep 1.37e-5 for inverted depth, 4 x 1.37e-5 otherwise) and
//               ffx_fsr2_reconstruct_dilated_velocity_and_previous_depth.h (commit
//               c8fc17d281665927e414b6b8117873cccbac0990); reconstructedDepthBilinearWeightThreshold
//               0.05 (ffx_fsr2_common.h of the same line); hit/miss: the lock rule's
//               depthClipThreshold 0.99 (ffx_fsr2_postprocess_lock_status.h).
// Simplifications common to all (stated in docs/measurements/COMPARISON.md, "How the peers were rebuilt"):
//   * double precision throughout; no fp16 packing of normals or depth (NRD, Falcor pack them).
//   * every test gets the same exact previous texel coordinate q (peer_tests.h).
//   * a pixel on the background is never a hit (the oracle calls any hit there false).
//   * NRD: only the surface-motion history of the diffuse signal; the Catmull-Rom history fetch
//     that NRD uses when all 12 taps of its footprint pass is reported as its bilinear footprint.
//   * FSR2: native resolution (render size = display size); its colour history is taken as a
//     bilinear fetch at the reprojected position (FSR2 resamples a display-resolution history).
#include "peer_tests.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrc_ref {
namespace peers {

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kPi = 3.14159265358979323846;

double saturate(double x) { return std::min(std::max(x, 0.0), 1.0); }
double lerp(double a, double b, double t) { return a + (b - a) * t; }
double linear_step(double a, double b, double x) { return saturate((x - a) / (b - a)); }
double frac(double x) { return x - std::floor(x); }

int clampi(int v, int lo, int hi) { return std::min(std::max(v, lo), hi); }

struct Footprint {
    int x0, y0;     // floor(q - 0.5): the bilinear origin
    double fx, fy;  // its fractions
    double w[4];    // (0,0), (1,0), (0,1), (1,1)
};

Footprint footprint(double qx, double qy) {
    Footprint f;
    const double px = qx - 0.5, py = qy - 0.5;
    f.x0 = static_cast<int>(std::floor(px));
    f.y0 = static_cast<int>(std::floor(py));
    f.fx = px - std::floor(px);
    f.fy = py - std::floor(py);
    f.w[0] = (1 - f.fx) * (1 - f.fy);
    f.w[1] = f.fx * (1 - f.fy);
    f.w[2] = (1 - f.fx) * f.fy;
    f.w[3] = f.fx * f.fy;
    return f;
}

// Tap t of a footprint, clamped to the image (NRD gathers with gNearestClamp).
size_t clamped_texel(const Footprint& f, int t, int W, int H) {
    const int x = clampi(f.x0 + (t & 1), 0, W - 1), y = clampi(f.y0 + (t >> 1), 0, H - 1);
    return static_cast<size_t>(y) * W + x;
}

// Weights w_k * valid_k normalised; fewer than 1e-4 in all: no history (REBLUR_Common.hlsli,
// _BilinearFilterWithCustomWeights_Color: "sum < 0.0001 ? 0 : color * rcp(sum)").
void set_weighted(Decision& d, const Footprint& f, const double valid[4], int W, int H) {
    double sum = 0.0;
    for (int t = 0; t < 4; ++t) sum += f.w[t] * valid[t];
    d.taps = 0;
    if (sum < 1e-4) return;
    for (int t = 0; t < 4; ++t)
        if (f.w[t] * valid[t] > 0.0) d.tap[d.taps++] = {clamped_texel(f, t, W, H), f.w[t] * valid[t] / sum};
}

void set_bilinear(Decision& d, const Footprint& f, int W, int H) {
    const double all[4] = {1, 1, 1, 1};
    set_weighted(d, f, all, W, H);
}

// ---- NRD ------------------------------------------------------------------

// Navg: the current 2x2 normals at (i-1 .. i, j-1 .. j), clamped to the rect (Preload clamps), unnormalised.
glm::dvec3 current_navg(const GBuffer& g, int i, int j) {
    glm::dvec3 n(0.0);
    for (int dy = -1; dy <= 0; ++dy)
        for (int dx = -1; dx <= 0; ++dx)
            n += g.normal[static_cast<size_t>(clampi(j + dy, 0, g.height - 1)) * g.width + clampi(i + dx, 0, g.width - 1)];
    return n / 4.0;
}

// prevNavg: the previous normals of the bilinear footprint averaged (a linear sample at origin + 1).
glm::dvec3 footprint_navg(const GBuffer& prev, const Footprint& f) {
    glm::dvec3 n(0.0);
    for (int t = 0; t < 4; ++t) n += prev.normal[clamped_texel(f, t, prev.width, prev.height)];
    return n / 4.0;
}

Decision reblur(const GBuffer& cur, const Reprojection& r, const GBuffer& prev, int i, int j) {
    Decision d;
    const size_t k = static_cast<size_t>(j) * cur.width + i;
    const int W = prev.width, H = prev.height;
    if (!std::isfinite(r.qx[k]) || !std::isfinite(r.qy[k])) return d;
    const glm::dvec3 N = cur.normal[k];
    const double NoV = std::fabs(glm::dot(N, r.view_dir[k]));
    const double parallax = r.parallax_px[k];
    double threshold = reblur_threshold(nrd_frustum_size(cur.width, cur.height, cur.tan_half_fovy, cur.view_z[k]), NoV, parallax);
    // The footprint of saturate(smbPixelUv): q clamped to [0, size].
    const Footprint f = footprint(std::min(std::max(r.qx[k], 0.0), double(W)), std::min(std::max(r.qy[k], 0.0), double(H)));
    // "isInScreenAndNotBackfacing": frontFacing ramps from cos 135 deg to cos 91 deg as the parallax
    // goes from 0.5 to 1 pixel.
    const double front_facing = lerp(std::cos(135.0 * kPi / 180.0), std::cos(91.0 * kPi / 180.0), linear_step(0.5, 1.0, parallax));
    const bool not_backfacing = glm::dot(footprint_navg(prev, f), current_navg(cur, i, j)) > front_facing;
    if (!(r.on_screen[k] && not_backfacing)) threshold = -1.0;
    double valid[4];
    for (int t = 0; t < 4; ++t)  // step(planeDist, threshold): planeDist <= threshold
        valid[t] = std::fabs(prev.view_z[clamped_texel(f, t, W, H)] - r.prev_view_z[k]) <= threshold ? 1.0 : 0.0;
    set_weighted(d, f, valid, W, H);
    d.hit = d.taps > 0;  // the history is used where its custom weights sum to 1e-4 or more
    return d;
}

Decision relax(const GBuffer& cur, const Reprojection& r, const GBuffer& prev, int i, int j) {
    Decision d;
    const size_t k = static_cast<size_t>(j) * cur.width + i;
    const int W = prev.width, H = prev.height;
    if (!std::isfinite(r.qx[k]) || !std::isfinite(r.qy[k])) return d;
    const glm::dvec3 N = cur.normal[k];
    // ReLAX's NdotV is taken as |N.V| (as ReBLUR's NoV); ReLAX does not floor it at 0.05.
    const double NoV = std::fabs(glm::dot(N, r.view_dir[k]));
    const double threshold = relax_threshold(nrd_frustum_size(cur.width, cur.height, cur.tan_half_fovy, cur.view_z[k]), NoV, r.parallax_px[k]);
    const Footprint f = footprint(r.qx[k], r.qy[k]);  // bilinearOrigin = floor(prevPixelPos - 0.5), no saturate
    double valid[4];
    for (int t = 0; t < 4; ++t)
        valid[t] = std::fabs(prev.view_z[clamped_texel(f, t, W, H)] - r.prev_view_z[k]) <= threshold ? 1.0 : 0.0;
    // "Reject backfacing history: if angle between current normal and previous normal is larger than 90 deg".
    if (glm::dot(N, footprint_navg(prev, f)) < 0.0) std::fill(valid, valid + 4, 0.0);
    // bilinearTapsValid *= IsInScreen(prevUVSMB).  Reprojection-test skipping without motion is
    // off (RelaxSettings' default), so every tap is tested.
    if (!r.on_screen[k]) std::fill(valid, valid + 4, 0.0);
    set_weighted(d, f, valid, W, H);
    // "if (!any(bilinearTapsValid)) reprojectionFound = 0": any passing tap keeps history, even
    // one whose bilinear weight is 0 (its history is then the others', or none).
    d.hit = valid[0] + valid[1] + valid[2] + valid[3] > 0.0;
    return d;
}

// ---- SVGF -----------------------------------------------------------------

// HLSL int() truncates toward zero; a load outside the texture reads 0 (D3D's rule).
int trunc_int(double v) { return static_cast<int>(std::trunc(v)); }

struct SvgfPrev {
    double z;
    glm::dvec3 n;
};
SvgfPrev svgf_load(const GBuffer& prev, int x, int y) {
    if (x < 0 || y < 0 || x >= prev.width || y >= prev.height) return {0.0, glm::dvec3(0.0)};
    const size_t t = static_cast<size_t>(y) * prev.width + x;
    return {prev.view_z[t], prev.normal[t]};
}

bool svgf_valid(int cx, int cy, int W, int H, double z, double z_prev, double fwidth_z, const glm::dvec3& n, const glm::dvec3& n_prev,
                double fwidth_n) {
    if (cx < 1 || cy < 1 || cx > W - 1 || cy > H - 1) return false;        // reprojected pixel inside the screen
    if (std::fabs(z_prev - z) / (fwidth_z + 1e-2) > 10.0) return false;    // depth deviation
    if (glm::distance(n, n_prev) / (fwidth_n + 1e-2) > 16.0) return false;  // normal compatibility
    return !std::isnan(z_prev - z);
}

Decision svgf(const GBuffer& cur, const Reprojection& r, const GBuffer& prev, int i, int j) {
    Decision d;
    const size_t k = static_cast<size_t>(j) * cur.width + i;
    const int W = prev.width, H = prev.height;
    if (!std::isfinite(r.qx[k]) || !std::isfinite(r.qy[k])) return d;
    // posPrev = floor(posH) + motion * dim = q - 0.5; iposPrev = int(ipos + motion * dim + 0.5) = int(q).
    const double ppx = r.qx[k] - 0.5, ppy = r.qy[k] - 0.5;
    const int ix = trunc_int(r.qx[k]), iy = trunc_int(r.qy[k]);
    const double z = cur.view_z[k], fz = cur.z_fwidth[k], fn = cur.n_fwidth[k];
    const glm::dvec3 n = cur.normal[k];
    const int bx = trunc_int(ppx), by = trunc_int(ppy);
    const double x = frac(ppx), y = frac(ppy);
    const double w[4] = {(1 - x) * (1 - y), x * (1 - y), (1 - x) * y, x * y};
    bool v[4];
    double sumw = 0.0;
    for (int t = 0; t < 4; ++t) {
        const SvgfPrev p = svgf_load(prev, bx + (t & 1), by + (t >> 1));
        v[t] = svgf_valid(ix, iy, W, H, z, p.z, fz, n, p.n, fn);
        if (v[t]) sumw += w[t];
    }
    // "redistribute weights in case not all taps were used": valid = sumw >= 0.01.
    if (sumw >= 0.01) {
        for (int t = 0; t < 4; ++t) {
            const int tx = bx + (t & 1), ty = by + (t >> 1);
            if (v[t] && w[t] > 0.0 && tx >= 0 && ty >= 0 && tx < W && ty < H)
                d.tap[d.taps++] = {static_cast<size_t>(ty) * W + tx, w[t] / sumw};
        }
        d.hit = true;
        return d;
    }
    // The cross-bilateral fallback: every valid texel of the 3x3 around iposPrev, equal weights.
    int n_valid = 0;
    size_t texels[9];
    for (int yy = -1; yy <= 1; ++yy)
        for (int xx = -1; xx <= 1; ++xx) {
            const int px = ix + xx, py = iy + yy;
            const SvgfPrev p = svgf_load(prev, px, py);
            if (svgf_valid(ix, iy, W, H, z, p.z, fz, n, p.n, fn) && px >= 0 && py >= 0 && px < W && py < H)
                texels[n_valid++] = static_cast<size_t>(py) * W + px;
        }
    for (int t = 0; t < n_valid; ++t) d.tap[d.taps++] = {texels[t], 1.0 / n_valid};
    d.hit = n_valid > 0;
    return d;
}

// ---- FSR2 -----------------------------------------------------------------

const double kReconstructedDepthBilinearWeightThreshold = 0.05;
const double kDepthClipBaseScale = 4.0;
const double kDepthClipThreshold = 0.99;

std::vector<Decision> fsr2(const GBuffer& cur, const Reprojection& r, const Options& o) {
    const int W = cur.width, H = cur.height;
    const size_t n = cur.size();
    std::vector<Decision> out(n);
    // FindNearestDepth: the nearest (smallest view depth; the device compare is monotonic in it)
    // of the 3x3, on screen, in FSR2's offset order (strictly nearer replaces); the dilated motion
    // is that pixel's.  Motion = q - pixel centre, here in texels.
    static const int kOffsets[9][2] = {{0, 0}, {1, 0}, {0, 1}, {0, -1}, {-1, 0}, {-1, 1}, {1, 1}, {-1, -1}, {1, -1}};
    std::vector<double> dil_z(n), mvx(n), mvy(n);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            int bi = i, bj = j;
            double best = cur.device_z[static_cast<size_t>(j) * W + i];
            for (int s = 1; s < 9; ++s) {
                const int x = i + kOffsets[s][0], y = j + kOffsets[s][1];
                if (x < 0 || y < 0 || x >= W || y >= H) continue;
                const double z = cur.device_z[static_cast<size_t>(y) * W + x];
                if (z < best) best = z, bi = x, bj = y;
            }
            const size_t k = static_cast<size_t>(j) * W + i, nk = static_cast<size_t>(bj) * W + bi;
            dil_z[k] = best;
            mvx[k] = r.qx[nk] - (bi + 0.5);
            mvy[k] = r.qy[nk] - (bj + 0.5);
        }
    // ReconstructPrevDepth: each pixel scatters its dilated depth to the taps of its reprojected
    // footprint whose weight exceeds the threshold, keeping the nearest (an atomic min / max of the
    // device depth).  The buffer starts cleared to the far value: +inf here.
    std::vector<double> recon(n, kInf);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const size_t k = static_cast<size_t>(j) * W + i;
            if (!std::isfinite(mvx[k]) || !std::isfinite(mvy[k])) continue;
            const Footprint f = footprint(i + 0.5 + mvx[k], j + 0.5 + mvy[k]);
            for (int t = 0; t < 4; ++t) {
                const int x = f.x0 + (t & 1), y = f.y0 + (t >> 1);
                if (f.w[t] > kReconstructedDepthBilinearWeightThreshold && x >= 0 && y >= 0 && x < W && y < H) {
                    double& slot = recon[static_cast<size_t>(y) * W + x];
                    slot = std::min(slot, dil_z[k]);
                }
            }
        }
    // DepthClip: the dilated depth and motion of the pixel against the reconstructed depth.
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const size_t k = static_cast<size_t>(j) * W + i;
            Decision& d = out[k];
            if (cur.background[k] || !std::isfinite(mvx[k]) || !std::isfinite(mvy[k])) continue;
            const double ux = i + 0.5 + mvx[k], uy = j + 0.5 + mvy[k];
            // bIsExistingSample: the reprojected position lies on the screen.
            if (ux < 0.0 || uy < 0.0 || ux > W || uy > H) continue;
            const Footprint f = footprint(ux, uy);
            double clip = 0.0, wsum = 0.0;
            for (int t = 0; t < 4; ++t) {
                const int x = f.x0 + (t & 1), y = f.y0 + (t >> 1);
                if (x < 0 || y < 0 || x >= W || y >= H || !(f.w[t] > kReconstructedDepthBilinearWeightThreshold)) continue;
                clip += f.w[t] * fsr2_sample_depth_clip(dil_z[k], recon[static_cast<size_t>(y) * W + x], cur.tan_half_fovy, W,
                                                        o.inverted_depth);
                wsum += f.w[t];
            }
            const double depth_clip = wsum > 0.0 ? clip / wsum : kDepthClipBaseScale;
            // FSR2 makes no binary decision: the accumulate pass reads saturate(depth clip) (1 keeps the
            // history, lower values shorten it).  Its own line between trusted and not is the lock
            // rule of ffx_fsr2_postprocess_lock_status.h (same commit line), which kills a lock where
            // the depth clip is below depthClipThreshold = 0.99: a hit here is >= 0.99.
            d.hit = saturate(depth_clip) >= kDepthClipThreshold;
            if (d.hit) set_bilinear(d, f, W, H);
        }
    return out;
}

// ---- The relative 1 % test --------------------------------------------------

Decision relative(const GBuffer& cur, const Reprojection& r, const GBuffer& prev, int i, int j) {
    Decision d;
    const size_t k = static_cast<size_t>(j) * cur.width + i;
    if (!r.on_screen[k]) return d;
    const Footprint f = footprint(r.qx[k], r.qy[k]);
    double fetched = 0.0;
    for (int t = 0; t < 4; ++t)
        if (f.w[t] > 0.0) fetched += f.w[t] * prev.device_z[clamped_texel(f, t, prev.width, prev.height)];
    const double e = r.prev_view_z[k];
    d.hit = std::fabs(fetched - e) <= 0.01 * e;  // inf or NaN fails
    if (d.hit) set_bilinear(d, f, prev.width, prev.height);
    return d;
}

}  // namespace

const char* peer_name(PeerTest t) {
    switch (t) {
        case PeerTest::NRD_REBLUR: return "nrd_reblur";
        case PeerTest::NRD_RELAX: return "nrd_relax";
        case PeerTest::SVGF: return "svgf";
        case PeerTest::FSR2: return "fsr2";
        default: return "relative_1pc";
    }
}

double nrd_frustum_size(int width, int height, double tan_half_fovy, double view_z) {
    // gMinRectDimMulUnproject = min(rectW, rectH) * unproject, unproject = 1 / (0.5 rectH |P11|),
    // P11 = 1 / tan(fovy / 2); GetFrustumSize multiplies it by viewZ (perspective).
    const double unproject = 2.0 * tan_half_fovy / height;
    return std::min(width, height) * unproject * view_z;
}

double reblur_threshold(double frustum_size, double n_dot_v, double parallax_px) {
    return 0.01 * frustum_size / lerp(0.05 + 0.95 * n_dot_v, 1.0, saturate(parallax_px / 30.0));
}

double relax_threshold(double frustum_size, double n_dot_v, double parallax_px) {
    return 0.01 * frustum_size / lerp(n_dot_v, 1.0, saturate(parallax_px / 30.0));
}

double fsr2_sample_depth_clip(double current_view_z, double prev_view_z, double tan_half_fovy, int width, bool inverted_depth) {
    const double half_viewport_width = width * 0.5;
    const double depth_threshold = std::min(current_view_z, prev_view_z);
    const double ksep = inverted_depth ? 1.37e-5 : 4.0 * 1.37e-5;  // "Arbitrary hack to make normal depth work better"
    const double required = ksep * depth_threshold * tan_half_fovy * half_viewport_width;
    const double diff = current_view_z - prev_view_z;
    const double factor = diff > 0.0 ? saturate(required / diff) : 1.0;
    return factor * lerp(1.0, kDepthClipBaseScale, saturate(diff * diff));
}

std::vector<Decision> run_peer_test(PeerTest test, const GBuffer& cur, const Reprojection& r, const GBuffer& prev, const Options& options) {
    if (test == PeerTest::FSR2) return fsr2(cur, r, options);
    std::vector<Decision> out(cur.size());
    for (int j = 0; j < cur.height; ++j)
        for (int i = 0; i < cur.width; ++i) {
            const size_t k = static_cast<size_t>(j) * cur.width + i;
            if (cur.background[k]) continue;
            switch (test) {
                case PeerTest::NRD_REBLUR: out[k] = reblur(cur, r, prev, i, j); break;
                case PeerTest::NRD_RELAX: out[k] = relax(cur, r, prev, i, j); break;
                case PeerTest::SVGF: out[k] = svgf(cur, r, prev, i, j); break;
                default: out[k] = relative(cur, r, prev, i, j); break;
            }
        }
    return out;
}

}  // namespace peers
}  // namespace rrc_ref
