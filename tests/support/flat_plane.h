// A fronto-parallel plane at depth 0.5 under CAMERA reprojection with one
// REUSE channel, and a camera that pans by whole pixels: every texel centre
// lands on a texel centre, so the expected values are exact.  The refresh
// tests on it (docs/CONVENTIONS.md, "Refresh policies") share the cases and
// the once-per-period count.
#pragma once

#include "support/rrc_test_context.h"

#include <algorithm>
#include <string>

namespace rrc_test {

// A camera panned by `shift` pixels in x on a width-pixel image: identity
// matrices but for the column-major NDC x translation (m[12]).
inline void pan(double shift, int width, double m[16]) {
    for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    m[12] = 2.0 * shift / width;
}

// One REUSE channel, fp32 and nearest: a hit gives the cached value exactly.
inline std::vector<rrc_channel_desc> one_reuse() {
    return {channel("shade", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST)};
}

struct FlatPlane {
    int width, height;
    std::vector<float> depth, shade;  // shade: the channel's samples, set by the test
    rrc_channel_input in{};

    FlatPlane(int w, int h) : width(w), height(h), depth((size_t)w * h, 0.5f), shade((size_t)w * h) {}

    // The context over `channels` (which must outlive it) with CAMERA reprojection.
    rrc_context_desc context(const std::vector<rrc_channel_desc>& channels) const {
        rrc_context_desc d = context_desc((uint32_t)width, (uint32_t)height, channels);
        d.reprojection = RRC_REPROJECTION_CAMERA;
        return d;
    }
    rrc_frame_desc frame(uint64_t index, double shift, double prev_shift) {
        in = channel_input(shade.data());
        rrc_frame_desc f = frame_desc();
        f.frame_index = index;
        f.depth = depth.data();
        f.channel_count = 1;
        f.channels = &in;
        pan(shift, width, f.view_proj);
        pan(prev_shift, width, f.prev_view_proj);
        return f;
    }
};

// f(d, flat, n, stride) for TILED and RANDOM, periods 1, 2, 4 and 8, frame
// indices stepping by 1 and by 3: each case a fresh width x height plane and
// its context `d` over `channels` refreshing by the policy every n frames.  A
// fatal failure ends the test as it would inside the loops.
template <typename F>
void for_each_refresh_case(int width, int height, const std::vector<rrc_channel_desc>& channels, F&& f) {
    for (rrc_refresh_policy policy : {RRC_REFRESH_TILED, RRC_REFRESH_RANDOM})
        for (uint32_t n : {1u, 2u, 4u, 8u})
            for (uint64_t stride : {uint64_t(1), uint64_t(3)}) {
                SCOPED_TRACE("policy " + std::to_string(policy) + " n " + std::to_string(n) + " stride " + std::to_string(stride));
                FlatPlane flat(width, height);
                rrc_context_desc d = flat.context(channels);
                d.refresh_policy = policy;
                d.refresh_period = n;
                f(d, flat, n, stride);
                if (::testing::Test::HasFatalFailure()) return;
            }
}

// Every pixel refreshed exactly once in each period of n frames.
class OncePerPeriod {
public:
    OncePerPeriod(size_t pixels, uint32_t n) : count_(pixels, 0), n_(n) {}
    void refreshed(size_t pixel) { ++count_[pixel]; }
    // After the k-th frame (from 0), frame index t: at a period's end, check and restart.
    void end_frame(uint32_t k, uint64_t t) {
        if ((k + 1) % n_ != 0) return;
        for (size_t i = 0; i < count_.size(); ++i) ASSERT_EQ(count_[i], 1) << "pixel " << i << " in the " << n_ << " frames to " << t;
        std::fill(count_.begin(), count_.end(), 0);
    }

private:
    std::vector<int> count_;
    uint32_t n_;
};

}  // namespace rrc_test
