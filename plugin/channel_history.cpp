#include "channel_history.h"

#include "error.h"

namespace rrc {
namespace {

VkFormat history_format(const ChannelConfig& ch) {
    if (ch.fp16) return ch.components == 1 ? kPackedHistoryFormat : VK_FORMAT_R16G16B16A16_SFLOAT;
    return ch.components == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
}

}  // namespace

ChannelHistory::ChannelHistory(VulkanDevice& dev, const ChannelConfig& c, uint32_t w, uint32_t h) {
    for (int p = 0; p < 2; ++p) {
        history[p] = GpuImage(dev, history_format(c), w, h);
        if (!packed()) age[p] = GpuImage(dev, VK_FORMAT_R16_UINT, w, h);
        if (c.confidence) weight[p] = GpuImage(dev, VK_FORMAT_R32_SFLOAT, w, h);
        if (c.gate_kappa > 0.0f) gate[p] = GpuImage(dev, VK_FORMAT_R16G16_SFLOAT, w, h, VK_FORMAT_R32_UINT);
    }
}

void ChannelHistory::collect(std::vector<GpuImage*>& out) {
    for (int p = 0; p < 2; ++p) out.insert(out.end(), {&history[p], &age[p], &weight[p], &gate[p]});
}

size_t ChannelHistory::bytes() const { return 2 * (history[0].bytes() + age[0].bytes() + weight[0].bytes() + gate[0].bytes()); }

void bind_history(DescriptorViews& v, uint32_t s, const ChannelHistory& r, uint32_t prev, const ChannelHistory& h, uint32_t p) {
    if (h.packed()) {  // one R32_UINT word: value and age in, value and age out (AGE_OUT takes any uint format)
        v.view[RRC_BINDING_HIST_PACKED][s] = r.history[prev].view;
        v.view[RRC_BINDING_AGE_OUT][s] = h.history[p].view;
    } else {
        const VkFormat f = r.history[prev].format;
        Binding read = f == VK_FORMAT_R16G16B16A16_SFLOAT ? RRC_BINDING_HIST_RGBA16F
                       : f == VK_FORMAT_R32_SFLOAT        ? RRC_BINDING_HIST_R32F
                                                          : RRC_BINDING_HIST_RGBA32F;
        v.view[read][s] = r.history[prev].view;
        v.view[RRC_BINDING_AGE][s] = r.age[prev].view;
        v.view[RRC_BINDING_HIST_OUT][s] = h.history[p].view;
        v.view[RRC_BINDING_AGE_OUT][s] = h.age[p].view;
    }
    if (r.weight[prev].view) v.view[RRC_BINDING_WEIGHT][s] = r.weight[prev].view;
    if (h.weight[p].view) v.view[RRC_BINDING_WEIGHT_OUT][s] = h.weight[p].view;
    if (r.gate[prev].view) v.view[RRC_BINDING_GATE][s] = r.gate[prev].alias_view;
    if (h.gate[p].view) v.view[RRC_BINDING_WEIGHT_OUT][s] = h.gate[p].view;
}

Placeholders::Placeholders(VulkanDevice& dev) {
    const VkFormat formats[] = {VK_FORMAT_R32_SFLOAT,
                                VK_FORMAT_R32G32B32A32_SFLOAT,
                                VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_FORMAT_R8_UINT,
                                VK_FORMAT_R16_UINT,
                                VK_FORMAT_R32_UINT};
    for (VkFormat f : formats) read_.emplace_back(dev, f, 1, 1);
    write_.emplace_back(dev, VK_FORMAT_R32_SFLOAT, 1, 1);
    write_.emplace_back(dev, VK_FORMAT_R16_UINT, 1, 1);
    write_.emplace_back(dev, VK_FORMAT_R32_UINT, 1, 1);
}

VkImageView Placeholders::read(VkFormat f) const {
    for (const GpuImage& img : read_)
        if (img.format == f) return img.view;
    fail(RRC_ERROR_UNSUPPORTED, "internal: no placeholder for VkFormat %d", (int)f);
}

DescriptorViews Placeholders::views() const {
    DescriptorViews v;
    const VkImageView wf = write_[0].view, wu = write_[1].view;
    v.view[RRC_BINDING_DEPTH][0] = v.view[RRC_BINDING_PREV_DEPTH][0] = read(VK_FORMAT_R32_SFLOAT);
    v.view[RRC_BINDING_REPROJ][0] = read(VK_FORMAT_R32G32B32A32_SFLOAT);
    v.view[RRC_BINDING_NOCACHE][0] = read(VK_FORMAT_R8_UINT);
    // RRC_BINDING_MASK is left empty: every context binds a mask image of its own.
    v.view[RRC_BINDING_HOST_DEPTH][0] = v.view[RRC_BINDING_HOST_REPROJ][0] = read(VK_FORMAT_R32_SFLOAT);
    v.view[RRC_BINDING_HOST_NOCACHE][0] = read(VK_FORMAT_R8_UINT);
    v.view[RRC_BINDING_DEPTH_OUT][0] = wf;
    // Object ids: bound to real images only when the context uses them (the
    // kernel's code for them is compiled out otherwise).
    v.view[RRC_BINDING_PREV_OBJECT_ID][0] = v.view[RRC_BINDING_HOST_OBJECT_ID][0] = read(VK_FORMAT_R32_UINT);
    v.view[RRC_BINDING_OBJECT_ID][0] = write_[2].view;
    for (uint32_t s = 0; s < RRC_MAX_CHANNELS; ++s) {
        v.view[RRC_BINDING_SAMPLE1][s] = v.view[RRC_BINDING_CONFIDENCE][s] = v.view[RRC_BINDING_HIST_R32F][s] =
            v.view[RRC_BINDING_WEIGHT][s] = read(VK_FORMAT_R32_SFLOAT);
        v.view[RRC_BINDING_SAMPLE4][s] = v.view[RRC_BINDING_HIST_RGBA32F][s] = read(VK_FORMAT_R32G32B32A32_SFLOAT);
        v.view[RRC_BINDING_HIST_PACKED][s] = read(kPackedHistoryFormat);
        v.view[RRC_BINDING_HIST_RGBA16F][s] = read(VK_FORMAT_R16G16B16A16_SFLOAT);
        v.view[RRC_BINDING_AGE][s] = read(VK_FORMAT_R16_UINT);
        v.view[RRC_BINDING_HIST_OUT][s] = v.view[RRC_BINDING_WEIGHT_OUT][s] = v.view[RRC_BINDING_HOST_OUT][s] = wf;
        v.view[RRC_BINDING_AGE_OUT][s] = v.view[RRC_BINDING_HOST_AGE_OUT][s] = wu;
        v.view[RRC_BINDING_HOST_SAMPLES][s] = v.view[RRC_BINDING_HOST_CONFIDENCE][s] = v.view[RRC_BINDING_FALLBACK][s] =
            read(VK_FORMAT_R32_SFLOAT);
        v.view[RRC_BINDING_GATE][s] = read(VK_FORMAT_R32_UINT);  // the gate's state, one word a texel
    }
    return v;
}

void Placeholders::collect(std::vector<GpuImage*>& out) {
    for (auto& img : read_) out.push_back(&img);
    for (auto& img : write_) out.push_back(&img);
}

}  // namespace rrc
