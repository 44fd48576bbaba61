#include "output.h"

#include "exr_io.h"
#include "png_io.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace rrc_sample {
namespace {

std::string numbered(const std::string& dir, const char* stem, int index, const char* suffix) {
    char name[128];
    std::snprintf(name, sizeof name, "%s_%04d%s", stem, index, suffix);
    return (std::filesystem::path(dir) / name).string();
}

rrc_png::RgbImage rgb_image(uint32_t w, uint32_t h, std::vector<uint8_t> rgb) {
    rrc_png::RgbImage img;
    img.width = (int)w;
    img.height = (int)h;
    img.rgb = std::move(rgb);
    return img;
}

std::vector<uint8_t> rgba_to_rgb(const std::vector<uint8_t>& rgba) {
    std::vector<uint8_t> rgb(rgba.size() / 4 * 3);
    for (size_t i = 0; i < rgba.size() / 4; ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = rgba[i * 4 + c];
    return rgb;
}

// Splits interleaved components into named EXR channels: layer.Y or layer.R/G/B/A.
void add_layer(rrc_exr::ExrImage& img, const std::string& layer, const std::vector<float>& v, int components) {
    if (v.empty()) return;
    const size_t n = img.pixel_count();
    const char* names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < components; ++c) {
        std::vector<float> plane(n);
        for (size_t i = 0; i < n; ++i) plane[i] = v[i * components + c];
        img.channels[layer + "." + (components == 1 ? "Y" : names[c])] = std::move(plane);
    }
}

}  // namespace

std::vector<uint8_t> coherence_map(const std::vector<uint8_t>& mask) {
    std::vector<uint8_t> rgb(mask.size() * 3, 0);
    for (size_t i = 0; i < mask.size(); ++i) {
        const uint8_t m = mask[i];
        uint8_t* p = &rgb[i * 3];
        if (m & RRC_MASK_BACKGROUND) continue;
        if (m & RRC_MASK_REFRESHED)
            p[2] = 230;
        else if (m & RRC_MASK_HIT)
            p[1] = 200;
        else
            p[0] = 230;
    }
    return rgb;
}

std::vector<uint8_t> age_heat_map(const std::vector<uint16_t>& age, uint32_t full) {
    std::vector<uint8_t> rgb(age.size() * 3, 0);
    for (size_t i = 0; i < age.size(); ++i) {
        if (!age[i]) continue;
        const float t = std::min((float)age[i] / (float)full, 1.0f);
        const float r = std::min(1.0f, 0.25f + 3.0f * t), g = std::clamp(3.0f * t - 1.0f, 0.0f, 1.0f),
                    b = std::clamp(3.0f * t - 2.0f, 0.0f, 1.0f);
        rgb[i * 3 + 0] = (uint8_t)(255.0f * r + 0.5f);
        rgb[i * 3 + 1] = (uint8_t)(255.0f * g + 0.5f);
        rgb[i * 3 + 2] = (uint8_t)(255.0f * b + 0.5f);
    }
    return rgb;
}

OutputWriter::OutputWriter(const std::string& out_dir, uint32_t w, uint32_t h) : dir_(out_dir), width_(w), height_(h) {
    for (const char* sub : {"frames", "coherence", "age", "exr", "oracle"})
        std::filesystem::create_directories(std::filesystem::path(dir_) / sub);
}

std::vector<uint8_t> oracle_map(const std::vector<uint8_t>& verdict) {
    std::vector<uint8_t> rgb(verdict.size() * 3, 0);
    for (size_t i = 0; i < verdict.size(); ++i) {
        const uint8_t v = verdict[i];
        const bool hit = v & kVerdictHit;
        uint8_t c[3] = {0, 0, 0};
        auto set = [&](uint8_t r, uint8_t g, uint8_t b) { c[0] = r, c[1] = g, c[2] = b; };
        if (v & kVerdictExcluded)
            set(255, 0, 255);
        else if (!(v & kVerdictSurface))
            set(0, 0, 0);
        else if (hit && !(v & kVerdictVisible))
            set(255, 0, 0);  // false hits first: they matter most, straddling or not
        else if (v & kVerdictStraddling)
            hit ? set(170, 170, 170) : set(80, 80, 80);
        else if (v & kVerdictVisible)
            hit ? set(0, 150, 0) : set(255, 220, 0);
        else
            set(0, 60, 200);
        for (int k = 0; k < 3; ++k) rgb[i * 3 + k] = c[k];
    }
    return rgb;
}

void OutputWriter::write_oracle(int index, const std::vector<uint8_t>& verdict) const {
    rrc_png::write_png(numbered((std::filesystem::path(dir_) / "oracle").string(), "oracle", index, ".png"),
                       rgb_image(width_, height_, oracle_map(verdict)));
}

void OutputWriter::write(const FrameOutput& f) const {
    namespace fs = std::filesystem;
    const std::string frames = (fs::path(dir_) / "frames").string(), exr = (fs::path(dir_) / "exr").string();
    rrc_png::write_png(numbered(frames, "frame", f.index, ".png"), rgb_image(width_, height_, rgba_to_rgb(f.colour[0])));
    if (f.checkpoint) {
        rrc_png::write_png(numbered(frames, "frame", f.index, "_raw.png"), rgb_image(width_, height_, rgba_to_rgb(f.colour[1])));
        rrc_png::write_png(numbered(frames, "frame", f.index, "_reference.png"), rgb_image(width_, height_, rgba_to_rgb(f.colour[2])));
    }
    rrc_png::write_png(numbered((fs::path(dir_) / "coherence").string(), "coherence", f.index, ".png"),
                       rgb_image(width_, height_, coherence_map(f.mask)));
    rrc_png::write_png(numbered((fs::path(dir_) / "age").string(), "age", f.index, ".png"),
                       rgb_image(width_, height_, age_heat_map(f.age, 64)));

    auto write_signal = [&](const char* name, const SignalData& s, bool soft) {
        if (s.raw.empty()) return;
        rrc_exr::ExrImage img;
        img.width = (int)width_;
        img.height = (int)height_;
        add_layer(img, "raw", s.raw, s.components);
        add_layer(img, "accumulated", s.accumulated, s.components);
        add_layer(img, "reference", s.reference, s.components);
        // Checkpoints: the brute force at 4x the samples, and the residual's base (the guides' pictures, docs/guide/).
        if (!s.brute_force.empty()) add_layer(img, "brute_force_4x", s.brute_force, s.components);
        if (!s.base.empty()) add_layer(img, "base", s.base, s.components);
        if (soft) {
            add_layer(img, "shown", s.shown, 1);
            add_layer(img, "pcss", s.pcss, 1);
        }
        img.uint_channels["rrc.mask"] = std::vector<uint32_t>(f.mask.begin(), f.mask.end());
        img.uint_channels["age"] = std::vector<uint32_t>(f.age.begin(), f.age.end());  // the track age
        img.uint_channels["rrc.age"] = std::vector<uint32_t>(s.age.begin(), s.age.end());  // the channel's, from rrc
        img.attributes["rrc.signal"] = name;
        rrc_exr::write_exr(numbered(exr, name, f.index, ".exr"), img);
    };
    write_signal("pcf", f.pcf, false);
    write_signal("env", f.env, false);
    write_signal("soft", f.soft, true);
}

}  // namespace rrc_sample
