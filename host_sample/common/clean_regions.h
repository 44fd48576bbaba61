// What rrc adds to a clean input, by region (docs/measurements/OFFLINE.md, "What rrc adds
// to a clean input"): on a noise-free input the accumulated output should be
// nearly the input itself, so its error against the frame's own input is what
// reprojection, resampling and the fill add.  Every pixel is put in one region
// by a fixed precedence, so the regions' squared errors and pixel counts add up
// to the image's.  CPU only; rrc-accumulate --clean-report and rrc-sweep
// --study clean share it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rrc_host {

/** The regions in their precedence order: a pixel belongs to the first one whose test it passes. */
enum CleanRegion : uint8_t {
    kCleanBackground = 0,  // RRC_MASK_BACKGROUND: out = s by definition
    kCleanEdge,            // within kCleanEdgeRadius px of a depth discontinuity, an object-id boundary or the background
    kCleanFilled,          // the channel has a fill (fill_age T > 0) and the pixel's age is below T
    kCleanMiss,            // no RRC_MASK_HIT (a miss or a refresh), not filled
    kCleanYoung,           // a hit whose age is below the young age (4 without a fill), not filled
    kCleanHistory,         // every other hit: resampled history
    kCleanRegionCount
};
const char* clean_region_name(int region);  // background, edge, filled, miss, young, history

constexpr uint32_t kCleanYoungAge = 4;     // young without a fill: age after the frame below this
constexpr int kCleanEdgeRadius = 1;        // edge: Chebyshev distance to a seed
constexpr float kCleanDepthJump = 0.05f;   // edge seed: |second difference of u| > kCleanDepthJump * u

/** One frame of one channel, row-major, width * height each.  inverse_depth (u) is a value
 *  proportional to 1 / view depth, affine in screen space on any plane, so its second difference
 *  is 0 on planes and large across a jump between surfaces: STANDARD 1 - z, REVERSED z, LINEAR 1/d
 *  (clean_inverse_depth); 0 or less on the background. */
struct CleanFrame {
    uint32_t width = 0, height = 0;
    const uint8_t* mask = nullptr;          // rrc's RRC_MASK_* bits
    const uint16_t* age = nullptr;          // the channel's age after the frame
    const float* inverse_depth = nullptr;   // may be null: no depth seeds
    const uint32_t* object_id = nullptr;    // may be null: no object seeds
    uint32_t fill_age = 0;                  // the channel's fill_age; 0 = no fill
};

/** Pixels within `radius` (Chebyshev) of a set pixel of `in` (w x h): a separable box dilation.
 *  The sweep's bias regions dilate their edges with it too. */
std::vector<uint8_t> dilate_chebyshev(const std::vector<uint8_t>& in, uint32_t w, uint32_t h, int radius);

/** Whether u (w x h, proportional to 1 / view depth, as CleanFrame::inverse_depth) jumps at (x, y):
 *  its second difference along x or y above jump * u (0 on planes, large across surfaces).  The
 *  sweep's bias regions seed their edges with it too. */
bool inverse_depth_jump(const float* u, uint32_t w, uint32_t h, uint32_t x, uint32_t y, float jump);

/** u of clean_frame.inverse_depth from a depth in one of rrc's modes (RRC_DEPTH_MODE_*). */
float clean_inverse_depth(uint32_t depth_mode, float depth);

/** Per pixel its CleanRegion.  Throws std::invalid_argument on a missing mask or age. */
std::vector<uint8_t> clean_regions(const CleanFrame& frame);

/** Squared errors of the output against the input by region. */
struct CleanSums {
    double sse[kCleanRegionCount] = {};
    uint64_t pixels[kCleanRegionCount] = {};
    uint64_t values[kCleanRegionCount] = {};  // pixels * compared components
    uint64_t skipped = 0;                     // pixels with a non-finite input or output value, left out
    void add(const CleanSums& other);
    double total_sse() const;
    uint64_t total_pixels() const;
    uint64_t total_values() const;
    double rmse(int region) const;  // region == kCleanRegionCount: over every pixel
};

/** Adds one frame: `input` and `output` hold `stride` floats a pixel, the first `components` compared.
 *  scored (optional): only the pixels where it is non-zero count (an application that scores part
 *  of the image, such as the sweep's env on its sphere). */
void add_clean_errors(CleanSums& sums, const std::vector<uint8_t>& regions, const float* input, const float* output, int stride,
                      int components, const uint8_t* scored = nullptr);

/** The report's table (markdown): a row per region and the total, each with its RMSE, its share of
 *  the squared error and its share of the pixels. */
std::string clean_table(const CleanSums& sums);
/** CSV lines "<prefix>,region,pixels,values,sse,rmse" (no header), a line per region and "all". */
std::string clean_csv_rows(const std::string& prefix, const CleanSums& sums);
constexpr const char* kCleanCsvColumns = "region,pixels,values,sse,rmse";
/** A number as the reports print it: `v` through printf's `fmt`. */
std::string clean_number(double v, const char* fmt);

}  // namespace rrc_host
