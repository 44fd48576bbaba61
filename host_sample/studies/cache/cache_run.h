// rrc-cache's GPU loop: rrc-sample's temple scene rasterised into a
// G-buffer, then either the procedural shader on every pixel (the frame
// without the cache) or rrc's shading cache: classify, the miss shader on
// the listed quads only (vkCmdDispatchIndirect), resolve.  Each pass runs in
// a submission of its own and is timed by the wall clock less the fastest
// empty submission (lavapipe's timestamps are unreliable after a render;
// host_sample/studies/sweep/README.md).  Only rrc's public headers are used.
#pragma once

#include <rrc/rrc.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rrc_cache {

// perlin.glsl's octave count: its specialization constant kOctaves (SpecId 0).
constexpr uint32_t kOctavesSpecId = 0, kDefaultOctaves = 8, kMaxOctaves = 256;

struct CacheConfig {
    std::string name;
    bool cache = true;  // false: shade every pixel (the baseline)
    rrc_refresh_policy policy = RRC_REFRESH_NONE;
    uint32_t period = 0;     // n
    uint32_t lifetime = 0;   // max_lifetime L, 0 = none
    bool stereo = false;     // a second eye (view 1) reusing the first eye's shading
    uint32_t subframes = 1;  // > 1: motion blur, the mean of this many sub-frames within the
                             // frame's time, each reusing the one before (the cache at that rate)
    uint32_t octaves = kDefaultOctaves;  // of the shader (perlin.glsl), its cost
};

struct FrameRecord {
    double raster_ms = 0, shade_ms = 0, classify_ms = 0, resolve_ms = 0;  // summed over the eyes
    // Cached runs: the same frame's G-buffer shaded everywhere (the error target), timed in its own
    // submission right after resolve, so the baseline is measured beside each cached frame under the
    // same machine load (a separate `full` run minutes earlier is not, on a shared machine).
    double full_shade_ms = 0;
    uint32_t listed = 0, shaded_quads = 0;  // rrc's count and the miss shader's own count
    double shaded_fraction = 0;             // shaded pixels / pixels (every eye)
    double rmse = 0;                        // of the shown frame against shading every pixel of it
    uint64_t hits = 0, refreshed = 0, pixels = 0;
    double total_ms() const { return raster_ms + shade_ms + classify_ms + resolve_ms; }  // every eye and sub-frame
    double full_total_ms() const { return raster_ms + full_shade_ms; }                   // the paired baseline
};

struct RunResult {
    CacheConfig config;
    std::vector<FrameRecord> frames;
    uint64_t validation_messages = 0;
    // The last frame's pictures (first eye; stereo: the second eye's too), RGBA32F and the mask.
    std::vector<float> image, truth, image_left;
    std::vector<uint8_t> mask, mask_left;
    bool list_matched = true;  // every frame: the miss shader shaded exactly the listed quads
};

struct Settings {
    uint32_t width = 320, height = 180;
    int frames = 24;
    bool validation = false;
    float eye_separation = 0.065f;  // world units (metres) between the two eyes
};

class Bench {
public:
    explicit Bench(const Settings& settings);
    ~Bench();
    Bench(const Bench&) = delete;
    Bench& operator=(const Bench&) = delete;
    RunResult run(const CacheConfig& config, void (*progress)(int frame, int frames));
    std::string device_name() const;
    std::vector<std::string> validation_messages() const;  // the first ones the layer sent

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rrc_cache
