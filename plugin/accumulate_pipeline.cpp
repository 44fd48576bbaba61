#include "accumulate_pipeline.h"

#include "error.h"
#include "rrc_accumulate_spv.h"

#include <cstring>
#include <vector>

namespace rrc {
namespace {

// Specialization constant ids (compute/rrc_reproject.glsl, rrc_accumulate.comp).
enum : uint32_t { kSource = 0, kDepthMode = 1, kEpsKind = 2, kHasNocache = 3, kChannelCount = 4, kGroupXId = 100, kGroupYId = 101 };
// Per-channel property k of slot c has id 16 + 4*k + c.
enum : uint32_t { kComponents = 0, kFp16, kBlend, kFilter, kConfidenceOn, kLambda, kAgeCap };
uint32_t channel_constant_id(uint32_t property, uint32_t slot) { return 16 + 4 * property + slot; }

struct SpecBuilder {
    std::vector<VkSpecializationMapEntry> entries;
    std::vector<uint32_t> data;  // every constant is 32 bits (bool, uint, float)
    void add(uint32_t id, uint32_t value) {
        entries.push_back({id, (uint32_t)(data.size() * 4), 4});
        data.push_back(value);
    }
    void add_float(uint32_t id, float value) {
        uint32_t bits;
        std::memcpy(&bits, &value, 4);
        add(id, bits);
    }
};

}  // namespace

AccumulatePipeline::AccumulatePipeline(VulkanDevice& dev, const ContextConfig& c) : dev_(dev) {
    auto& vk = dev.vk;
    try {
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        for (uint32_t b = kDepth; b <= kMask; ++b)
            bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
        for (uint32_t b = kFirstChannelBinding; b <= kLastBinding; ++b)
            bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, RRC_MAX_CHANNELS, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
        VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        lci.bindingCount = (uint32_t)bindings.size();
        lci.pBindings = bindings.data();
        VulkanDevice::check(vk.vkCreateDescriptorSetLayout(dev.device, &lci, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");

        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(FramePushConstants)};
        VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        pli.setLayoutCount = 1;
        pli.pSetLayouts = &set_layout_;
        pli.pushConstantRangeCount = 1;
        pli.pPushConstantRanges = &range;
        VulkanDevice::check(vk.vkCreatePipelineLayout(dev.device, &pli, nullptr, &layout_), "vkCreatePipelineLayout");

        VkShaderModuleCreateInfo smi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        smi.codeSize = sizeof(rrc_accumulate_spv);
        smi.pCode = rrc_accumulate_spv;
        VkShaderModule module = VK_NULL_HANDLE;
        VulkanDevice::check(vk.vkCreateShaderModule(dev.device, &smi, nullptr, &module), "vkCreateShaderModule");

        SpecBuilder spec;
        spec.add(kSource, c.reprojection);
        spec.add(kDepthMode, c.depth_mode);
        spec.add(kEpsKind, (uint32_t)c.epsilon_kind);
        spec.add(kHasNocache, c.use_nocache ? 1u : 0u);
        spec.add(kChannelCount, (uint32_t)c.channels.size());
        spec.add(kGroupXId, kGroupX);
        spec.add(kGroupYId, kGroupY);
        for (uint32_t slot = 0; slot < c.channels.size(); ++slot) {
            const ChannelConfig& ch = c.channels[slot];
            spec.add(channel_constant_id(kComponents, slot), ch.components);
            spec.add(channel_constant_id(kFp16, slot), ch.fp16 ? 1u : 0u);
            spec.add(channel_constant_id(kBlend, slot), ch.blend);
            spec.add(channel_constant_id(kFilter, slot), ch.filter);
            spec.add(channel_constant_id(kConfidenceOn, slot), ch.confidence ? 1u : 0u);
            spec.add_float(channel_constant_id(kLambda, slot), ch.lambda);
            spec.add(channel_constant_id(kAgeCap, slot), ch.age_cap);
        }
        VkSpecializationInfo si{(uint32_t)spec.entries.size(), spec.entries.data(), spec.data.size() * 4, spec.data.data()};
        VkComputePipelineCreateInfo pci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        pci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        pci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        pci.stage.module = module;
        pci.stage.pName = "main";
        pci.stage.pSpecializationInfo = &si;
        pci.layout = layout_;
        VkResult r = vk.vkCreateComputePipelines(dev.device, VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline_);
        vk.vkDestroyShaderModule(dev.device, module, nullptr);
        VulkanDevice::check(r, "vkCreateComputePipelines");

        // Two sets: the ping-pong parity of history and depth.
        uint32_t per_set = (kMask - kDepth + 1) + (kLastBinding - kFirstChannelBinding + 1) * RRC_MAX_CHANNELS;
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2 * per_set};
        VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpi.maxSets = 2;
        dpi.poolSizeCount = 1;
        dpi.pPoolSizes = &size;
        VulkanDevice::check(vk.vkCreateDescriptorPool(dev.device, &dpi, nullptr, &pool_), "vkCreateDescriptorPool");
    } catch (...) {
        release();  // the destructor does not run for a constructor that throws
        throw;
    }
}

AccumulatePipeline::~AccumulatePipeline() { release(); }

void AccumulatePipeline::release() {
    auto& vk = dev_.vk;
    if (pool_) vk.vkDestroyDescriptorPool(dev_.device, pool_, nullptr);
    if (pipeline_) vk.vkDestroyPipeline(dev_.device, pipeline_, nullptr);
    if (layout_) vk.vkDestroyPipelineLayout(dev_.device, layout_, nullptr);
    if (set_layout_) vk.vkDestroyDescriptorSetLayout(dev_.device, set_layout_, nullptr);
    pool_ = VK_NULL_HANDLE;
    pipeline_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

VkDescriptorSet AccumulatePipeline::allocate_set() {
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &set_layout_;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VulkanDevice::check(dev_.vk.vkAllocateDescriptorSets(dev_.device, &ai, &set), "vkAllocateDescriptorSets");
    return set;
}

void AccumulatePipeline::record(VkCommandBuffer cmd, VkDescriptorSet set, const FramePushConstants& pc, uint32_t width,
                                uint32_t height) const {
    auto& vk = dev_.vk;
    vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
    vk.vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, &pc);
    // Round up; the kernel bounds-checks.
    vk.vkCmdDispatch(cmd, (width + kGroupX - 1) / kGroupX, (height + kGroupY - 1) / kGroupY, 1);
}

}  // namespace rrc
