// Error statistics of one configuration over an ensemble of seeds, against
// one fixed target per checkpoint frame (docs/measurements/PERFORMANCE.md, "Error against
// run time"): mean squared error, squared bias and variance per pixel, the
// reference's own noise subtracted, and the flicker on static pixels.
// CPU only, no Vulkan: the sweep feeds it the values it read back.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rrc_sweep {

/** The pixels one application is scored on at one checkpoint, and its target there. */
struct CheckpointTarget {
    std::vector<uint32_t> pixels;  // indices into the image (row-major)
    int components = 1;            // values per pixel that are scored (env: 3, RGB)
    std::vector<double> target;    // pixels.size() * components
    double noise = 0.0;            // the target's own variance per value (mean over values): subtracted from the MSE
    std::vector<uint8_t> is_static;  // per pixel: the target did not change since the previous frame (flicker)
};

struct Metrics {
    double mse_measured = 0.0;  // mean over seeds, values and checkpoints of (x - target)^2
    double reference_noise = 0.0;
    double rmse = 0.0;      // sqrt(max(mse_measured - reference_noise, 0))
    double psnr = 0.0;      // peak 1
    double bias2 = 0.0;     // (mean over seeds - target)^2, corrected for the mean's and the target's variance
    double variance = 0.0;  // across seeds, per value (unbiased), averaged
    double flicker = 0.0;   // mean |x_t - x_(t-1)| on static pixels, NaN when none was given
    int seeds = 0, checkpoints = 0;
};

/** Accumulates one configuration's values, checkpoint by checkpoint and seed by seed. */
class Ensemble {
public:
    explicit Ensemble(size_t checkpoints) : sums_(checkpoints) {}

    /** One seed's image at checkpoint c: `image` holds `stride` floats per pixel
     *  (components read from the first target.components of them).  `previous`
     *  (same layout, the frame before; may be null) adds to the flicker. */
    void add(size_t c, const CheckpointTarget& target, const float* image, int stride, const float* previous = nullptr);

    Metrics metrics(const std::vector<CheckpointTarget>& targets) const;

    /** Checkpoint c's sums over seeds of x and x² per value (CheckpointTarget::target's order), and its seeds:
     *  what bias_regions.h splits by region. */
    const std::vector<double>& sum(size_t c) const { return sums_.at(c).sum; }
    const std::vector<double>& sum_sq(size_t c) const { return sums_.at(c).sum_sq; }
    int seeds(size_t c) const { return sums_.at(c).seeds; }
    size_t checkpoints() const { return sums_.size(); }

private:
    struct Sums {
        std::vector<double> sum, sum_sq;
        int seeds = 0;
        double flicker_sum = 0.0;
        uint64_t flicker_count = 0;
    };
    std::vector<Sums> sums_;
};

}  // namespace rrc_sweep
