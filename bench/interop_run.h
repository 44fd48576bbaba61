// The kernel timed through the interop path, interleaved with the roof: an
// rrc context on the bench's own device, each frame recorded into the
// bench's command buffer between two timestamps, and the roof dispatched
// between two timestamps of its own; the two alternate (order swapped every
// repetition so a drift of the machine hits both alike).
#pragma once

#include "bench_images.h"
#include "context_setup.h"
#include "fenced_commands.h"
#include "roof.h"

#include <rrc/rrc_vulkan.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rrc_bench {

struct InteropResult {
    std::vector<double> kernel_ms, roof_ms, ratio;  // per repetition (ratio of the pair)
    std::vector<double> wall_ms;                    // CPU wall clock of a kernel frame: record, submit, wait
    bool timestamps = false;                        // false: the device has none, *_ms are wall clock of the submission
    uint64_t memory_bytes = 0;                      // rrc_context_memory_usage
    rrc_vulkan_frame_stats stats{};                 // of one untimed frame after the timed ones
    bool io_counted = false;                        // that frame also counted its image operations (rrc_vulkan_record_frame's rows)
    rrc_vulkan_io_counts io{};                      // what it counted (rrc_vulkan_frame_desc.count_io)
    uint32_t listed_quads = 0;                      // Config::Cache::Split: the quads that frame listed
    uint64_t young = 0;                             // that frame's surface pixels of age < kYoungAge (channel 0)
    std::string roof_check;                         // "" exact, else what differs ("skipped" when not asked)
    RoofBytes roof_bytes_bound;                     // the bytes of the images the roof bound
};

/** One configuration's interop context and roof on the bench's device.
 *  step() runs one kernel/roof pair, so the caller can interleave
 *  configurations too: then every configuration sees the same drift of a
 *  shared machine, and times of different rows compare rep by rep. */
class InteropBench {
public:
    InteropBench(VulkanBootstrap& vk, const Config& config, const SceneInputs& scene, const BenchImages& images, LogCounter& log);
    ~InteropBench();
    InteropBench(const InteropBench&) = delete;
    InteropBench& operator=(const InteropBench&) = delete;

    /** One kernel frame and one roof dispatch (their order swaps every call);
     *  `record` false: warm-up (lavapipe compiles at the first dispatch, and
     *  the first frames have no history), not kept. */
    void step(bool record);
    /** `frames` untimed kernel frames (no roof): history to reach a steady state before the warm-up rounds. */
    void prime(int frames);
    /** An untimed frame with statistics, the roof check if asked; the result. */
    InteropResult finish(bool check_roof);

private:
    std::pair<double, double> kernel(bool with_stats);
    double roof_pass(int pose);
    double elapsed_ms(uint32_t first) const;
    uint64_t count_young();
    void release();
    VulkanBootstrap& vk_;
    const Config& config_;
    const SceneInputs& scene_;
    const BenchImages& img_;
    rrc_context* ctx_ = nullptr;
    rrc_host::Buffer stats_;
    rrc_host::Buffer quads_;  // Config::Cache::Split: classify's list
    std::unique_ptr<Roof> roof_;
    std::unique_ptr<rrc_host::TimestampQueries> timer_;
    std::unique_ptr<rrc_host::FencedCommands> sub_;
    std::vector<rrc_vulkan_channel_images> channels_;
    uint64_t frame_ = 0, steps_ = 0;
    InteropResult res_;
};

}  // namespace rrc_bench
