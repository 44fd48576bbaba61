#include "golden/golden_io.h"

#include "scenes/scene.h"

#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace rrc_golden {
namespace {

const char* kComponentNames[4] = {"R", "G", "B", "A"};

std::string component(uint32_t comps, uint32_t k) { return comps == 1 ? "Y" : kComponentNames[k]; }

uint32_t reprojection_floats(rrc_reprojection s) {
    return s == RRC_REPROJECTION_PREV_CLIP ? 4 : s == RRC_REPROJECTION_MOTION_DEPTH ? 3 : s == RRC_REPROJECTION_MOTION ? 2 : 0;
}

std::string join(const double* v, int n) {
    std::ostringstream out;
    char buf[40];
    for (int i = 0; i < n; ++i) {
        std::snprintf(buf, sizeof buf, "%.17g", v[i]);
        out << (i ? " " : "") << buf;
    }
    return out.str();
}

void split(const std::string& s, double* v, int n) {
    std::istringstream in(s);
    for (int i = 0; i < n; ++i)
        if (!(in >> v[i])) throw std::runtime_error("golden attribute has fewer than " + std::to_string(n) + " numbers: " + s);
}

// Interleaved <-> planar.
void put(rrc_exr::ExrImage& img, const std::string& base, const std::vector<float>& v, uint32_t comps) {
    const size_t n = img.pixel_count();
    for (uint32_t k = 0; k < comps; ++k) {
        std::vector<float> plane(n);
        for (size_t i = 0; i < n; ++i) plane[i] = v[comps * i + k];
        img.channels[base + "." + std::to_string(k)] = plane;
    }
}
std::vector<float> get(const rrc_exr::ExrImage& img, const std::string& base, uint32_t comps, const std::string& path) {
    const size_t n = img.pixel_count();
    std::vector<float> v(n * comps);
    for (uint32_t k = 0; k < comps; ++k) {
        std::vector<float> plane = img.as_float(base + "." + std::to_string(k), path);
        for (size_t i = 0; i < n; ++i) v[comps * i + k] = plane[i];
    }
    return v;
}
template <typename T>
std::vector<float> to_float(const std::vector<T>& v) {
    return std::vector<float>(v.begin(), v.end());
}

}  // namespace

void FrameArrays::bind(const GoldenCase& c) {
    inputs.clear();
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        rrc_channel_input in;
        std::memset(&in, 0, sizeof in);
        in.type = RRC_STRUCT_TYPE_CHANNEL_INPUT;
        in.size = sizeof in;
        in.samples = samples[ch].data();
        in.confidence = confidence[ch].empty() ? nullptr : confidence[ch].data();
        inputs.push_back(in);
    }
    desc = rrc_test::frame_desc();
    desc.depth = depth.data();
    desc.reprojection = reprojection.empty() ? nullptr : reprojection.data();
    std::memcpy(desc.view_proj, view_proj, sizeof view_proj);
    std::memcpy(desc.prev_view_proj, prev_view_proj, sizeof prev_view_proj);
    std::memcpy(desc.jitter, jitter, sizeof jitter);
    std::memcpy(desc.prev_jitter, prev_jitter, sizeof prev_jitter);
    desc.channel_count = (uint32_t)inputs.size();
    desc.channels = inputs.data();
}

// The case's scene: jittered, FLOAT32 depth (near 0.1).
static rrc_scene::SceneConfig scene_config_for(const GoldenCase& c) {
    rrc_scene::SceneConfig sc = rrc_test::scene_config(kWidth, kHeight, c.depth_mode, RRC_DEPTH_FORMAT_FLOAT32, c.far_plane);
    sc.object_motion = c.object_motion;
    sc.jitter = true;
    return sc;
}

rrc_context_desc context_for(const GoldenCase& c, std::vector<rrc_channel_desc>& channels) {
    channels = c.channels;
    rrc_context_desc d = rrc_test::scene_context_desc(scene_config_for(c), c.source, channels);
    d.depth_test = c.depth_test;
    return d;
}

FrameArrays arrays_from_scene(const GoldenCase& c, rrc_test::SceneFrameInputs& in) {
    rrc_test::make_frame_inputs(in, c.source, c.channels);
    FrameArrays a;
    a.depth = in.frame.depth;
    a.reprojection = in.reprojection;
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        a.samples.push_back(c.channels[ch].components == 1 ? in.frame.signal1 : in.frame.signal4);
        a.confidence.push_back(in.confidence[ch]);
    }
    std::memcpy(a.view_proj, in.frame.view_proj, sizeof a.view_proj);
    std::memcpy(a.prev_view_proj, in.frame.prev_view_proj, sizeof a.prev_view_proj);
    std::memcpy(a.jitter, in.frame.jitter, sizeof a.jitter);
    std::memcpy(a.prev_jitter, in.frame.prev_jitter, sizeof a.prev_jitter);
    a.bind(c);
    return a;
}

GoldenData compute_golden(const GoldenCase& c) {
    rrc_scene::Scene scene(scene_config_for(c));
    std::vector<rrc_channel_desc> channels;
    rrc_context_desc d = context_for(c, channels);
    GoldenData g;
    rrc_ref::PreviousFrame prev;
    for (int f = 0; f < 2; ++f) {
        rrc_test::SceneFrameInputs in;
        in.frame = scene.render(kFirstFrame + f);
        g.frames[f] = arrays_from_scene(c, in);
        g.frames[f].bind(c);
        rrc_ref::FrameResult r = rrc_ref::run_frame(d, prev, g.frames[f].desc);
        if (f == 1) g.expected = r;
        prev = rrc_ref::as_previous(d, g.frames[f].desc, r);
    }
    return g;
}

