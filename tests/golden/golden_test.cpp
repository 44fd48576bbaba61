// The kernel against the committed golden EXR files (tests/data), made by
// rrc-make-golden from the analytic scenes and the double-precision
// reference; and the reference against its own committed output, so neither
// can drift unnoticed.
#include "golden/golden_io.h"
#include "support/tolerance.h"

#include <cstdlib>

using namespace rrc_golden;
using namespace rrc_test;

namespace {

std::string data_dir() {
    const char* d = std::getenv("RRC_TEST_DATA");
    return d ? d : "tests/data";
}

class Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, KernelMatchesGoldenFrame) {
    const GoldenCase& c = GetParam();
    GoldenData g = read_golden(golden_file(data_dir(), c), c);
    std::vector<rrc_channel_desc> channels;
    Context ctx(context_for(c, channels));
    ASSERT_TRUE(ctx);
    g.frames[0].bind(c);
    g.frames[1].bind(c);
    FrameResult first = ctx.run(g.frames[0].desc);
    EXPECT_EQ(first.stats.hits, 0u) << "the first frame is all misses";
    FrameResult k = ctx.run(g.frames[1].desc);
    const size_t n = (size_t)kWidth * kHeight;
    size_t compared = 0, flips = 0, hits = 0;
    for (size_t i = 0; i < n; ++i) {
        if (k.mask[i] != g.expected.mask[i]) {
            EXPECT_TRUE(g.expected.near_threshold[i])
                << c.name << " pixel " << i << " mask " << int(k.mask[i]) << " golden " << int(g.expected.mask[i]);
            ++flips;
            continue;
        }
        hits += (k.mask[i] & RRC_MASK_HIT) ? 1 : 0;
        if (g.expected.near_nearest_edge[i]) continue;
        ++compared;
        for (size_t ch = 0; ch < c.channels.size(); ++ch) {
            EXPECT_EQ(k.age[ch][i], g.expected.channels[ch].age[i]) << c.name << " pixel " << i;
            const uint32_t m = c.channels[ch].components;
            const bool fp16 = c.channels[ch].precision == RRC_HISTORY_FP16;
            for (uint32_t q = 0; q < m; ++q) {
                double rv = g.expected.channels[ch].out[m * i + q];
                // Frame 0 missed everywhere, so the history is frame 0's samples as stored.
                double spread = history_spread(first.values[ch], m, q, kWidth, kHeight, g.expected.uv_prev_x[i], g.expected.uv_prev_y[i],
                                               g.frames[1].prev_jitter);
                double tol = arithmetic_tolerance(rv, rv, fp16) + position_tolerance(spread, kWidth, kHeight);
                EXPECT_NEAR(k.values[ch][m * i + q], rv, tol) << c.name << " pixel " << i << " channel " << ch;
            }
            if (!g.expected.channels[ch].weight.empty())
                EXPECT_NEAR(k.weight[ch][i], g.expected.channels[ch].weight[i], 1e-6 + 1e-5 * g.expected.channels[ch].weight[i]);
        }
    }
    EXPECT_GT(hits, n / 3) << c.name << ": the golden frame must exercise hits";
    EXPECT_GT(compared, n * 9 / 10) << c.name;
    std::printf("%-26s hits %zu compared %zu/%zu flips within margin %zu\n", c.name.c_str(), hits, compared, n, flips);
}

// The committed files are what the generator makes today: the reference
// has not changed under them.
TEST_P(Golden, ReferenceReproducesCommittedFile) {
    const GoldenCase& c = GetParam();
    GoldenData committed = read_golden(golden_file(data_dir(), c), c);
    GoldenData now = compute_golden(c);
    EXPECT_EQ(committed.expected.mask, now.expected.mask);
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        EXPECT_EQ(committed.expected.channels[ch].age, now.expected.channels[ch].age);
        ASSERT_EQ(committed.expected.channels[ch].out.size(), now.expected.channels[ch].out.size());
        for (size_t i = 0; i < now.expected.channels[ch].out.size(); ++i)
            ASSERT_EQ((float)now.expected.channels[ch].out[i], committed.expected.channels[ch].out[i]) << c.name << " value " << i;
    }
    EXPECT_EQ(committed.frames[1].depth, now.frames[1].depth);
}

INSTANTIATE_TEST_SUITE_P(Cases, Golden, ::testing::ValuesIn(golden_cases()),
                         [](const ::testing::TestParamInfo<GoldenCase>& i) { return i.param.name; });

}  // namespace
