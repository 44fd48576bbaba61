// rrc-make-demo-sequence: writes a small synthetic input sequence for
// rrc-accumulate: a sphere on a ground plane seen by a slowly orbiting
// camera, ray traced analytically in double precision.
//
//   rrc-make-demo-sequence DIR [--frames N] [--first F] [--size WxH] [--seed S] [--check-options]
//
// DIR/frame_%04d.exr holds Z (reversed-Z float NDC depth, background 0),
// prevclip.X/Y/Z/W, mv.X/Y (uv_prev - uv_cur) and mv.Z (depth change), a
// noisy shadow.Y (soft disc shadow + uniform noise) and a noisy
// color.R/G/B/A; DIR/camera.json maps each frame to its view_proj
// (column-major, Vulkan clip: y down, z in [0,1]) and a zero jitter.
#include <exr_io.h>
#include <options_parser.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>

namespace {

constexpr double kNear = 0.1, kFar = 100.0, kPlaneHalf = 20.0;
const glm::dvec3 kSphere(0.0, 1.0, 0.0);
constexpr double kRadius = 1.0;

glm::dmat4 view_proj(int frame, int w, int h) {
    const double angle = 0.5 + 0.012 * frame;  // slow orbit
    const glm::dvec3 eye(6.0 * std::sin(angle), 2.5 + 0.02 * frame, 6.0 * std::cos(angle));
    const glm::dmat4 view = glm::lookAtRH(eye, glm::dvec3(0.0, 0.8, 0.0), glm::dvec3(0.0, 1.0, 0.0));
    // Reversed Z: near and far swapped give z = 1 at near, 0 at far.
    glm::dmat4 proj = glm::perspectiveRH_ZO(glm::radians(45.0), double(w) / h, kFar, kNear);
    proj[1][1] = -proj[1][1];  // Vulkan: NDC y points down
    return proj * view;
}

// Nearest hit along the ray: t, or -1.  Sets the normal and the object id.
double trace(const glm::dvec3& o, const glm::dvec3& d, glm::dvec3& n, int& id) {
    double best = -1.0;
    const glm::dvec3 oc = o - kSphere;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - kRadius * kRadius, disc = b * b - c;
    if (disc >= 0.0) {
        const double t = -b - std::sqrt(disc);
        if (t > 0.0) {
            best = t;
            n = glm::normalize(o + t * d - kSphere);
            id = 1;
        }
    }
    if (d.y < 0.0) {
        const double t = -o.y / d.y;
        const glm::dvec3 p = o + t * d;
        if (std::fabs(p.x) < kPlaneHalf && std::fabs(p.z) < kPlaneHalf && (best < 0.0 || t < best)) {
            best = t;
            n = glm::dvec3(0.0, 1.0, 0.0);
            id = 0;
        }
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir;
    int frames = 24, first = 1, seed = 1;
    uint32_t size_w = 128, size_h = 96;
    bool help = false, check = false;
    const char* usage =
        "usage: rrc-make-demo-sequence DIR [--frames N (24)] [--first F (1)] [--size WxH (128x96)] [--seed S (1)] [--check-options]\n"
        "--check-options: check the arguments as a run would, print \"rrc-make-demo-sequence: options ok\" and exit.\n";
    try {
        rrc_host::ArgCursor c(argc, argv);
        while (c.next()) {
            if (c.option("--frames"))
                frames = (int)c.integer(1, 100000);
            else if (c.option("--first"))
                first = (int)c.integer(0, 100000);
            else if (c.option("--seed"))
                seed = (int)c.integer(0, 100000);
            else if (c.option("--size"))
                c.size(size_w, size_h, 1, 4096);
            else if (c.positional() && dir.empty())
                dir = c.arg();
            else
                c.unknown();
        }
        check = c.check_only();
        help = c.help();
        if (!help && dir.empty()) throw rrc_host::OptionError("the output directory DIR is missing");
    } catch (const rrc_host::OptionError& e) {
        return rrc_host::report_option_error("rrc-make-demo-sequence", e, usage, true);
    }
    if (help || check) return rrc_host::report_help_or_check("rrc-make-demo-sequence", help, check, usage);
    const int width = (int)size_w, height = (int)size_h;
    try {
        std::filesystem::create_directories(dir);
        const glm::dvec3 light = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
        // Centre of the sphere's shadow on the ground.
        const glm::dvec2 shadow_c(kSphere.x - light.x * kSphere.y / light.y, kSphere.z - light.z * kSphere.y / light.y);
        const std::size_t n = std::size_t(width) * height;
        std::string json = "{\n";
        for (int f = first; f < first + frames; ++f) {
            const glm::dmat4 vp = view_proj(f, width, height), vp_prev = view_proj(f - 1, width, height);
            const glm::dmat4 inv = glm::inverse(vp);
            std::mt19937 rng(static_cast<unsigned>(seed) * 1000003u + static_cast<unsigned>(f));
            auto noise = [&](double amp) { return amp * (2.0 * double(rng() >> 8) / 16777216.0 - 1.0); };

            rrc_exr::ExrImage img;
            img.width = width;
            img.height = height;
            for (const char* c : {"Z", "prevclip.X", "prevclip.Y", "prevclip.Z", "prevclip.W", "mv.X", "mv.Y", "mv.Z", "shadow.Y",
                                  "color.R", "color.G", "color.B", "color.A"})
                img.channels[c].assign(n, 0.0f);
            auto set = [&](const char* c, std::size_t i, double v) { img.channels[c][i] = float(v); };

            for (int j = 0; j < height; ++j)
                for (int i = 0; i < width; ++i) {
                    const std::size_t idx = std::size_t(j) * width + i;
                    const glm::dvec2 uv((i + 0.5) / width, (j + 0.5) / height), ndc = 2.0 * uv - 1.0;
                    glm::dvec4 pn = inv * glm::dvec4(ndc, 1.0, 1.0), pf = inv * glm::dvec4(ndc, 0.0, 1.0);
                    const glm::dvec3 o = glm::dvec3(pn) / pn.w, d = glm::normalize(glm::dvec3(pf) / pf.w - o);
                    glm::dvec3 nrm;
                    int id = -1;
                    const double t = trace(o, d, nrm, id);
                    glm::dvec3 rgb;
                    double vis;
                    if (t < 0.0) {  // background: depth 0, reprojects onto itself
                        set("prevclip.X", idx, ndc.x);
                        set("prevclip.Y", idx, ndc.y);
                        set("prevclip.W", idx, 1.0);
                        vis = 1.0;
                        rgb = glm::dvec3(0.45, 0.6, 0.9) + 0.2 * (1.0 - uv.y);
                    } else {
                        const glm::dvec3 p = o + t * d;
                        const glm::dvec4 c = vp * glm::dvec4(p, 1.0), cp = vp_prev * glm::dvec4(p, 1.0);
                        const double depth = c.z / c.w;
                        set("Z", idx, depth);
                        set("prevclip.X", idx, cp.x);
                        set("prevclip.Y", idx, cp.y);
                        set("prevclip.Z", idx, cp.z);
                        set("prevclip.W", idx, cp.w);
                        set("mv.X", idx, (cp.x / cp.w + 1.0) / 2.0 - uv.x);
                        set("mv.Y", idx, (cp.y / cp.w + 1.0) / 2.0 - uv.y);
                        set("mv.Z", idx, cp.z / cp.w - depth);
                        const double lambert = std::max(0.0, glm::dot(nrm, light));
                        if (id == 0) {
                            const double r = glm::length(glm::dvec2(p.x, p.z) - shadow_c);
                            vis = glm::smoothstep(0.6, 1.4, r);
                            const bool check = (int(std::floor(p.x)) + int(std::floor(p.z))) & 1;
                            rgb = glm::dvec3(check ? 0.75 : 0.35);
                        } else {
                            vis = glm::clamp(2.0 * lambert, 0.0, 1.0);
                            rgb = glm::dvec3(0.8, 0.3, 0.2);
                        }
                        rgb *= 0.25 + 0.75 * vis * lambert;
                    }
                    set("shadow.Y", idx, vis + noise(0.25));
                    set("color.R", idx, rgb.r + noise(0.1));
                    set("color.G", idx, rgb.g + noise(0.1));
                    set("color.B", idx, rgb.b + noise(0.1));
                    set("color.A", idx, 1.0);
                }
            char name[64];
            std::snprintf(name, sizeof name, "frame_%04d.exr", f);
            rrc_exr::write_exr((std::filesystem::path(dir) / name).string(), img);

            json += "  \"" + std::to_string(f) + "\": {\"view_proj\": [";
            for (int k = 0; k < 16; ++k) {
                char num[40];
                std::snprintf(num, sizeof num, "%s%.17g", k ? ", " : "", vp[k / 4][k % 4]);
                json += num;
            }
            json += std::string("], \"jitter\": [0, 0]}") + (f + 1 < first + frames ? ",\n" : "\n");
        }
        json += "}\n";
        const std::string cam = (std::filesystem::path(dir) / "camera.json").string();
        std::FILE* fp = std::fopen(cam.c_str(), "wb");
        if (!fp || std::fwrite(json.data(), 1, json.size(), fp) != json.size() || std::fclose(fp) != 0)
            throw std::runtime_error(cam + ": cannot write");
        std::printf(
            "wrote %d frames %dx%d to %s (reversed-Z float depth, near %g, far %g)\n"
            "try: rrc-accumulate --input %s/frame_%%04d.exr --frames %d-%d --output OUT/acc_%%04d.exr "
            "--depth-mode reversed --camera %s\n",
            frames, width, height, dir.c_str(), kNear, kFar, dir.c_str(), first, first + frames - 1, cam.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rrc-make-demo-sequence: %s\n", e.what());
        return 1;
    }
    return 0;
}
