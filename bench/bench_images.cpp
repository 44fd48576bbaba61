#include "bench_images.h"

#include <glm/gtc/packing.hpp>

#include <cstring>
#include <stdexcept>

namespace rrc_bench {
namespace {

constexpr VkImageUsageFlags kUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
constexpr VkImageLayout kGeneral = VK_IMAGE_LAYOUT_GENERAL;

Image make(VulkanBootstrap& vk, VkFormat format, const Config& c, const char* name) {
    return vk.create_image(format, c.width, c.height, kUsage, name);
}

template <typename T>
void upload(VulkanBootstrap& vk, const Image& img, const std::vector<T>& data) {
    if (data.size() * sizeof(T) != image_bytes(img)) throw std::logic_error("bench: upload size does not match the image");
    vk.upload(img, data.data(), data.size() * sizeof(T), kGeneral);
}

// Outputs start as zeros (and in GENERAL) so every readback is defined.
void zero(VulkanBootstrap& vk, const Image& img) { upload(vk, img, std::vector<unsigned char>(image_bytes(img), 0)); }

}  // namespace

VkFormat channel_format(const ChannelConfig& c) {
    const bool four = c.components == 4;
    if (c.precision == RRC_HISTORY_FP32) return four ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32_SFLOAT;
    return four ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R16_SFLOAT;
}

uint32_t texel_bytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UINT: return 1;
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_R16_UINT: return 2;
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_R32_UINT: return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT: return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        default: throw std::logic_error("bench: texel_bytes of an unexpected format");
    }
}

uint64_t image_bytes(const Image& img) { return img.image ? (uint64_t)img.width * img.height * texel_bytes(img.format) : 0; }

void upload_floats(VulkanBootstrap& vk, const Image& img, const std::vector<float>& data) {
    if (img.format == VK_FORMAT_R16_SFLOAT || img.format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        std::vector<uint16_t> half(data.size());
        for (size_t i = 0; i < data.size(); ++i) half[i] = glm::packHalf1x16(data[i]);
        upload(vk, img, half);
    } else {
        upload(vk, img, data);
    }
}

BenchImages create_images(VulkanBootstrap& vk, const Config& c, const SceneInputs& s) {
    BenchImages b;
    const size_t px = (size_t)c.width * c.height;
    for (int p = 0; p < 2; ++p) {
        PoseImages& pi = b.poses[p];
        const PoseFrame& f = s.poses[p];
        pi.depth = make(vk, VK_FORMAT_R32_SFLOAT, c, "bench depth");
        upload(vk, pi.depth, f.depth);
        if (c.source == RRC_REPROJECTION_PREV_CLIP || c.source == RRC_REPROJECTION_MOTION) {
            pi.reprojection = make(vk, c.source == RRC_REPROJECTION_MOTION ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT, c,
                                   "bench reprojection");
            upload(vk, pi.reprojection, f.reprojection);
        }
        if (c.source == RRC_REPROJECTION_MOTION_DEPTH) {  // rgb padded to rgba
            pi.reprojection = make(vk, VK_FORMAT_R32G32B32A32_SFLOAT, c, "bench motion+depth");
            std::vector<float> rgba(px * 4, 0.0f);
            for (size_t i = 0; i < px; ++i) std::memcpy(&rgba[i * 4], &f.reprojection[i * 3], 3 * sizeof(float));
            upload(vk, pi.reprojection, rgba);
        }
        if (c.object_id) {
            pi.object_id = make(vk, VK_FORMAT_R32_UINT, c, "bench object id");
            upload(vk, pi.object_id, f.object_id);
        }
    }
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        const VkFormat fmt = channel_format(c.channels[ch]);
        const bool four = c.channels[ch].components == 4;
        b.samples.push_back(make(vk, four ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32_SFLOAT, c, "bench samples"));
        upload_floats(vk, b.samples.back(), s.samples[ch]);
        b.history.push_back(make(vk, fmt, c, "bench roof history"));
        upload_floats(vk, b.history.back(), s.samples[ch]);
        b.values.push_back(make(vk, fmt, c, "bench values out"));
        zero(vk, b.values.back());
        b.age_in.push_back(make(vk, VK_FORMAT_R16_UINT, c, "bench roof age"));
        std::vector<uint16_t> age(px);
        for (size_t i = 0; i < px; ++i) age[i] = (uint16_t)(i * 7 % 256);
        upload(vk, b.age_in.back(), age);
        b.age_out.push_back(make(vk, VK_FORMAT_R16_UINT, c, "bench age out"));
        zero(vk, b.age_out.back());
        Image conf, w_in, w_out;
        if (c.channels[ch].confidence) {
            conf = make(vk, VK_FORMAT_R32_SFLOAT, c, "bench confidence");
            upload(vk, conf, s.confidence[ch]);
            w_in = make(vk, VK_FORMAT_R32_SFLOAT, c, "bench roof weight");
            upload(vk, w_in, s.confidence[ch]);
            w_out = make(vk, VK_FORMAT_R32_SFLOAT, c, "bench roof weight out");
            zero(vk, w_out);
        }
        b.confidence.push_back(conf);
        Image base;
        if (c.channels[ch].residual) {
            base = make(vk, four ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32_SFLOAT, c, "bench base");
            upload_floats(vk, base, s.base[ch]);
        }
        b.base.push_back(base);
        b.weight_in.push_back(w_in);
        b.weight_out.push_back(w_out);
    }
    if (c.nocache) {
        b.nocache = make(vk, VK_FORMAT_R8_UINT, c, "bench nocache");
        upload(vk, b.nocache, s.nocache);
    }
    b.mask = make(vk, VK_FORMAT_R8_UINT, c, "bench mask");
    zero(vk, b.mask);
    b.prev_depth = make(vk, VK_FORMAT_R32_SFLOAT, c, "bench roof previous depth");
    upload(vk, b.prev_depth, s.poses[1].depth);
    b.depth_copy = make(vk, VK_FORMAT_R32_SFLOAT, c, "bench roof depth copy");
    zero(vk, b.depth_copy);
    if (c.object_id) {
        b.prev_object_id = make(vk, VK_FORMAT_R32_UINT, c, "bench roof previous ids");
        upload(vk, b.prev_object_id, s.poses[1].object_id);
        b.object_id_copy = make(vk, VK_FORMAT_R32_UINT, c, "bench roof ids copy");
        zero(vk, b.object_id_copy);
    }
    return b;
}

void destroy_images(VulkanBootstrap& vk, BenchImages& b) {
    for (PoseImages& p : b.poses)
        for (Image* i : {&p.depth, &p.reprojection, &p.object_id}) vk.destroy(*i);
    for (auto* list : {&b.samples, &b.confidence, &b.base, &b.values, &b.age_out, &b.history, &b.age_in, &b.weight_in, &b.weight_out})
        for (Image& i : *list) vk.destroy(i);
    for (Image* i : {&b.nocache, &b.mask, &b.prev_depth, &b.prev_object_id, &b.depth_copy, &b.object_id_copy}) vk.destroy(*i);
    b = BenchImages();
}

}  // namespace rrc_bench
