// What the library owns per channel in both modes: the ping-pong history,
// age, (with confidence) weight and (with the deviation gate) the gate's
// state; plus the 1x1 placeholder images bound
// wherever a configuration leaves a kernel binding unused.
#pragma once

#include "accumulate_pipeline.h"
#include "config.h"
#include "gpu_resources.h"

#include <vector>

namespace rrc {

// A 1-component fp16 channel keeps its value (low 16 bits, fp16) and age
// (high 16 bits) in one R32_UINT word and has no age image: one load per
// bilinear tap brings both and one store writes both (docs/design/inside-the-kernel.md).
constexpr VkFormat kPackedHistoryFormat = VK_FORMAT_R32_UINT;

struct ChannelHistory {
    GpuImage history[2], age[2], weight[2];  // [parity]: the frame writing parity p reads 1 - p
    // The deviation gate's (beta, sqrt(varsigma)) in fp16, R16G16_SFLOAT
    // (docs/CONVENTIONS.md, "The deviation gate"): written through
    // RRC_BINDING_WEIGHT_OUT (a gated channel has no weight), read through
    // RRC_BINDING_GATE as one R32_UINT word a texel (alias_view), so that one
    // gather brings a bilinear cell's four states.
    GpuImage gate[2];
    bool packed() const { return history[0].format == kPackedHistoryFormat; }
    ChannelHistory(VulkanDevice& dev, const ChannelConfig& config, uint32_t width, uint32_t height);
    void collect(std::vector<GpuImage*>& out);
    size_t bytes() const;
};

// Binds a channel's history for the frame that writes `parity`: it reads
// `read` at read_parity (its own history's other parity, or another view's
// latest) and writes `write` at `parity`.
void bind_history(DescriptorViews& views, uint32_t slot, const ChannelHistory& read, uint32_t read_parity, const ChannelHistory& write,
                  uint32_t parity);

class Placeholders {
public:
    explicit Placeholders(VulkanDevice& dev);
    // Every binding filled with a placeholder of a matching format: reads
    // and writes never share an image, so synchronization validation sees
    // no false hazard between them.
    DescriptorViews views() const;
    void collect(std::vector<GpuImage*>& out);

private:
    VkImageView read(VkFormat format) const;
    std::vector<GpuImage> read_, write_;  // write_: R32F (float writes), R16UI (ages), R32UI (object ids)
};

}  // namespace rrc
