// The standalone path: rrc_context_create (the library's own device) and
// rrc_frame_run with CPU arrays, i.e. uploads, the kernel and readbacks in
// one call (the shading cache's rows make the interop path's calls:
// classify, then resolve or the fused frame).  Beside it, in the same process and interleaved with it, a
// memcpy of the same bytes (every input array and every output array), so
// the report can set the round trip against "kernel time + memcpy of its
// bytes": what an ideal standalone path would cost.
#pragma once

#include "context_setup.h"
#include "scene.h"

#include <string>
#include <vector>

namespace rrc_bench {

struct StandaloneResult {
    std::vector<double> frame_ms;   // wall clock of one rrc_frame_run
    std::vector<double> memcpy_ms;  // one memcpy of `bytes`
    uint64_t bytes = 0;             // inputs passed + outputs read back
    uint64_t memory_bytes = 0;      // rrc_context_memory_usage (staging included)
    uint64_t validation_messages = 0;
    std::string device;
    double hit_fraction = 0;        // hits / pixels of the last frame
};

/** The standalone context of a configuration; each step() runs one frame and
 *  one memcpy, so the caller can interleave them with the interop kernel's
 *  repetitions (the machine's drift then hits both alike). */
class StandaloneBench {
public:
    StandaloneBench(const Config& config, const SceneInputs& scene, LogCounter& log, const std::string& device, bool validation);
    ~StandaloneBench();
    StandaloneBench(const StandaloneBench&) = delete;
    StandaloneBench& operator=(const StandaloneBench&) = delete;

    /** One frame and one memcpy; `record` false: warm-up, not kept. */
    void step(bool record);
    /** The timings so far, with memory, validation count and device. */
    StandaloneResult result() const;

private:
    double run_frame();
    double copy();
    const Config& config_;
    const SceneInputs& scene_;
    rrc_context* ctx_ = nullptr;
    std::vector<std::vector<float>> values_, weights_;
    std::vector<std::vector<uint16_t>> ages_;
    std::vector<uint8_t> mask_;
    std::vector<uint32_t> quads_;  // the shading cache's rows: classify's list
    std::vector<rrc_channel_output> outs_;
    std::vector<unsigned char> src_, dst_;
    uint64_t frame_ = 0;
    StandaloneResult res_;
};

}  // namespace rrc_bench
