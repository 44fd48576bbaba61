#include "sweep_time.h"

#include <algorithm>

namespace rrc_sweep {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double pass_ms(const Timing& pass, const Timing& empty_floor, bool wall) {
    return wall ? std::max(pass.wall_ms - empty_floor.wall_ms, 0.0) : pass.stamps_ms;
}

Timing empty_floor(const Timing& floor_so_far, const Timing& empty) {
    return Timing{std::min(floor_so_far.stamps_ms, empty.stamps_ms), std::min(floor_so_far.wall_ms, empty.wall_ms)};
}

double sharing_saving_ms(const std::vector<double>& alone_sum_ms, const std::vector<double>& together_ms, size_t apps) {
    if (together_ms.empty() || alone_sum_ms.empty() || apps == 0) return 0.0;
    return (median(alone_sum_ms) - median(together_ms)) / (double)apps;
}

double rrc_share_ms(double channel_alone_ms, double saving_ms) { return std::max(channel_alone_ms - saving_ms, 0.0); }

}  // namespace rrc_sweep
