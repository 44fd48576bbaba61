#include "channel_history.h"

#include "error.h"

namespace rrc {
namespace {

VkFormat history_format(const ChannelConfig& ch) {
    if (ch.fp16) return ch.components == 1 ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    return ch.components == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
}

}  // namespace

ChannelHistory::ChannelHistory(VulkanDevice& dev, const ChannelConfig& c, uint32_t w, uint32_t h) {
    for (int p = 0; p < 2; ++p) {
        history[p] = GpuImage(dev, history_format(c), w, h);
        age[p] = GpuImage(dev, VK_FORMAT_R16_UINT, w, h);
        if (c.confidence) weight[p] = GpuImage(dev, VK_FORMAT_R32_SFLOAT, w, h);
    }
}

void ChannelHistory::collect(std::vector<GpuImage*>& out) {
    for (int p = 0; p < 2; ++p) out.insert(out.end(), {&history[p], &age[p], &weight[p]});
}

size_t ChannelHistory::bytes() const { return 2 * (history[0].bytes() + age[0].bytes() + weight[0].bytes()); }

void bind_history(DescriptorViews& v, uint32_t s, const ChannelHistory& h, uint32_t p) {
    const uint32_t prev = 1 - p;
    const VkFormat f = h.history[prev].format;
    Binding read = f == VK_FORMAT_R16_SFLOAT            ? kHistR16f
                   : f == VK_FORMAT_R16G16B16A16_SFLOAT ? kHistRgba16f
                   : f == VK_FORMAT_R32_SFLOAT          ? kHistR32f
                                                        : kHistRgba32f;
    v.view[read][s] = h.history[prev].view;
    v.view[kAge][s] = h.age[prev].view;
    if (h.weight[prev].view) v.view[kWeight][s] = h.weight[prev].view;
    v.view[kHistOut][s] = h.history[p].view;
    v.view[kAgeOut][s] = h.age[p].view;
    if (h.weight[p].view) v.view[kWeightOut][s] = h.weight[p].view;
}

Placeholders::Placeholders(VulkanDevice& dev) {
    const VkFormat formats[] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT,       VK_FORMAT_R32G32B32A32_SFLOAT,
                                VK_FORMAT_R16_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8_UINT,
                                VK_FORMAT_R16_UINT};
    for (VkFormat f : formats) read_.emplace_back(dev, f, 1, 1);
    write_.emplace_back(dev, VK_FORMAT_R32_SFLOAT, 1, 1);
    write_.emplace_back(dev, VK_FORMAT_R16_UINT, 1, 1);
}

VkImageView Placeholders::read(VkFormat f) const {
    for (const GpuImage& img : read_)
        if (img.format == f) return img.view;
    fail(RRC_ERROR_UNSUPPORTED, "internal: no placeholder for VkFormat %d", (int)f);
}

DescriptorViews Placeholders::views() const {
    DescriptorViews v;
    const VkImageView wf = write_[0].view, wu = write_[1].view;
    v.view[kDepth][0] = v.view[kPrevDepth][0] = read(VK_FORMAT_R32_SFLOAT);
    v.view[kReproj][0] = read(VK_FORMAT_R32G32B32A32_SFLOAT);
    v.view[kMotion][0] = read(VK_FORMAT_R32G32_SFLOAT);
    v.view[kNocache][0] = read(VK_FORMAT_R8_UINT);
    // kMask is left empty: every context binds a mask image of its own.
    v.view[kHostDepth][0] = v.view[kHostReproj][0] = read(VK_FORMAT_R32_SFLOAT);
    v.view[kHostNocache][0] = read(VK_FORMAT_R8_UINT);
    v.view[kDepthOut][0] = wf;
    for (uint32_t s = 0; s < RRC_MAX_CHANNELS; ++s) {
        v.view[kSample1][s] = v.view[kConfidence][s] = v.view[kHistR32f][s] = v.view[kWeight][s] = read(VK_FORMAT_R32_SFLOAT);
        v.view[kSample4][s] = v.view[kHistRgba32f][s] = read(VK_FORMAT_R32G32B32A32_SFLOAT);
        v.view[kHistR16f][s] = read(VK_FORMAT_R16_SFLOAT);
        v.view[kHistRgba16f][s] = read(VK_FORMAT_R16G16B16A16_SFLOAT);
        v.view[kAge][s] = read(VK_FORMAT_R16_UINT);
        v.view[kHistOut][s] = v.view[kWeightOut][s] = v.view[kHostOut][s] = wf;
        v.view[kAgeOut][s] = v.view[kHostAgeOut][s] = wu;
        v.view[kHostSamples][s] = v.view[kHostConfidence][s] = read(VK_FORMAT_R32_SFLOAT);
    }
    return v;
}

void Placeholders::collect(std::vector<GpuImage*>& out) {
    for (auto& img : read_) out.push_back(&img);
    for (auto& img : write_) out.push_back(&img);
}

}  // namespace rrc
