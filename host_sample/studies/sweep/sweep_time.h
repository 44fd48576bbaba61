// rrc-sweep's time model: how a row's signal_ms, rrc_ms and time_ms follow
// from the measured per-pass times (README.md, "Definitions", Time).  Pure
// functions of the measurements, so the arithmetic is tested on made-up
// timings (sweep_test.cpp, SweepTime) rather than on a loaded machine's
// clock, where 0 ms is a legitimate measurement.
#pragma once

#include <cstddef>
#include <vector>

namespace rrc_sweep {

/** The median; 0 for no samples (a row that was never timed). */
double median(std::vector<double> v);

/** One isolated submission: its timestamps' interval and its wall clock. */
struct Timing {
    double stamps_ms = 0.0, wall_ms = 0.0;
};

/** A pass's time on the chosen clock: the timestamps on a GPU; the wall clock less the
 *  fastest empty submission's on a CPU device (lavapipe's timestamps are wrong after graphics
 *  work), never below 0 (a pass faster than the empty floor's jitter). */
double pass_ms(const Timing& pass, const Timing& empty_floor, bool wall);

/** The submission overhead so far: the fastest empty submission, per clock (one slow empty
 *  submission under load must not eat a pass's time). */
Timing empty_floor(const Timing& floor_so_far, const Timing& empty);

/** What one context for all `apps` default channels saves each application: a share
 *  (1/apps) of the median over frames of (channels alone, summed) less the median of (one
 *  context together).  0 when the probe did not run (one application, or no frame timed).
 *  Negative when sharing costs more: the shares then grow, as measured. */
double sharing_saving_ms(const std::vector<double>& alone_sum_ms, const std::vector<double>& together_ms, size_t apps);

/** A row's share of rrc: its channel alone (median of the pooled samples) less the saving,
 *  never below 0 (a saving larger than the channel alone is timing noise, not negative work). */
double rrc_share_ms(double channel_alone_ms, double saving_ms);

/** A row's time: its signal pass plus its share of rrc (brute force: rrc_ms = 0). */
inline double row_time_ms(double signal_ms, double rrc_ms) { return signal_ms + rrc_ms; }

}  // namespace rrc_sweep
