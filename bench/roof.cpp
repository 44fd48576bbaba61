#include "roof.h"

#include "bench_roof_comp.h"  // the SPIR-V of roof.comp, compiled by glslang at build time

#include <cstring>
#include <stdexcept>

namespace rrc_bench {
namespace {

using rrc_host::vk_check;

// roof.comp's bindings: (binding, descriptor count).
enum Binding : uint32_t {
    kDepth = 0, kReproj4, kReproj2, kNocache, kObjectId, kPrevDepth, kPrevObjectId,
    kSamplesR32f, kSamplesRgba32f,
    kHistR16f, kHistRgba16f, kHistR32f, kHistRgba32f,
    kAge, kConfidence, kWeight, kValuesOut, kAgeOut, kWeightOut, kMask, kDepthCopy, kObjectIdCopy, kBindingCount
};
bool is_array(uint32_t b) { return b >= kSamplesR32f && b <= kWeightOut; }

// The format qualifier of each binding (what its placeholder must be).
VkFormat binding_format(uint32_t b) {
    switch (b) {
        case kReproj4: case kSamplesRgba32f: case kHistRgba32f: return VK_FORMAT_R32G32B32A32_SFLOAT;
        case kReproj2: return VK_FORMAT_R32G32_SFLOAT;
        case kNocache: case kMask: return VK_FORMAT_R8_UINT;
        case kObjectId: case kPrevObjectId: case kObjectIdCopy: return VK_FORMAT_R32_UINT;
        case kHistR16f: return VK_FORMAT_R16_SFLOAT;
        case kHistRgba16f: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case kAge: case kAgeOut: return VK_FORMAT_R16_UINT;
        default: return VK_FORMAT_R32_SFLOAT;
    }
}

uint32_t channel_kind(const ChannelConfig& c) { return (c.precision == RRC_HISTORY_FP32 ? 2u : 0u) + (c.components == 4 ? 1u : 0u); }

uint32_t reprojection_bytes(rrc_reprojection s) {
    if (s == RRC_REPROJECTION_CAMERA) return 0;
    return s == RRC_REPROJECTION_MOTION ? 8 : 16;  // MOTION_DEPTH's rgb travels in RGBA32F
}

template <typename T>
size_t count_differences(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
    if (a.size() != b.size()) return a.size() + b.size();
    size_t n = 0;
    for (size_t i = 0; i + sizeof(T) <= a.size(); i += sizeof(T)) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
    return n;
}

}  // namespace

RoofBytes roof_bytes_from_api(const Config& c) {
    // Bytes and images a pixel: the roof loads each image once and stores each output once.
    uint64_t r = 4 + reprojection_bytes(c.source) + 4;  // depth, reprojection data, previous depth (R32F)
    uint64_t w = 1 + 4;                                  // mask, depth copy (interop)
    uint32_t loads = c.source == RRC_REPROJECTION_CAMERA ? 2 : 3, stores = 2;
    for (const ChannelConfig& ch : c.channels) {
        const uint64_t value = (ch.precision == RRC_HISTORY_FP32 ? 4 : 2) * (uint64_t)ch.components;
        r += 4 * (uint64_t)ch.components + value + 2;  // samples (fp32, as passed), history at the channel's precision, age R16_UINT
        w += value + 2;          // values, age
        loads += 3, stores += 2;
        if (ch.confidence) {
            r += 4 + 4;  // confidence, previous weight (R32F)
            w += 4;      // weight
            loads += 2, stores += 1;
        }
    }
    if (c.nocache) r += 1, loads += 1;
    if (c.object_id) {
        r += 4 + 4;  // ids, previous ids (R32_UINT)
        w += 4;      // ids copy
        loads += 2, stores += 1;
    }
    const uint64_t px = (uint64_t)c.width * c.height;
    return RoofBytes{r * px, w * px, loads, stores};
}

Roof::Roof(VulkanBootstrap& vk, const Config& c, const BenchImages& img) : vk_(vk), config_(c), images_(img) {
    // Placeholders, one per binding format, for the descriptors this configuration does not use.
    std::vector<VkFormat> formats;
    for (uint32_t b = 0; b < kBindingCount; ++b) {
        const VkFormat f = binding_format(b);
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(vk.physical, f, &fp);
        if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
            throw std::runtime_error("roof: the device has no storage images of format " + std::to_string((int)f));
        bool seen = false;
        for (VkFormat g : formats) seen |= g == f;
        if (!seen) formats.push_back(f);
    }
    for (VkFormat f : formats) {
        placeholders_.push_back(vk.create_image(f, 1, 1, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "roof placeholder"));
        std::vector<unsigned char> zero(texel_bytes(f), 0);
        vk.upload(placeholders_.back(), zero.data(), zero.size(), VK_IMAGE_LAYOUT_GENERAL);
    }

    std::vector<VkDescriptorSetLayoutBinding> bindings;
    uint32_t descriptors = 0;
    for (uint32_t b = 0; b < kBindingCount; ++b) {
        const uint32_t n = is_array(b) ? 4 : 1;
        bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, n, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
        descriptors += n;
    }
    if (descriptors > vk.properties.limits.maxPerStageDescriptorStorageImages)
        throw std::runtime_error("roof: needs " + std::to_string(descriptors) + " storage images per stage");
    VkDescriptorSetLayoutCreateInfo sli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    sli.bindingCount = (uint32_t)bindings.size();
    sli.pBindings = bindings.data();
    vk_check(vkCreateDescriptorSetLayout(vk.device, &sli, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 3 * sizeof(uint32_t)};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &set_layout_;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &push;
    vk_check(vkCreatePipelineLayout(vk.device, &pli, nullptr, &layout_), "vkCreatePipelineLayout");

    // Specialisation: what this configuration reads and writes.
    uint32_t spec[9] = {};
    spec[0] = c.source == RRC_REPROJECTION_CAMERA ? 0u : c.source == RRC_REPROJECTION_MOTION ? 2u : 1u;
    spec[1] = (uint32_t)c.channels.size();
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        spec[2 + ch] = channel_kind(c.channels[ch]);
        if (c.channels[ch].confidence) spec[6] |= 1u << ch;
    }
    spec[7] = c.nocache ? 1u : 0u;  // SPIR-V booleans are specialised by a 32-bit value
    spec[8] = c.object_id ? 1u : 0u;
    VkSpecializationMapEntry entries[9];
    for (uint32_t i = 0; i < 9; ++i) entries[i] = {i, i * (uint32_t)sizeof(uint32_t), sizeof(uint32_t)};
    const VkSpecializationInfo si{9, entries, sizeof spec, spec};

    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = sizeof bench_roof_comp;
    mi.pCode = bench_roof_comp;
    VkShaderModule module;
    vk_check(vkCreateShaderModule(vk.device, &mi, nullptr, &module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", &si};
    ci.layout = layout_;
    const VkResult r = vkCreateComputePipelines(vk.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
    vkDestroyShaderModule(vk.device, module, nullptr);
    vk_check(r, "vkCreateComputePipelines (roof)");

    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2 * descriptors};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = 2;
    pi.poolSizeCount = 1;
    pi.pPoolSizes = &size;
    vk_check(vkCreateDescriptorPool(vk.device, &pi, nullptr, &pool_), "vkCreateDescriptorPool");
    const VkDescriptorSetLayout layouts[2] = {set_layout_, set_layout_};
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 2;
    ai.pSetLayouts = layouts;
    vk_check(vkAllocateDescriptorSets(vk.device, &ai, sets_), "vkAllocateDescriptorSets");

    // Each pose's set: the real image where the configuration uses the binding, else the placeholder.
    for (int pose = 0; pose < 2; ++pose) {
        const Image* real[kBindingCount][4] = {};
        const PoseImages& p = img.poses[pose];
        real[kDepth][0] = &p.depth;
        if (p.reprojection.image) real[p.reprojection.format == VK_FORMAT_R32G32_SFLOAT ? kReproj2 : kReproj4][0] = &p.reprojection;
        if (c.nocache) real[kNocache][0] = &img.nocache;
        if (c.object_id) {
            real[kObjectId][0] = &p.object_id;
            real[kPrevObjectId][0] = &img.prev_object_id;
            real[kObjectIdCopy][0] = &img.object_id_copy;
        }
        real[kPrevDepth][0] = &img.prev_depth;
        real[kMask][0] = &img.mask;
        real[kDepthCopy][0] = &img.depth_copy;
        for (size_t ch = 0; ch < c.channels.size(); ++ch) {
            const uint32_t kind = channel_kind(c.channels[ch]);
            real[kSamplesR32f + (kind & 1u)][ch] = &img.samples[ch];
            real[kHistR16f + kind][ch] = &img.history[ch];
            real[kAge][ch] = &img.age_in[ch];
            real[kValuesOut][ch] = &img.values[ch];
            real[kAgeOut][ch] = &img.age_out[ch];
            if (c.channels[ch].confidence) {
                real[kConfidence][ch] = &img.confidence[ch];
                real[kWeight][ch] = &img.weight_in[ch];
                real[kWeightOut][ch] = &img.weight_out[ch];
            }
        }
        std::vector<VkDescriptorImageInfo> infos;
        infos.reserve(descriptors);
        std::vector<VkWriteDescriptorSet> writes;
        RoofBytes bound;
        for (uint32_t b = 0; b < kBindingCount; ++b) {
            const uint32_t n = is_array(b) ? 4 : 1;
            const size_t first = infos.size();
            for (uint32_t e = 0; e < n; ++e) {
                const Image* use = real[b][e];
                if (use) {
                    const bool written = b >= kValuesOut;
                    (written ? bound.written : bound.read) += image_bytes(*use);
                } else {
                    for (const Image& ph : placeholders_)
                        if (ph.format == binding_format(b)) use = &ph;
                }
                infos.push_back({VK_NULL_HANDLE, use->view, VK_IMAGE_LAYOUT_GENERAL});
            }
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = sets_[pose];
            w.dstBinding = b;
            w.descriptorCount = n;
            w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            w.pImageInfo = &infos[first];
            writes.push_back(w);
        }
        vkUpdateDescriptorSets(vk.device, (uint32_t)writes.size(), writes.data(), 0, nullptr);
        bound_ = bound;
    }
}

Roof::~Roof() {
    if (pool_) vkDestroyDescriptorPool(vk_.device, pool_, nullptr);
    if (pipeline_) vkDestroyPipeline(vk_.device, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(vk_.device, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(vk_.device, set_layout_, nullptr);
    for (Image& i : placeholders_) vk_.destroy(i);
}

void Roof::record(VkCommandBuffer cmd, int pose) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets_[pose], 0, nullptr);
    const uint32_t push[3] = {config_.width, config_.height, 0xFFFFFFFFu};  // sentinel: see roof.comp
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, push);
    vkCmdDispatch(cmd, (config_.width + 127) / 128, config_.height, 1);
}

std::string Roof::check(int pose) const {
    std::string errors;
    auto compare = [&](const char* what, const Image& out, const Image& in) {
        const VkImageLayout g = VK_IMAGE_LAYOUT_GENERAL;
        const auto a = vk_.download(out, image_bytes(out), g), b = vk_.download(in, image_bytes(in), g);
        const size_t n = count_differences<unsigned char>(a, b);
        if (n) errors += std::string(errors.empty() ? "" : "; ") + what + ": " + std::to_string(n) + " bytes differ";
    };
    const PoseImages& p = images_.poses[pose];
    compare("depth copy", images_.depth_copy, p.depth);
    for (size_t ch = 0; ch < config_.channels.size(); ++ch) {
        compare("values", images_.values[ch], images_.history[ch]);
        compare("age", images_.age_out[ch], images_.age_in[ch]);
        if (config_.channels[ch].confidence) compare("weight", images_.weight_out[ch], images_.weight_in[ch]);
    }
    if (config_.object_id) compare("ids copy", images_.object_id_copy, p.object_id);
    if (config_.nocache) {
        compare("mask", images_.mask, images_.nocache);
    } else {
        const auto m = vk_.download(images_.mask, image_bytes(images_.mask), VK_IMAGE_LAYOUT_GENERAL);
        size_t n = 0;
        for (unsigned char v : m) n += v != 0;
        if (n) errors += std::string(errors.empty() ? "" : "; ") + "mask: " + std::to_string(n) + " bytes not 0";
    }
    return errors;
}

}  // namespace rrc_bench