void write_golden(const std::string& path, const GoldenCase& c, const GoldenData& g) {
    rrc_exr::ExrImage img;
    img.width = kWidth;
    img.height = kHeight;
    const uint32_t rf = reprojection_floats(c.source);
    for (int f = 0; f < 2; ++f) {
        const FrameArrays& a = g.frames[f];
        std::string p = "f" + std::to_string(f) + ".";
        img.channels[p + "Z"] = a.depth;
        if (rf) put(img, p + "reproj", a.reprojection, rf);
        for (size_t ch = 0; ch < c.channels.size(); ++ch) {
            put(img, p + c.channels[ch].name, a.samples[ch], c.channels[ch].components);
            if (!a.confidence[ch].empty()) img.channels[p + c.channels[ch].name + ".conf"] = a.confidence[ch];
        }
        img.attributes[p + "view_proj"] = join(a.view_proj, 16);
        img.attributes[p + "prev_view_proj"] = join(a.prev_view_proj, 16);
        double j[4] = {a.jitter[0], a.jitter[1], a.prev_jitter[0], a.prev_jitter[1]};
        img.attributes[p + "jitter"] = join(j, 4);
    }
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        const auto& r = g.expected.channels[ch];
        std::string p = std::string("expected.") + c.channels[ch].name;
        put(img, p, to_float(r.out), c.channels[ch].components);
        img.channels[p + ".age"] = to_float(r.age);
        if (!r.weight.empty()) img.channels[p + ".weight"] = to_float(r.weight);
    }
    img.channels["expected.rrc.mask"] = to_float(g.expected.mask);
    img.channels["expected.rrc.near_threshold"] = to_float(g.expected.near_threshold);
    img.channels["expected.rrc.near_nearest_edge"] = to_float(g.expected.near_nearest_edge);
    img.channels["expected.rrc.uv_prev.X"] = to_float(g.expected.uv_prev_x);
    img.channels["expected.rrc.uv_prev.Y"] = to_float(g.expected.uv_prev_y);
    img.attributes["rrc.golden.case"] = c.name;
    img.attributes["rrc.golden.generator"] = "tests/golden/make_golden.cpp (rrc-make-golden tests/data)";
    rrc_exr::write_exr(path, img);
}

GoldenData read_golden(const std::string& path, const GoldenCase& c) {
    rrc_exr::ExrImage img = rrc_exr::read_exr(path);
    if (img.width != kWidth || img.height != kHeight) throw std::runtime_error(path + ": unexpected size");
    const uint32_t rf = reprojection_floats(c.source);
    GoldenData g;
    for (int f = 0; f < 2; ++f) {
        FrameArrays& a = g.frames[f];
        std::string p = "f" + std::to_string(f) + ".";
        a.depth = img.as_float(p + "Z", path);
        if (rf) a.reprojection = get(img, p + "reproj", rf, path);
        for (size_t ch = 0; ch < c.channels.size(); ++ch) {
            a.samples.push_back(get(img, p + c.channels[ch].name, c.channels[ch].components, path));
            std::string conf = p + c.channels[ch].name + ".conf";
            a.confidence.push_back(img.has(conf) ? img.as_float(conf, path) : std::vector<float>());
        }
        split(img.attributes.at(p + "view_proj"), a.view_proj, 16);
        split(img.attributes.at(p + "prev_view_proj"), a.prev_view_proj, 16);
        double j[4];
        split(img.attributes.at(p + "jitter"), j, 4);
        a.jitter[0] = (float)j[0];
        a.jitter[1] = (float)j[1];
        a.prev_jitter[0] = (float)j[2];
        a.prev_jitter[1] = (float)j[3];
        a.bind(c);
    }
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        rrc_ref::ChannelResult r;
        std::string p = std::string("expected.") + c.channels[ch].name;
        std::vector<float> out = get(img, p, c.channels[ch].components, path);
        r.out.assign(out.begin(), out.end());
        r.exact = r.out;
        std::vector<float> age = img.as_float(p + ".age", path);
        r.age.assign(age.begin(), age.end());
        if (img.has(p + ".weight")) {
            std::vector<float> w = img.as_float(p + ".weight", path);
            r.weight.assign(w.begin(), w.end());
        }
        g.expected.channels.push_back(r);
    }
    auto bytes = [&](const char* name) {
        std::vector<float> v = img.as_float(name, path);
        return std::vector<uint8_t>(v.begin(), v.end());
    };
    g.expected.mask = bytes("expected.rrc.mask");
    g.expected.near_threshold = bytes("expected.rrc.near_threshold");
    g.expected.near_nearest_edge = bytes("expected.rrc.near_nearest_edge");
    for (const char* axis : {"X", "Y"}) {
        std::vector<float> v = img.as_float(std::string("expected.rrc.uv_prev.") + axis, path);
        (axis[0] == 'X' ? g.expected.uv_prev_x : g.expected.uv_prev_y).assign(v.begin(), v.end());
    }
    return g;
}

}  // namespace rrc_golden
