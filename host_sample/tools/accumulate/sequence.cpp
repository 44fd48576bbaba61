// rrc-accumulate: reading the sequence into rrc's descriptors.
#include "sequence.h"

#include "rrc_descs.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <system_error>
#include <utility>

namespace rrc_cli {

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

bool is_reserved_layer(const std::string& layer) {
    return layer.empty() || layer == "mv" || layer == "prevclip" || layer == "nocache" || layer == "rrc";
}

// Channel suffixes that are never components of a signal.
bool is_reserved_component(const std::string& c) { return c == "conf" || c == "age" || c == "weight"; }

// layer -> component suffixes, from names "layer.comp" (layer may hold dots).
std::map<std::string, std::set<std::string>> group_layers(const rrc_exr::ExrInfo& info) {
    std::map<std::string, std::set<std::string>> layers;
    for (const auto& c : info.channels) {
        std::size_t dot = c.name.rfind('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == c.name.size()) continue;
        layers[c.name.substr(0, dot)].insert(c.name.substr(dot + 1));
    }
    return layers;
}

SignalLayout layout_signal(const SignalOptions& options, const std::set<std::string>& suffixes, const rrc_exr::ExrInfo& info,
                           const std::string& path) {
    SignalLayout s;
    s.options = options;
    const std::string& layer = options.layer;
    std::set<std::string> comps;
    for (const std::string& c : suffixes)
        if (!is_reserved_component(c)) comps.insert(c);
    s.confidence = suffixes.count("conf") != 0;
    if (comps.empty())
        throw CliError(path + ": layer " + quoted(layer) + " not found (no channel " + quoted(layer + ".*") +
                       "); the file has: " + list_channels(info));
    const std::set<std::string> rgb = {"B", "G", "R"}, rgba = {"A", "B", "G", "R"};
    if (comps.size() == 1) {
        s.components = {*comps.begin()};
        s.rrc_components = 1;
    } else if (comps == rgb || comps == rgba) {
        s.components = {"R", "G", "B"};
        if (comps.count("A")) s.components.push_back("A");
        s.rrc_components = 4;
    } else {
        std::string have;
        for (const std::string& c : comps) have += (have.empty() ? "" : ", ") + layer + "." + c;
        throw CliError(path + ": layer " + quoted(layer) + " has channels " + have + "; expected " + layer + ".Y (or one channel) or " +
                       layer + ".R/.G/.B[/.A]");
    }
    return s;
}

void check_finite(double v, const std::string& where) {
    if (!std::isfinite(v)) throw CliError(where + ": not a finite number");
}

}  // namespace

std::string list_channels(const rrc_exr::ExrInfo& info) {
    std::string s;
    std::size_t n = 0;
    for (const auto& c : info.channels) {
        if (n == 40) {
            s += ", ... (" + std::to_string(info.channels.size()) + " in all)";
            break;
        }
        s += (n++ ? ", " : "") + c.name;
    }
    return s.empty() ? "none" : s;
}

namespace {

std::string layer_of(const std::string& channel) {
    const std::size_t dot = channel.rfind('.');
    return dot == std::string::npos ? std::string() : channel.substr(0, dot);
}

// The view layer of a Blender multilayer file: the prefix of "<layer>.Depth.Z".
std::string find_view_layer(const rrc_exr::ExrInfo& info, const std::string& path, const Options& o) {
    if (!o.view_layer.empty()) {
        if (!info.has(o.view_layer + ".Depth.Z") && !info.has(o.view_layer + ".Combined.R")) {
            std::set<std::string> layers;
            for (const auto& c : info.channels)
                if (c.name.size() > 8 && c.name.compare(c.name.size() - 8, 8, ".Depth.Z") == 0)
                    layers.insert(c.name.substr(0, c.name.size() - 8));
            std::string have;
            for (const std::string& l : layers) have += (have.empty() ? "" : ", ") + quoted(l);
            throw CliError(path + ": --view-layer " + quoted(o.view_layer) + ": no channel " + quoted(o.view_layer + ".Depth.Z") + " or " +
                           quoted(o.view_layer + ".Combined.R") +
                           (have.empty() ? std::string() : "; view layers with a depth pass: " + have) +
                           "; the file has: " + list_channels(info));
        }
        return o.view_layer;
    }
    std::vector<std::string> layers;
    for (const auto& c : info.channels)
        if (c.name.size() > 8 && c.name.compare(c.name.size() - 8, 8, ".Depth.Z") == 0)
            layers.push_back(c.name.substr(0, c.name.size() - 8));
    if (layers.size() == 1) return layers[0];
    if (layers.empty()) {
        if (!o.depth_channel.empty()) return std::string();  // the depth is mapped explicitly; the view layer is not needed for it
        throw CliError(path +
                       ": --preset blender: no channel '<view layer>.Depth.Z' (enable the Z pass: View "
                       "Layer Properties > Passes > Data > Z, and save as OpenEXR MultiLayer); the file has: " +
                       list_channels(info));
    }
    std::string names;
    for (const std::string& l : layers) names += (names.empty() ? "" : ", ") + quoted(l);
    throw CliError(path + ": --preset blender: several view layers have a depth pass (" + names + "): choose one with --view-layer");
}

ChannelMap resolve_channels(const rrc_exr::ExrInfo& first, const std::string& path, const Options& o, rrc_reprojection& reprojection) {
    ChannelMap m;
    const bool blender = o.preset == "blender";
    if (blender) {
        m.view_layer = find_view_layer(first, path, o);
        const std::string p = m.view_layer.empty() ? std::string() : m.view_layer + ".";
        m.depth = p + "Depth.Z";
        m.motion = {p + "Vector.X", p + "Vector.Y"};  // .Z/.W are the next frame's vectors, not a depth change
    } else {
        m.motion = {"mv.X", "mv.Y"};
        if (first.has("mv.Z")) m.motion.push_back("mv.Z");
    }
    m.prevclip = {"prevclip.X", "prevclip.Y", "prevclip.Z", "prevclip.W"};
    if (!o.depth_channel.empty()) m.depth = o.depth_channel;
    if (!o.motion_channels.empty()) m.motion = o.motion_channels;
    if (!o.prevclip_channels.empty()) m.prevclip = o.prevclip_channels;
    if (!o.nocache_channel.empty()) m.nocache = o.nocache_channel;
    m.object_id = o.object_id_channel;
    switch (o.reproject) {
        case Reproject::PrevClip:
            reprojection = RRC_REPROJECTION_PREV_CLIP;
            m.motion.clear();
            break;
        case Reproject::Motion:
            reprojection = m.motion.size() == 3 ? RRC_REPROJECTION_MOTION_DEPTH : RRC_REPROJECTION_MOTION;
            m.prevclip.clear();
            break;
        case Reproject::Camera:
            reprojection = RRC_REPROJECTION_CAMERA;
            m.motion.clear();
            m.prevclip.clear();
            break;
    }
    return m;
}

}  // namespace

SequenceLayout discover_layout(const rrc_exr::ExrInfo& first, const std::string& first_path, const Options& options) {
    SequenceLayout layout;
    layout.width = first.width;
    layout.height = first.height;
    if (first.width > static_cast<int>(RRC_MAX_EXTENT) || first.height > static_cast<int>(RRC_MAX_EXTENT))
        throw CliError(first_path + ": " + std::to_string(first.width) + "x" + std::to_string(first.height) +
                       " is larger than rrc's limit of " + std::to_string(RRC_MAX_EXTENT) + " pixels a side");
    layout.channels = resolve_channels(first, first_path, options, layout.reprojection);
    ChannelMap& map = layout.channels;
    layout.nocache = first.has(map.nocache);
    // Object ids: named (then required), the preset's when present, or none.
    if (options.no_object_id) {
        map.object_id.clear();
        layout.object_id_report = "no object ids (--no-object-id)";
    } else if (!map.object_id.empty()) {
        layout.object_id_report = "object ids from " + quoted(std::as_const(map.object_id)) + " (--object-id)";
    } else if (options.preset == "blender") {
        const std::string index = (map.view_layer.empty() ? std::string() : map.view_layer + ".") + "IndexOB.X";
        if (first.has(index)) {
            map.object_id = index;
            layout.object_id_report = "object ids from " + quoted(index);
        } else {
            layout.object_id_report = "no object ids: " + first_path + " has no " + quoted(index) +
                                      " (enable View Layer Properties > Passes > Data > Object Index for them)";
        }
    }

    // Layers that carry geometry are never signals.
    std::set<std::string> geometry_layers = {"mv", "prevclip", "nocache", "rrc"};
    for (const std::string& c : {map.depth, map.nocache, map.object_id}) geometry_layers.insert(layer_of(c));
    for (const auto* list : {&map.motion, &map.prevclip})
        for (const std::string& c : *list) geometry_layers.insert(layer_of(c));

    const auto layers = group_layers(first);
    std::vector<SignalOptions> requested = options.signals;
    if (requested.empty() && options.preset == "blender") {
        SignalOptions s = blender_preset_signal((map.view_layer.empty() ? std::string() : map.view_layer + ".") + "Combined");
        if (!layers.count(s.layer))
            throw CliError(first_path + ": --preset blender without --signal accumulates " + quoted(std::as_const(s.layer)) +
                           ", which the file lacks (name the layers with --signal); the file has: " + list_channels(first));
        requested.push_back(s);
    }
    if (!requested.empty()) {
        for (const SignalOptions& s : requested) {
            auto it = layers.find(s.layer);
            layout.signals.push_back(layout_signal(s, it == layers.end() ? std::set<std::string>{} : it->second, first, first_path));
        }
    } else {
        std::vector<std::string> found;
        for (const auto& kv : layers) {
            if (is_reserved_layer(kv.first) || geometry_layers.count(kv.first)) continue;
            bool has_component = false;
            for (const std::string& c : kv.second) has_component = has_component || !is_reserved_component(c);
            if (has_component) found.push_back(kv.first);
        }
        if (found.empty())
            throw CliError(first_path +
                           ": no signal layer to accumulate (expected e.g. shadow.Y or color.R/.G/.B); "
                           "the file has: " +
                           list_channels(first));
        if (found.size() > RRC_MAX_CHANNELS) {
            std::string names;
            for (const std::string& f : found) names += (names.empty() ? "" : ", ") + f;
            throw CliError(first_path + ": " + std::to_string(found.size()) + " signal layers (" + names + "); rrc accumulates at most " +
                           std::to_string(RRC_MAX_CHANNELS) + " per run: choose them with --signal");
        }
        for (const std::string& f : found) {
            SignalOptions s;
            s.layer = f;
            layout.signals.push_back(layout_signal(s, layers.at(f), first, first_path));
        }
    }
    return layout;
}

std::vector<RequiredChannel> required_channels(const SequenceLayout& layout) {
    std::vector<RequiredChannel> req;
    const ChannelMap& map = layout.channels;
    req.push_back({map.depth, "the depth"});
    switch (layout.reprojection) {
        case RRC_REPROJECTION_PREV_CLIP:
            for (const std::string& c : map.prevclip) req.push_back({c, "needed by --reproject prev_clip"});
            break;
        case RRC_REPROJECTION_MOTION:
        case RRC_REPROJECTION_MOTION_DEPTH:
            req.push_back({map.motion[0], "motion vector x, needed by --reproject motion"});
            req.push_back({map.motion[1], "motion vector y, needed by --reproject motion"});
            if (layout.reprojection == RRC_REPROJECTION_MOTION_DEPTH)
                req.push_back({map.motion[2], "the depth change of the motion vectors"});
            break;
        default: break;
    }
    for (const SignalLayout& s : layout.signals) {
        for (const std::string& c : s.components) req.push_back({s.options.layer + "." + c, "signal " + quoted(s.options.layer)});
        if (s.confidence)
            req.push_back({s.options.layer + ".conf",
                           "confidence of signal " + quoted(s.options.layer) + "; the first frame has it, so every frame needs it"});
    }
    if (layout.nocache) req.push_back({map.nocache, "the do-not-cache mask; the first frame has it, so every frame needs it"});
    if (!map.object_id.empty())
        req.push_back({map.object_id, "the object ids; every frame needs them once the run uses them (--no-object-id goes without)"});
    return req;
}

void check_frame_header(const rrc_exr::ExrInfo& info, const std::string& path, const SequenceLayout& layout) {
    if (info.width != layout.width || info.height != layout.height)
        throw CliError(path + ": " + std::to_string(info.width) + "x" + std::to_string(info.height) + " differs from the first frame's " +
                       std::to_string(layout.width) + "x" + std::to_string(layout.height));
    for (const RequiredChannel& r : required_channels(layout))
        if (!info.has(r.name))
            throw CliError(path + ": missing channel " + quoted(r.name) + " (" + r.reason + "); the file has: " + list_channels(info));
}

std::map<int64_t, CameraFrame> load_camera_file(const std::string& path, int64_t first, int64_t last, bool need_view_proj) {
    using nlohmann::json;
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw CliError("camera file " + quoted(path) + ": cannot open (" + std::error_code(errno, std::generic_category()).message() + ")");
    json root;
    try {
        root = json::parse(in);
    } catch (const json::exception& e) {
        throw CliError("camera file " + quoted(path) + ": invalid JSON: " + e.what());
    }
    const std::string where = "camera file " + quoted(path);
    if (!root.is_object()) throw CliError(where + ": expected an object mapping frame numbers to {\"view_proj\": [...]}");

    std::map<int64_t, CameraFrame> frames;
    for (auto it = root.begin(); it != root.end(); ++it) {
        const std::string& key = it.key();
        const std::string at = where + ", frame " + quoted(key);
        char* end = nullptr;
        errno = 0;
        long long n = key.empty() || !std::isdigit(static_cast<unsigned char>(key[0])) ? -1 : std::strtoll(key.c_str(), &end, 10);
        if (n < 0 || errno == ERANGE || end != key.c_str() + key.size())
            throw CliError(at + ": keys must be frame numbers (non-negative integers)");
        if (frames.count(n)) throw CliError(at + ": frame " + std::to_string(n) + " appears twice");
        const json& v = it.value();
        if (!v.is_object()) throw CliError(at + ": expected an object {\"view_proj\": [16 numbers], \"jitter\": [x, y]}");
        CameraFrame cf;
        if (auto vp = v.find("view_proj"); vp != v.end()) {
            if (!vp->is_array() || vp->size() != 16) throw CliError(at + ": \"view_proj\" must be an array of 16 numbers (column-major)");
            for (std::size_t i = 0; i < 16; ++i) {
                if (!(*vp)[i].is_number()) throw CliError(at + ": \"view_proj\"[" + std::to_string(i) + "] is not a number");
                cf.view_proj[i] = (*vp)[i].get<double>();
                check_finite(cf.view_proj[i], at + ": \"view_proj\"[" + std::to_string(i) + "]");
            }
            cf.has_view_proj = true;
        }
        if (auto j = v.find("jitter"); j != v.end()) {
            if (!j->is_array() || j->size() != 2 || !(*j)[0].is_number() || !(*j)[1].is_number())
                throw CliError(at + ": \"jitter\" must be an array of 2 numbers (pixels)");
            for (int i = 0; i < 2; ++i) {
                double d = (*j)[i].get<double>();
                check_finite(d, at + ": \"jitter\"[" + std::to_string(i) + "]");
                cf.jitter[i] = static_cast<float>(d);
            }
        }
        frames[n] = cf;
    }
    if (need_view_proj) {
        for (int64_t f = first; f <= last; ++f) {
            auto it = frames.find(f);
            if (it == frames.end() || !it->second.has_view_proj)
                throw CliError(where + ": no \"view_proj\" for frame " + std::to_string(f) + " (needed by --reproject camera)");
        }
    }
    return frames;
}

FrameData load_frame(const rrc_exr::ExrImage& image, const std::string& path, const SequenceLayout& layout) {
    const std::size_t n = image.pixel_count();
    if (image.width != layout.width || image.height != layout.height) throw CliError(path + ": the size changed while reading");
    auto channel = [&](const std::string& name) {
        try {
            return image.as_float(name, path);
        } catch (const std::exception& e) {
            throw CliError(e.what());
        }
    };
    auto interleave = [&](const std::vector<std::string>& names, std::vector<float>& out) {
        const std::size_t k = names.size();
        out.assign(n * k, 0.0f);
        std::size_t c = 0;
        for (const std::string& name : names) {
            std::vector<float> v = channel(name);
            for (std::size_t i = 0; i < n; ++i) out[i * k + c] = v[i];
            ++c;
        }
    };

    FrameData f;
    f.depth = channel(layout.channels.depth);
    switch (layout.reprojection) {
        case RRC_REPROJECTION_PREV_CLIP: interleave(layout.channels.prevclip, f.reprojection); break;
        case RRC_REPROJECTION_MOTION:
        case RRC_REPROJECTION_MOTION_DEPTH: interleave(layout.channels.motion, f.reprojection); break;
        default: break;
    }
    for (const SignalLayout& s : layout.signals) {
        const std::string& layer = s.options.layer;
        std::vector<float> samples;
        if (s.rrc_components == 1) {
            samples = channel(layer + "." + s.components[0]);
        } else {
            samples.assign(n * 4, 1.0f);  // a missing A stays 1
            for (std::size_t c = 0; c < s.components.size(); ++c) {
                std::vector<float> v = channel(layer + "." + s.components[c]);
                for (std::size_t i = 0; i < n; ++i) samples[i * 4 + c] = v[i];
            }
        }
        f.samples.push_back(std::move(samples));
        f.confidence.push_back(s.confidence ? channel(layer + ".conf") : std::vector<float>{});
    }
    if (layout.nocache) {
        std::vector<float> v = channel(layout.channels.nocache);
        f.nocache.resize(n);
        for (std::size_t i = 0; i < n; ++i) f.nocache[i] = v[i] != 0.0f ? 1 : 0;  // NaN counts as non-zero
    }
    if (!layout.channels.object_id.empty()) f.object_id = object_ids_of(image, layout.channels.object_id, path);
    return f;
}

std::vector<uint32_t> object_ids_of(const rrc_exr::ExrImage& image, const std::string& channel, const std::string& path) {
    // UINT: exact (as_float would round ids above 2^24).
    if (auto it = image.uint_channels.find(channel); it != image.uint_channels.end()) return it->second;
    const std::vector<float>* values = image.find(channel);
    if (!values) throw CliError(path + ": missing channel " + quoted(channel) + " (the object ids)");
    std::vector<uint32_t> ids(values->size());
    for (std::size_t i = 0; i < values->size(); ++i) {
        const double v = (*values)[i];
        // Round half up; -0.0 and -0.4 are not ids although they round to 0:
        // a negative value means the channel is not what --object-id says.
        const double rounded = std::floor(v + 0.5);
        if (!std::isfinite(v) || v < 0.0 || rounded > 4294967295.0) {
            char text[64];
            std::snprintf(text, sizeof text, "%.10g", v);  // every float below 2^32 in full
            const std::size_t w = image.width > 0 ? std::size_t(image.width) : 1;
            throw CliError(path + ": channel " + quoted(channel) + " (the object ids): pixel (" + std::to_string(i % w) + ", " +
                           std::to_string(i / w) + ") holds " + text +
                           "; an object id must be a finite number in [0, 4294967295] (rounded to the nearest integer)");
        }
        ids[i] = static_cast<uint32_t>(rounded);
    }
    return ids;
}

rrc_context_desc make_context_desc(const Options& o, const SequenceLayout& layout, std::vector<rrc_channel_desc>& channels) {
    if (layout.reprojection == RRC_REPROJECTION_MOTION && o.depth_mode != RRC_DEPTH_MODE_LINEAR &&
        !(o.near_plane > 0.0f && o.far_plane > 0.0f))
        throw CliError(std::string("--reproject motion without a depth-change channel (mv.Z) on --depth-mode ") +
                       depth_mode_name(o.depth_mode) +
                       " compares linear depths: give the camera's --near and --far planes "
                       "(or add mv.Z, the depth change)");

    channels.clear();
    for (const SignalLayout& s : layout.signals) {
        if (s.options.layer.size() >= RRC_MAX_NAME) throw CliError("layer name " + quoted(s.options.layer) + " is too long for rrc");
        channels.push_back(rrc_host::channel(s.options.layer.c_str(), s.rrc_components, s.options.lambda, s.options.history,
                                             s.options.blend, s.options.filter, s.options.max_age, s.confidence ? 1u : 0u));
        channels.back().fill_age = s.options.fill_age;
        channels.back().fill_radius = s.options.fill_radius;
        channels.back().fill_depth_tolerance = s.options.fill_depth_tolerance;
        channels.back().rectify = s.options.rectify;
        channels.back().rectify_gamma = s.options.rectify_gamma;
        channels.back().antilag = s.options.antilag;
        channels.back().antilag_gamma = s.options.antilag_gamma;
        channels.back().antilag_threshold = s.options.antilag_threshold;
        channels.back().blur_bound = s.options.blur_bound;
        channels.back().gate_kappa = s.options.gate_kappa;
    }

    rrc_context_desc d = rrc_host::context_desc(static_cast<uint32_t>(layout.width), static_cast<uint32_t>(layout.height), channels);
    d.depth_mode = o.depth_mode;
    d.near_plane = o.near_plane;
    d.far_plane = o.far_plane;
    d.background_threshold = o.background_threshold;
    d.depth_format = o.depth_format;
    d.epsilon_scale = o.epsilon_scale;
    d.epsilon = o.epsilon;
    d.tau = o.tau;
    d.reprojection = layout.reprojection;
    // Into uv units, y down: pixels divide by the size, y-up vectors flip y.
    double sx = o.motion_scale[0], sy = o.motion_scale[1];
    if (o.motion_units == MotionUnits::Pixels) {
        sx /= layout.width;
        sy /= layout.height;
    }
    if (o.motion_y_up) sy = -sy;
    d.motion_scale[0] = static_cast<float>(sx);
    d.motion_scale[1] = static_cast<float>(sy);
    d.use_nocache_mask = layout.nocache ? 1u : 0u;
    d.depth_test = o.depth_test;
    d.use_object_id = layout.channels.object_id.empty() ? 0u : 1u;
    d.device_name = o.device.empty() ? nullptr : o.device.c_str();
    d.enable_validation = o.validation ? 1u : 0u;
    return d;
}

rrc_exr::ExrImage make_output_image(const SequenceLayout& layout, const FrameResult& r) {
    rrc_exr::ExrImage img;
    img.width = layout.width;
    img.height = layout.height;
    const std::size_t n = img.pixel_count();
    for (std::size_t k = 0; k < layout.signals.size(); ++k) {
        const SignalLayout& s = layout.signals[k];
        const std::string& layer = s.options.layer;
        for (std::size_t c = 0; c < s.components.size(); ++c) {
            std::vector<float>& out = img.channels[layer + "." + s.components[c]];
            out.resize(n);
            for (std::size_t i = 0; i < n; ++i) out[i] = r.values[k][i * s.rrc_components + c];
        }
        std::vector<float>& age = img.channels[layer + ".age"];
        age.assign(r.age[k].begin(), r.age[k].end());
        if (s.confidence) img.channels[layer + ".weight"] = r.weight[k];
    }
    std::vector<float>& mask = img.channels["rrc.mask"];
    mask.assign(r.mask.begin(), r.mask.end());
    img.attributes["rrc.mask"] = "bits: 1 HIT, 2 REFRESHED, 4 BACKGROUND, 8 INVALID_SAMPLE, 16 INVALID_GEOMETRY";
    return img;
}

std::vector<uint8_t> coherence_rgb(const std::vector<uint8_t>& mask) {
    std::vector<uint8_t> rgb(mask.size() * 3, 0);
    for (std::size_t i = 0; i < mask.size(); ++i) {
        const uint8_t m = mask[i];
        uint8_t r = 255, g = 0, b = 0;  // miss
        if (m & RRC_MASK_BACKGROUND)
            r = g = b = 64;
        else if (m & RRC_MASK_INVALID_GEOMETRY)
            r = 255, g = 0, b = 255;
        else if (m & RRC_MASK_REFRESHED)
            r = 0, g = 0, b = 255;
        else if (m & RRC_MASK_HIT)
            r = 0, g = 255, b = 0;
        rgb[3 * i] = r;
        rgb[3 * i + 1] = g;
        rgb[3 * i + 2] = b;
    }
    return rgb;
}

std::vector<std::string> metric_channels(const SignalLayout& signal) {
    std::vector<std::string> names;
    for (const std::string& c : signal.components)
        if (!(c == "A" && signal.components.size() > 1)) names.push_back(signal.options.layer + "." + c);
    return names;
}

}  // namespace rrc_cli
