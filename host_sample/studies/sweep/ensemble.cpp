#include "ensemble.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rrc_sweep {

void Ensemble::add(size_t c, const CheckpointTarget& t, const float* image, int stride, const float* previous) {
    Sums& s = sums_.at(c);
    const size_t n = t.pixels.size() * (size_t)t.components;
    if (s.sum.empty()) s.sum.assign(n, 0.0), s.sum_sq.assign(n, 0.0);
    for (size_t i = 0; i < t.pixels.size(); ++i) {
        const size_t p = t.pixels[i];
        for (int k = 0; k < t.components; ++k) {
            const double x = image[p * stride + k];
            s.sum[i * t.components + k] += x;
            s.sum_sq[i * t.components + k] += x * x;
            if (previous && t.is_static[i]) {
                s.flicker_sum += std::abs(x - (double)previous[p * stride + k]);
                ++s.flicker_count;
            }
        }
    }
    ++s.seeds;
}

Metrics Ensemble::metrics(const std::vector<CheckpointTarget>& targets) const {
    Metrics m;
    double flicker_sum = 0.0;
    uint64_t flicker_count = 0;
    m.seeds = sums_.empty() ? 0 : sums_[0].seeds;
    for (size_t c = 0; c < sums_.size(); ++c) {
        const Sums& s = sums_[c];
        const CheckpointTarget& t = targets.at(c);
        if (s.seeds < 2) throw std::runtime_error("an ensemble needs at least 2 seeds at every checkpoint");
        const double S = s.seeds;
        double mse = 0.0, mean_err2 = 0.0, var = 0.0;
        const size_t n = s.sum.size();
        for (size_t i = 0; i < n; ++i) {
            const double r = t.target[i], mean = s.sum[i] / S;
            // (1/S) sum_s (x_s - r)^2, from the sums.
            mse += (s.sum_sq[i] - 2.0 * r * s.sum[i]) / S + r * r;
            mean_err2 += (mean - r) * (mean - r);
            var += std::max(s.sum_sq[i] - S * mean * mean, 0.0) / (S - 1.0);
        }
        mse /= (double)n, mean_err2 /= (double)n, var /= (double)n;
        m.mse_measured += mse;
        m.variance += var;
        // E[(mean - r)^2] = bias^2 + var/S + the target's noise.
        m.bias2 += mean_err2 - var / S - t.noise;
        m.reference_noise += t.noise;
        flicker_sum += s.flicker_sum;
        flicker_count += s.flicker_count;
        ++m.checkpoints;
    }
    if (m.checkpoints == 0) return m;
    const double C = m.checkpoints;
    m.mse_measured /= C, m.variance /= C, m.bias2 /= C, m.reference_noise /= C;
    const double mse = std::max(m.mse_measured - m.reference_noise, 0.0);
    m.rmse = std::sqrt(mse);
    m.psnr = -10.0 * std::log10(std::max(mse, 1e-30));
    m.flicker = flicker_count ? flicker_sum / (double)flicker_count : std::numeric_limits<double>::quiet_NaN();
    return m;
}

}  // namespace rrc_sweep
