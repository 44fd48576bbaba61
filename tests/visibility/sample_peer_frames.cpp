#include "sample_peer_frames.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrc_sample {

namespace {

const double kInf = std::numeric_limits<double>::infinity();
constexpr double kMixWeight = 1e-3;  // the oracle's tap threshold (oracle.cpp)

}  // namespace

rrc_ref::peers::GBuffer peer_gbuffer(const FrameOutput& out, const glm::dmat4& view_proj, double tan_half_fovy, double n, double f) {
    rrc_ref::peers::GBuffer g;
    g.width = out.width;
    g.height = out.height;
    g.tan_half_fovy = tan_half_fovy;
    const size_t count = g.size();
    g.view_z.assign(count, kInf);
    g.device_z.assign(count, kInf);
    g.normal.assign(count, glm::dvec3(0.0));
    g.z_fwidth.assign(count, 0.0);
    g.n_fwidth.assign(count, 0.0);
    g.background.assign(count, 0);
    for (size_t k = 0; k < count; ++k) {
        if (out.object[k] == 0) {
            g.background[k] = 1;
            continue;
        }
        const glm::dvec4 c = view_proj * glm::dvec4(out.position[4 * k], out.position[4 * k + 1], out.position[4 * k + 2], 1.0);
        g.view_z[k] = (float)c.w;
        const double z = (float)(c.z / c.w);  // the reversed-z value a depth buffer stores
        g.device_z[k] = n * f / (n + z * (f - n));
        g.normal[k] = glm::normalize(glm::dvec3(out.normal[3 * k], out.normal[3 * k + 1], out.normal[3 * k + 2]));
    }
    const int W = g.width, H = g.height;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t k = (size_t)y * W + x;
            if (g.background[k]) continue;
            // The difference to a neighbour on the same object along one axis: forward, else backward.
            auto neighbour = [&](int dx, int dy) -> long {
                for (int s : {1, -1}) {
                    const int nx = x + s * dx, ny = y + s * dy;
                    if (nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
                    const size_t m = (size_t)ny * W + nx;
                    if (out.object[m] == out.object[k]) return (long)m;
                }
                return -1;
            };
            const long mx = neighbour(1, 0), my = neighbour(0, 1);
            glm::dvec3 dn(0.0);
            double dz = 0.0;
            if (mx >= 0) dz = std::max(dz, std::fabs(g.view_z[mx] - g.view_z[k])), dn += glm::abs(g.normal[mx] - g.normal[k]);
            if (my >= 0) dz = std::max(dz, std::fabs(g.view_z[my] - g.view_z[k])), dn += glm::abs(g.normal[my] - g.normal[k]);
            g.z_fwidth[k] = dz;
            g.n_fwidth[k] = glm::length(dn);
        }
    return g;
}

rrc_ref::peers::Reprojection peer_reprojection(const FrameOutput& out, const glm::dmat4& view_proj, const glm::dmat4& prev_view_proj,
                                               const glm::dvec3& prev_eye) {
    rrc_ref::peers::Reprojection r;
    const size_t count = (size_t)out.width * out.height;
    r.qx.assign(count, NAN);
    r.qy.assign(count, NAN);
    r.on_screen.assign(count, 0);
    r.prev_view_z.assign(count, kInf);
    r.view_dir.assign(count, glm::dvec3(0.0));
    r.parallax_px.assign(count, 0.0);
    const glm::dmat4 prev_inv = glm::inverse(prev_view_proj);
    const glm::dvec3 eye(out.eye);
    auto pixel_of = [&](const glm::dvec3& P) {
        const glm::dvec4 c = view_proj * glm::dvec4(P, 1.0);
        return glm::dvec2((c.x / c.w + 1.0) * 0.5 * out.width, (c.y / c.w + 1.0) * 0.5 * out.height);
    };
    for (size_t k = 0; k < count; ++k) {
        const glm::dvec4 pc(out.prev_clip[4 * k], out.prev_clip[4 * k + 1], out.prev_clip[4 * k + 2], out.prev_clip[4 * k + 3]);
        if (out.object[k] == 0 || !(pc.w > 0.0)) continue;
        const double ux = (pc.x / pc.w + 1.0) * 0.5, uy = (pc.y / pc.w + 1.0) * 0.5;
        r.qx[k] = ux * out.width;
        r.qy[k] = uy * out.height;
        r.on_screen[k] = ux >= 0.0 && ux <= 1.0 && uy >= 0.0 && uy <= 1.0;
        r.prev_view_z[k] = pc.w;
        const glm::dvec3 X(out.position[4 * k], out.position[4 * k + 1], out.position[4 * k + 2]);
        const glm::dvec4 xp = prev_inv * pc;
        const glm::dvec3 X_prev = glm::dvec3(xp) / xp.w;
        r.view_dir[k] = glm::normalize(eye - X);
        r.parallax_px[k] = glm::length(pixel_of(eye + (X_prev - prev_eye)) - pixel_of(X));
    }
    return r;
}

void score_peer(PeerScore& s, const std::vector<rrc_ref::peers::Decision>& d, const std::vector<uint8_t>& verdict,
                const std::vector<uint16_t>& object, const std::vector<uint16_t>& prev_object) {
    for (size_t k = 0; k < verdict.size(); ++k) {
        const uint8_t v = verdict[k];
        if (!(v & kVerdictSurface)) continue;  // background and excluded pixels: as the oracle's own counts
        ++s.surface;
        const bool visible = v & kVerdictVisible, straddles = v & kVerdictStraddling, hit = d[k].hit;
        if (visible && !straddles) {
            ++s.clean_visible;
            s.clean_hits += hit;
        }
        if (visible) continue;
        ++s.not_visible;
        if (!hit) continue;
        ++s.false_hits;
        for (int t = 0; t < d[k].taps; ++t)
            if (d[k].tap[t].weight > kMixWeight && !prev_object.empty() && prev_object[d[k].tap[t].texel] != object[k]) {
                ++s.mixing;
                break;
            }
    }
}

std::vector<rrc_ref::peers::Decision> rrc_decisions(const std::vector<uint8_t>& mask, const rrc_ref::peers::Reprojection& r, int W, int H) {
    std::vector<rrc_ref::peers::Decision> d(mask.size());
    for (size_t k = 0; k < mask.size(); ++k) {
        d[k].hit = (mask[k] & RRC_MASK_HIT) != 0;
        if (!d[k].hit || !std::isfinite(r.qx[k])) continue;
        const double px = r.qx[k] - 0.5, py = r.qy[k] - 0.5;
        const int x0 = (int)std::floor(px), y0 = (int)std::floor(py);
        const double fx = px - x0, fy = py - y0;
        for (int t = 0; t < 4; ++t) {
            const int x = std::clamp(x0 + (t & 1), 0, W - 1), y = std::clamp(y0 + (t >> 1), 0, H - 1);
            d[k].tap[d[k].taps++] = {(size_t)y * W + x, ((t & 1) ? fx : 1 - fx) * ((t >> 1) ? fy : 1 - fy)};
        }
    }
    return d;
}

}  // namespace rrc_sample
