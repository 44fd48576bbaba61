// rrc-blender-check: measures what Blender's Depth and Vector passes hold,
// against the exact geometry of the scene render_check_scene.py made
// (docs/measurements/OFFLINE.md, "2. What Blender writes, measured").  Development aid: no test runs it.
//
//   rrc-blender-check DIR [OTHER_DIR]
//   rrc-blender-check DIR --hits OUT_PATTERN
//   rrc-blender-check --hits IN_PATTERN OUT_PATTERN FIRST-LAST
//
// DIR holds frame_0001.exr... and scene.json from render_check_scene.py.
// With OTHER_DIR (the same scene rendered with another sample count) it also
// reports how many Depth and Vector values are bitwise equal between the two
// renders: equal Depth at 1 and 64 samples means Depth comes from one sample.
// With --hits and rrc-accumulate's outputs of DIR (OUT_PATTERN, printf-style)
// it counts the hits whose history comes from another object, by Blender's
// object index (object_index_hits.h, which rrc_offline_test shares): the
// nearest previous texel's (nearest) or any bilinear tap's of non-zero
// weight (object-index false hits; taps below kBorderlineTapWeight are
// counted apart); hits on the moving sphere are reported too.  The second
// --hits form needs no scene.json: any Blender sequence (IN_PATTERN) with
// its IndexOB pass, e.g. tests/data/offline/blender_cycles_%04d.exr.
#include "object_index_hits.h"

#include <exr_io.h>
#include <options_parser.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

struct FrameInfo {
    glm::dmat4 camera_world{1.0}, projection{1.0};
    glm::dmat4 objects[4];  // by pass index 1..3
};

glm::dmat4 from_rows(const nlohmann::json& m) {
    glm::dmat4 r(1.0);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r[j][i] = m[i][j].get<double>();  // glm is column-major: r[col][row]
    return r;
}

struct Scene {
    int W = 0, H = 0, count = 3;  // frames 1..count rendered; 0..count+1 described
    std::vector<FrameInfo> frames;
};

Scene load_scene(const std::string& dir) {
    std::ifstream in(dir + "/scene.json");
    nlohmann::json j = nlohmann::json::parse(in);
    Scene s;
    s.W = j["width"];
    s.H = j["height"];
    s.count = j.value("frame_count", 3);
    s.frames.resize(std::size_t(s.count) + 2);
    for (int f = 0; f < s.count + 2; ++f) {
        const auto& fj = j["frames"][std::to_string(f)];
        s.frames[f].camera_world = from_rows(fj["camera_world"]);
        s.frames[f].projection = from_rows(fj["projection"]);
        for (const auto& kv : fj["objects"].items()) s.frames[f].objects[kv.value()["index"].get<int>()] = from_rows(kv.value()["world"]);
    }
    return s;
}

// The centre ray of pixel (i, j) (row j from the top): origin and a world
// direction scaled so that its view-space z is -1 (so t is planar depth).
void centre_ray(const Scene& s, int f, double px, double py_down, glm::dvec3& o, glm::dvec3& d) {
    const FrameInfo& fi = s.frames[f];
    const double ndc_x = 2.0 * px / s.W - 1.0, ndc_y = 1.0 - 2.0 * py_down / s.H;  // OpenGL: y up
    const glm::dvec3 dir_view(ndc_x / fi.projection[0][0], ndc_y / fi.projection[1][1], -1.0);
    o = glm::dvec3(fi.camera_world[3]);
    d = glm::dmat3(fi.camera_world) * dir_view;
}

