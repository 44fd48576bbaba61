// The kernel timed through the interop path, interleaved with the roof: an
// rrc context on the bench's own device, each frame recorded into the
// bench's command buffer between two timestamps, and the roof dispatched
// between two timestamps of its own; the two alternate (order swapped every
// repetition so a drift of the machine hits both alike).
#pragma once

#include "bench_images.h"
#include "context_setup.h"
#include "roof.h"

#include <rrc/rrc_vulkan.h>

#include <functional>
#include <string>
#include <vector>

namespace rrc_bench {

struct InteropResult {
    std::vector<double> kernel_ms, roof_ms, ratio;  // per repetition (ratio of the pair)
    std::vector<double> wall_ms;                    // CPU wall clock of a kernel frame: record, submit, wait
    bool timestamps = false;                        // false: the device has none, *_ms are wall clock of the submission
    uint64_t memory_bytes = 0;                      // rrc_context_memory_usage
    rrc_vulkan_frame_stats stats{};                 // of one untimed frame after the timed ones
    std::string roof_check;                         // "" exact, else what differs ("skipped" when not asked)
    RoofBytes roof_bytes_bound;                     // the bytes of the images the roof bound
};

/** `between(record)`, if given, runs after each warm-up (record false) and
 *  timed (record true) kernel/roof pair: the standalone path interleaves there. */
InteropResult run_interop(VulkanBootstrap& vk, const Config& config, const SceneInputs& scene, BenchImages& images, LogCounter& log,
                          int reps, int warmup, bool check_roof, const std::function<void(bool)>& between = {});

}  // namespace rrc_bench
