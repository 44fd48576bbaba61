// Where the bias sits (README.md, "Bias maps"): every scored pixel of a
// checkpoint is put in one region by a fixed precedence, and a row's bias²
// and variance over seeds are split over the regions, so that the parts add
// up exactly to the row's totals (ensemble.h).  CPU only: the sweep feeds it
// the G-buffer, rrc's mask and age and the targets it read back.
#pragma once

#include "ensemble.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rrc_sweep {

/** The regions in their precedence order: a pixel belongs to the first one whose test it passes. */
enum Region : uint8_t { kRegionObject = 0, kRegionEdge, kRegionYoung, kRegionChanged, kRegionStatic, kRegionCount };
constexpr uint8_t kRegionUnscored = 255;  // in a region image: a pixel the application does not score
const char* region_name(int region);       // object, edge, young, changed, static

/** The thresholds of the tests (README.md, "Bias maps", where each is defined). */
struct RegionThresholds {
    float depth_jump = 0.05f;     // edge: |second difference of reversed-z depth| > depth_jump * depth, along x or y
    int edge_radius = 1;          // edge: within this many pixels (Chebyshev) of a jump, the background or an rrc miss
    uint32_t young_age = 4;       // young: rrc's age after the frame below this
    uint8_t object_material = 0;  // object: the G-buffer's material id of the moving object (the torus)
};

/** The application-independent inputs at one checkpoint frame t (row-major, width * height). */
struct RegionFrame {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> material;  // the G-buffer's material id at t
    std::vector<float> depth;       // reversed-z depth at t (0: background)
    std::vector<uint8_t> mask;      // rrc's RRC_MASK_* bits at t
    std::vector<uint16_t> age;      // rrc's age after t
};

/** The target a surface point had in an earlier frame t - j, over the whole image: `stride` floats a
 *  pixel, the CheckpointTarget's `components` of them compared.  Two kinds (README.md, "Bias maps"):
 *  - at_same_point (pcf, soft: the signal does not depend on the eye): frame t - j's scene (its light,
 *    its moving object) seen from frame t's camera, so pixel p shows the same surface point in both
 *    and is compared with itself, without resampling: a moving camera alone changes nothing;
 *  - otherwise (env: the reflection depends on the eye): frame t - j's own image, read bilinearly where
 *    the pixel's surface point (its world position at t; env's sphere does not move) projects with
 *    frame t - j's view_proj, from the texels scored there. */
struct PreviousTarget {
    const float* values = nullptr;
    int stride = 1;
    std::vector<uint8_t> scored;    // per pixel: scored in that image
    bool at_same_point = false;
    std::vector<uint8_t> material;  // at_same_point: the material each pixel shows there (another one: a disocclusion)
    double view_proj[16] = {};      // otherwise: frame t - j's, column-major
};

/** Marks (sets to 1) the pixels of `now` whose target differs from `previous` by more than `tau` in any
 *  component; `changed` and `position` (4 floats a pixel, the world position at t) cover the image.  No
 *  previous value for the pixel (another surface there, or no scored texel): not marked, a disocclusion,
 *  which the edge and young tests take.  Called once per earlier frame of the window. */
void mark_changes(std::vector<uint8_t>& changed, const CheckpointTarget& now, const PreviousTarget& previous, const float* position,
                  const std::vector<uint8_t>& material_now, uint32_t width, uint32_t height, float tau);

/** One checkpoint's regions, per scored pixel in CheckpointTarget::pixels order. */
struct RegionMap {
    std::vector<uint8_t> region;  // by precedence
    std::vector<uint8_t> bits;    // 1 << r for every region r whose test the pixel passes (they overlap)
};

/** changed: per image pixel, the target changed within the window (mark_changes). */
RegionMap classify_regions(const RegionFrame& frame, const CheckpointTarget& now, const std::vector<uint8_t>& changed,
                           const RegionThresholds& thresholds);

/** One row's bias² and variance split over the regions, averaged over the checkpoints as Ensemble::metrics is. */
struct RegionParts {
    double pixel_share[kRegionCount] = {};  // of the scored pixels, by precedence
    double raw_share[kRegionCount] = {};    // of the scored pixels passing the region's own test (overlapping)
    double bias2[kRegionCount] = {};        // summed over the regions: Metrics::bias2
    double variance[kRegionCount] = {};     // summed over the regions: Metrics::variance
    int checkpoints = 0;
};

RegionParts decompose(const Ensemble& ensemble, const std::vector<CheckpointTarget>& targets, const std::vector<RegionMap>& maps);

/** The signed bias map at checkpoint c: per pixel the mean over components of (mean over seeds - target);
 *  NaN where the application scores nothing.  width * height values. */
std::vector<float> bias_map(const Ensemble& ensemble, size_t c, const CheckpointTarget& target, size_t pixel_count);

/** The region image: per pixel its region, kRegionUnscored where nothing is scored. */
std::vector<uint8_t> region_image(const RegionMap& map, const CheckpointTarget& target, size_t pixel_count);

/** rrc's age after a frame, followed on the host from its mask as the sample's age.comp does (docs/CONVENTIONS.md):
 *  background 0, miss 1, hit min(n + 1, cap) with n fetched nearest at the pixel's previous position. */
std::vector<uint16_t> next_age(const std::vector<uint16_t>& age_before, const std::vector<uint8_t>& mask, const float* prev_clip,
                               uint32_t width, uint32_t height, uint32_t cap);

}  // namespace rrc_sweep