// Nearest intersection with object `id` (1 plane z=0, 2 cube, 3 sphere) at frame f; -1 if none.
double intersect(const Scene& s, int f, int id, const glm::dvec3& o, const glm::dvec3& d) {
    const glm::dmat4& m = s.frames[f].objects[id];
    const glm::dvec3 c(m[3]);
    if (id == 1) return d.z < 0 ? -o.z / d.z : -1.0;
    if (id == 3) {  // radius 0.8 (a 48x24 UV sphere: within ~0.2% of it)
        const glm::dvec3 oc = o - c;
        const double a = glm::dot(d, d), b = glm::dot(oc, d), cc = glm::dot(oc, oc) - 0.64, disc = b * b - a * cc;
        if (disc < 0) return -1.0;
        return (-b - std::sqrt(disc)) / a;
    }
    double t0 = -1e300, t1 = 1e300;  // cube: half size 0.75, axis-aligned
    for (int k = 0; k < 3; ++k) {
        const double lo = c[k] - 0.75, hi = c[k] + 0.75;
        if (std::fabs(d[k]) < 1e-300) {
            if (o[k] < lo || o[k] > hi) return -1.0;
            continue;
        }
        double a = (lo - o[k]) / d[k], b = (hi - o[k]) / d[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1 && t0 > 0 ? t0 : -1.0;
}

// Pixel position (x right, y UP from the bottom edge, Blender's raster) of a world point at frame f.
glm::dvec2 project_up(const Scene& s, int f, const glm::dvec3& p) {
    const FrameInfo& fi = s.frames[f];
    const glm::dvec4 c = fi.projection * glm::inverse(fi.camera_world) * glm::dvec4(p, 1.0);
    return glm::dvec2((c.x / c.w + 1.0) / 2.0 * s.W, (c.y / c.w + 1.0) / 2.0 * s.H);
}

struct Stat {
    double sum = 0, max = 0;
    long n = 0;
    void add(double v) {
        sum += std::fabs(v);
        max = std::max(max, std::fabs(v));
        ++n;
    }
    double mean() const { return n ? sum / n : 0.0; }
};

std::string frame_name(const std::string& pattern, int f) {
    char name[1024];
    std::snprintf(name, sizeof name, pattern.c_str(), f);
    return name;
}

// Frames first+1..last of IN_PATTERN against rrc-accumulate's masks in
// OUT_PATTERN (frame `first` has no previous frame: all misses).
int count_hits(const std::string& in_pattern, const std::string& out_pattern, int first, int last) {
    const std::string L = "ViewLayer.";
    auto ids_of = [&](const rrc_exr::ExrImage& img) {
        const std::vector<float>& v = img.channels.at(L + "IndexOB.X");
        std::vector<uint32_t> ids(v.size());
        for (std::size_t k = 0; k < v.size(); ++k) ids[k] = uint32_t(std::lround(v[k]));
        return ids;
    };
    rrc_cli::ObjectIndexHits total;
    long sphere = 0, sphere_hits = 0;
    for (int f = first + 1; f <= last; ++f) {
        const rrc_exr::ExrImage cur = rrc_exr::read_exr(frame_name(in_pattern, f));
        const rrc_exr::ExrImage prev = rrc_exr::read_exr(frame_name(in_pattern, f - 1));
        const std::vector<float> mask = rrc_exr::read_exr(frame_name(out_pattern, f)).channels.at("rrc.mask");
        const std::vector<uint32_t> ids = ids_of(cur);
        total += rrc_cli::count_object_index_hits(cur.width, cur.height, mask, ids, ids_of(prev), cur.channels.at(L + "Vector.X"),
                                                  cur.channels.at(L + "Vector.Y"));
        for (std::size_t k = 0; k < mask.size(); ++k) {
            if (int(mask[k]) & 4 || ids[k] != 3) continue;  // index 3: the moving sphere of render_check_scene.py
            ++sphere;
            sphere_hits += int(mask[k]) & 1;
        }
    }
    auto pct = [](int64_t a, int64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; };
    std::printf(
        "frames %d-%d: hit ratio %.2f%% (%lld of %lld), object-index false hits %.3f%% (%lld; %lld more only at taps of weight <= %g), "
        "nearest-texel false hits %.3f%% (%lld), moving sphere hit ratio %.2f%%\n",
        first + 1, last, pct(total.hits, total.tested), (long long)total.hits, (long long)total.tested, pct(total.foreign, total.hits),
        (long long)total.foreign, (long long)total.borderline, double(rrc_cli::kBorderlineTapWeight),
        pct(total.nearest_foreign, total.hits), (long long)total.nearest_foreign, pct(sphere_hits, sphere));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const char* usage =
        "usage: rrc-blender-check DIR [OTHER_DIR] | DIR --hits OUT_PATTERN | --hits IN_PATTERN OUT_PATTERN FIRST-LAST\n"
        "--check-options: check the arguments' shape, print \"rrc-blender-check: options ok\" and exit (no file is read)\n";
    // The shared cursor (options_parser.h): positional paths, --hits and --check-options.
    std::vector<std::string> paths;
    bool hits = false, help = false, check = false;
    int first = 0, last = -1;
    try {
        rrc_host::ArgCursor c(argc, argv);
        while (c.next()) {
            if (c.flag("--hits"))
                hits = true;
            else if (c.positional())
                paths.push_back(c.arg());
            else
                c.unknown();
        }
        check = c.check_only();
        help = c.help();
        if (help) {
            // nothing is required
        } else if (hits && paths.size() == 3) {  // --hits IN_PATTERN OUT_PATTERN FIRST-LAST
            if (std::sscanf(paths[2].c_str(), "%d-%d", &first, &last) != 2 || first < 0 || last <= first)
                throw rrc_host::OptionError("--hits " + rrc_host::quoted(paths[2]) + ": expected FIRST-LAST, two frames or more");
        } else if (paths.empty() || paths.size() > 2 || (hits && paths.size() != 2)) {  // DIR [OTHER_DIR] | DIR --hits OUT
            throw rrc_host::OptionError("expected DIR [OTHER_DIR], DIR --hits OUT_PATTERN or --hits IN_PATTERN OUT_PATTERN FIRST-LAST");
        }
    } catch (const rrc_host::OptionError& e) {
        return rrc_host::report_option_error("rrc-blender-check", e, usage, true);
    }
    if (help || check) return rrc_host::report_help_or_check("rrc-blender-check", help, check, usage);
    if (hits && paths.size() == 3) return count_hits(paths[0], paths[1], first, last);
    const std::string dir = paths[0];
    const Scene s = load_scene(dir);
    const std::string L = "ViewLayer.";
    if (hits) return count_hits(dir + "/frame_%04d.exr", paths[1], 1, s.count);
    for (int f = 1; f <= s.count; ++f) {
        char name[64];
        std::snprintf(name, sizeof name, "/frame_%04d.exr", f);
        const rrc_exr::ExrImage img = rrc_exr::read_exr(dir + name);
        const auto& Z = img.channels.at(L + "Depth.Z");
        const auto& VX = img.channels.at(L + "Vector.X");
        const auto& VY = img.channels.at(L + "Vector.Y");
        const auto& VZ = img.channels.at(L + "Vector.Z");
        const auto& VW = img.channels.at(L + "Vector.W");
        const auto& ID = img.channels.at(L + "IndexOB.X");
        long sky = 0, sky_1e10 = 0, sky_zero_vector = 0, nonsky_1e10 = 0;
        Stat planar_rel, euclid_rel, offset_px;
        long offset_over_half = 0, offset_n = 0;
        // Hypotheses for Vector.XY: prev - cur (y up), cur - prev (y up), prev - cur (y down).
        Stat h_prev_up, h_cur_up, h_prev_down, h_next_zw, h_next_zw_flip;
        long interior = 0;
        Stat edge_fraction;  // object edge pixels: |V| / |V_object| (1 = not diluted by sky or other samples)
        // What rrc's plain-motion test sees: |fetched previous depth - depth| / depth at the
        // position the Vector gives, per object (interior pixels, previous frame needed).
        std::vector<double> rel_change[4];
        rrc_exr::ExrImage prev_img;
        if (f > 1) {
            char pname[64];
            std::snprintf(pname, sizeof pname, "/frame_%04d.exr", f - 1);
            prev_img = rrc_exr::read_exr(dir + pname);
        }
        for (int j = 0; j < s.H; ++j)
            for (int i = 0; i < s.W; ++i) {
                const std::size_t k = std::size_t(j) * s.W + i;
                const int id = int(std::lround(ID[k]));
                if (id == 0) {
                    ++sky;
                    sky_1e10 += Z[k] == 1e10f;
                    sky_zero_vector += VX[k] == 0 && VY[k] == 0 && VZ[k] == 0 && VW[k] == 0;
                    continue;
                }
                nonsky_1e10 += Z[k] == 1e10f;
                bool uniform = true;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        const int x = std::clamp(i + di, 0, s.W - 1), y = std::clamp(j + dj, 0, s.H - 1);
                        uniform = uniform && int(std::lround(ID[std::size_t(y) * s.W + x])) == id;
                    }
                glm::dvec3 o, d;
                centre_ray(s, f, i + 0.5, j + 0.5, o, d);
                const double t = intersect(s, f, id, o, d);
                if (t <= 0) continue;
                const glm::dvec3 p = o + t * d;
                if (uniform) {
                    planar_rel.add((Z[k] - t) / t);
                    euclid_rel.add((Z[k] - t * glm::length(d)) / (t * glm::length(d)));
                    if (id == 1) {  // ground plane: where on the plane did the depth sample land?
                        glm::dvec3 o2, d2;
                        const double h = 0.01;
                        centre_ray(s, f, i + 0.5 + h, j + 0.5, o2, d2);
                        const double gx = (intersect(s, f, 1, o2, d2) - t) / h;
                        centre_ray(s, f, i + 0.5, j + 0.5 + h, o2, d2);
                        const double gy = (intersect(s, f, 1, o2, d2) - t) / h;
                        const double g = std::hypot(gx, gy);
                        if (g > 1e-3 * t) {                     // only where depth changes measurably across a pixel
                            const double off = (Z[k] - t) / g;  // along the gradient, pixels
                            offset_px.add(off);
                            ++offset_n;
                            offset_over_half += std::fabs(off) > 0.5;
                        }
                    }
                }
                // Where is this surface point in the previous and next frames?
                const glm::dmat4& m = s.frames[f].objects[id];
                const glm::dvec3 po = glm::dvec3(glm::inverse(m) * glm::dvec4(p, 1.0));
                const glm::dvec2 cur(i + 0.5, s.H - (j + 0.5));
                const glm::dvec2 prev = project_up(s, f - 1, glm::dvec3(s.frames[f - 1].objects[id] * glm::dvec4(po, 1.0)));
                const glm::dvec2 next = project_up(s, f + 1, glm::dvec3(s.frames[f + 1].objects[id] * glm::dvec4(po, 1.0)));
                const glm::dvec2 v(VX[k], VY[k]), vn(VZ[k], VW[k]);
                if (uniform && f > 1) {
                    const auto& PZ = prev_img.channels.at(L + "Depth.Z");
                    const double qx = i + 0.5 + VX[k], qy = j + 0.5 - VY[k];  // y up -> rows
                    const double px = qx - 0.5, py = qy - 0.5;
                    const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
                    const double fx = px - x0, fy = py - y0;
                    double inv = 0;
                    bool sky_tap = false;
                    for (int t = 0; t < 4; ++t) {
                        const int x = std::clamp(x0 + (t & 1), 0, s.W - 1), y = std::clamp(y0 + (t >> 1), 0, s.H - 1);
                        const double z = PZ[std::size_t(y) * s.W + x];
                        sky_tap = sky_tap || z >= 1e10;
                        inv += ((t & 1) ? fx : 1 - fx) * ((t >> 1) ? fy : 1 - fy) / z;
                    }
                    if (!sky_tap && qx >= 0 && qy >= 0 && qx <= s.W && qy <= s.H)
                        rel_change[id].push_back(std::fabs(1.0 / inv - Z[k]) / Z[k]);
                }
                if (uniform) {
                    ++interior;
                    h_prev_up.add(glm::length(v - (prev - cur)));
                    h_cur_up.add(glm::length(v - (cur - prev)));
                    h_prev_down.add(glm::length(v - glm::dvec2(prev.x - cur.x, -(prev.y - cur.y))));
                    h_next_zw.add(glm::length(vn - (cur - next)));
                    h_next_zw_flip.add(glm::length(vn - (next - cur)));
                } else if (id == 3 && glm::length(prev - cur) > 0.5) {
                    edge_fraction.add(glm::length(v) / glm::length(prev - cur));
                }
            }
        std::printf(
            "frame %d: %ld sky pixels (IndexOB 0), %ld with Depth exactly 1e10, %ld with Vector exactly 0; "
            "%ld non-sky pixels with Depth 1e10\n",
            f, sky, sky_1e10, sky_zero_vector, nonsky_1e10);
        std::printf("  depth vs centre ray (interior pixels): planar |rel| mean %.2e max %.2e; along-ray |rel| mean %.2e max %.2e\n",
                    planar_rel.mean(), planar_rel.max, euclid_rel.mean(), euclid_rel.max);
        std::printf(
            "  ground-plane depth sample offset along the depth gradient: mean |off| %.3f px, max %.3f px, "
            "%.1f%% beyond 0.5 px (%ld pixels)\n",
            offset_px.mean(), offset_px.max, offset_n ? 100.0 * offset_over_half / offset_n : 0.0, offset_n);
        std::printf(
            "  Vector.XY vs exact motion (%ld interior pixels), mean |error| px: prev-cur y-up %.4f (max %.4f), "
            "cur-prev y-up %.4f, prev-cur y-down %.4f\n",
            interior, h_prev_up.mean(), h_prev_up.max, h_cur_up.mean(), h_prev_down.mean());
        std::printf("  Vector.ZW: cur-next y-up %.4f (max %.4f), next-cur %.4f\n", h_next_zw.mean(), h_next_zw.max, h_next_zw_flip.mean());
        for (int id = 1; id <= 3; ++id) {
            auto& v = rel_change[id];
            if (v.empty()) continue;
            std::sort(v.begin(), v.end());
            auto pct = [&](double p) { return v[std::min(v.size() - 1, std::size_t(p * v.size()))]; };
            std::printf("  %s: |fetched previous depth - depth| / depth: median %.4f, 90%% %.4f, 99%% %.4f, max %.4f (%zu pixels)\n",
                        id == 1   ? "ground"
                        : id == 2 ? "cube  "
                                  : "sphere",
                        pct(0.5), pct(0.9), pct(0.99), v.back(), v.size());
        }
        std::printf("  moving-sphere edge pixels: |Vector| / |exact motion| mean %.3f (%ld pixels; 1 = not diluted)\n",
                    edge_fraction.mean(), edge_fraction.n);
    }
    if (paths.size() > 1) {
        for (int f = 1; f <= s.count; ++f) {
            char name[64];
            std::snprintf(name, sizeof name, "/frame_%04d.exr", f);
            const rrc_exr::ExrImage a = rrc_exr::read_exr(dir + name), b = rrc_exr::read_exr(paths[1] + name);
            for (const char* c : {"Depth.Z", "Vector.X", "IndexOB.X", "Combined.R"}) {
                const auto &x = a.channels.at(L + c), &y = b.channels.at(L + c);
                long same = 0;
                for (std::size_t k = 0; k < x.size(); ++k) same += x[k] == y[k];
                std::printf("frame %d %-10s bitwise equal in %s and %s: %5.1f%%\n", f, c, paths[0].c_str(), paths[1].c_str(),
                            100.0 * same / double(x.size()));
            }
        }
    }
    return 0;
}
