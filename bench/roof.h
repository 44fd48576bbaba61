// The roof of a configuration (roof.comp): its pipeline, specialised to the
// configuration, one descriptor set per camera pose, the byte bookkeeping,
// and the exact-copy check the smoke test relies on.
#pragma once

#include "bench_images.h"

#include <string>

namespace rrc_bench {

struct RoofBytes {
    uint64_t read = 0, written = 0;
    uint32_t loads_per_pixel = 0, stores_per_pixel = 0;  // the roof's image loads and stores a pixel (roof_bytes_from_api only)
    uint64_t total() const { return read + written; }
};

/** The bytes the API implies for `config` (docs/measurements/PERFORMANCE.md, "The roof"),
 *  from formats alone: per-pixel sums times the pixel count. */
RoofBytes roof_bytes_from_api(const Config& config);

class Roof {
public:
    Roof(VulkanBootstrap& vk, const Config& config, const BenchImages& images);
    ~Roof();
    Roof(const Roof&) = delete;
    Roof& operator=(const Roof&) = delete;

    /** One dispatch reading pose `pose`'s inputs; the caller orders it with barriers. */
    void record(VkCommandBuffer cmd, int pose) const;
    /** The bytes of the images actually bound (each read or written once): must equal roof_bytes_from_api. */
    RoofBytes bound_bytes() const { return bound_; }
    /** Reads the outputs back and compares each with the input it copies, after
     *  a dispatch of `pose`.  "" when exact, else what differs. */
    std::string check(int pose) const;

private:
    VulkanBootstrap& vk_;
    const Config& config_;
    const BenchImages& images_;
    RoofBytes bound_;
    std::vector<Image> placeholders_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet sets_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
};

}  // namespace rrc_bench
