#include "accumulate_pipeline.h"

#include "channel_options.h"
#include "error.h"
#include "rrc_module_copy_out_spv.h"
#include "rrc_module_fill_1_spv.h"
#include "rrc_module_fill_2_spv.h"
#include "rrc_module_fill_3_spv.h"
#include "rrc_module_fill_4_spv.h"
#include "rrc_module_frame_1_spv.h"
#include "rrc_module_frame_2_spv.h"
#include "rrc_module_frame_3_spv.h"
#include "rrc_module_frame_4_spv.h"
#include "rrc_module_list_spv.h"

#include <cstring>
#include <vector>

namespace rrc {
namespace {

// The specialization constants are one range, 0..RRC_SPEC_COUNT - 1
// (compute/rrc_kernel_interface.h); each channel slot has one feature word.
static_assert(RRC_MAX_CHANNELS <= RRC_SPEC_CHANNEL_SLOTS, "the kernel declares RRC_SPEC_CHANNEL_SLOTS channel slots");
static_assert(RRC_SPEC_MASK_IN_PLACE < RRC_SPEC_REFRESH_POLICY && RRC_SPEC_MAX_LIFETIME < RRC_SPEC_GROUP_SIZE_X &&
                  RRC_SPEC_GROUP_SIZE_Y < RRC_SPEC_CHANNEL_FEATURES &&
                  RRC_SPEC_CHANNEL_FEATURES + RRC_SPEC_CHANNEL_SLOTS == RRC_SPEC_COUNT_IO && RRC_SPEC_COUNT_IO + 1 == RRC_SPEC_COUNT,
              "the ids: dispatch, shading cache, workgroup size, channel feature words, the I/O counts, in one range");
static_assert(RRC_BINDING_STATS > RRC_BINDING_LAST && RRC_BINDING_QUADS == RRC_BINDING_STATS + 1 && RRC_BINDING_FILL_LIST == RRC_BINDING_QUADS + 1 &&
                  RRC_BINDING_VIEW == RRC_BINDING_FILL_LIST + 1 && RRC_BINDING_CHANNEL_PARAMS == RRC_BINDING_VIEW + 1,
              "the buffers follow every image binding, in a row");
constexpr uint32_t kBufferBindings = RRC_BINDING_CHANNEL_PARAMS - RRC_BINDING_STATS + 1;

// Each module (compute/rrc_module_*.comp) has its own bindings
// (compute/rrc_module_bindings.h); the per-pixel passes (FUSED, CLASSIFY,
// RESOLVE, RESOLVE_LISTED) are one module that the PASS constant
// specialises (docs/design/frame-plan.md).  Constants a module
// does not declare are ignored by vkCreateComputePipelines.
struct KernelModule {
    const uint32_t* code;
    size_t size;
    const Binding* bindings;
    uint32_t binding_count;
};
#define RRC_BINDING_ID(name) RRC_BINDING_##name,
constexpr Binding kFrameBindings[] = {RRC_MODULE_FRAME_BINDINGS(RRC_BINDING_ID)};
constexpr Binding kListBindings[] = {RRC_MODULE_LIST_BINDINGS(RRC_BINDING_ID)};
constexpr Binding kCopyOutBindings[] = {RRC_MODULE_COPY_OUT_BINDINGS(RRC_BINDING_ID)};
constexpr Binding kFillBindings[] = {RRC_MODULE_FILL_BINDINGS(RRC_BINDING_ID)};
#undef RRC_BINDING_ID
#define RRC_KERNEL_MODULE(code, bindings) KernelModule{code, sizeof(code), bindings, (uint32_t)(sizeof(bindings) / sizeof(Binding))}
// The per-channel modules (frame, fill) come once for each channel count, slots
// 1..RRC_MAX_CHANNELS (compute/CMakeLists.txt, RRC_SLOTS): `slots` picks the
// module with exactly the context's channels, so a driver compiles no code for
// slots it cannot use (docs/design/modules.md, "One module a channel count").  Every
// count has the same bindings.
static_assert(RRC_MAX_CHANNELS == 4, "one module a channel count: rrc_module_frame_1..4_spv, rrc_module_fill_1..4_spv");
KernelModule kernel_module(uint32_t module, uint32_t slots) {
    switch (module) {
        case RRC_MODULE_LIST: return RRC_KERNEL_MODULE(rrc_module_list_spv, kListBindings);
        case RRC_MODULE_COPY_OUT: return RRC_KERNEL_MODULE(rrc_module_copy_out_spv, kCopyOutBindings);
        case RRC_MODULE_FILL:
            return slots <= 1   ? RRC_KERNEL_MODULE(rrc_module_fill_1_spv, kFillBindings)
                   : slots == 2 ? RRC_KERNEL_MODULE(rrc_module_fill_2_spv, kFillBindings)
                   : slots == 3 ? RRC_KERNEL_MODULE(rrc_module_fill_3_spv, kFillBindings)
                                : RRC_KERNEL_MODULE(rrc_module_fill_4_spv, kFillBindings);
        default:
            return slots <= 1   ? RRC_KERNEL_MODULE(rrc_module_frame_1_spv, kFrameBindings)
                   : slots == 2 ? RRC_KERNEL_MODULE(rrc_module_frame_2_spv, kFrameBindings)
                   : slots == 3 ? RRC_KERNEL_MODULE(rrc_module_frame_3_spv, kFrameBindings)
                                : RRC_KERNEL_MODULE(rrc_module_frame_4_spv, kFrameBindings);
    }
}
#undef RRC_KERNEL_MODULE

bool is_buffer_binding(Binding b) { return b >= RRC_BINDING_STATS && b <= RRC_BINDING_CHANNEL_PARAMS; }
VkDescriptorType descriptor_type(Binding b) {
    return b == RRC_BINDING_CHANNEL_PARAMS ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
           : is_buffer_binding(b)    ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
           : is_sampled_binding(b) ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                   : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}
uint32_t descriptor_count(Binding b) { return is_buffer_binding(b) ? 1 : binding_count(b); }

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

AccumulatePipeline::AccumulatePipeline(VulkanDevice& dev, const ContextConfig& c, bool interop, uint32_t sets, VkPipelineCache cache)
    : dev_(dev), config_(c), interop_(interop), cache_(cache) {
    auto& vk = dev.vk;
    try {
        VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
        sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        VulkanDevice::check(vk.vkCreateSampler(dev.device, &sci, dev.allocator, &sampler_), "vkCreateSampler");
        const VkSampler immutable[RRC_MAX_CHANNELS] = {sampler_, sampler_, sampler_, sampler_};
        // Each module's layout from its list; the pool holds `sets` of each.
        uint32_t storage = 0, sampled = 0, buffers = 0, uniforms = 0;
        for (uint32_t module = 0; module < RRC_MODULE_COUNT; ++module) {
            const KernelModule m = kernel_module(module, RRC_MAX_CHANNELS);  // the bindings: every count's
            std::vector<VkDescriptorSetLayoutBinding> bindings;
            for (uint32_t i = 0; i < m.binding_count; ++i) {
                const Binding b = m.bindings[i];
                const VkDescriptorType type = descriptor_type(b);
                bindings.push_back({b, type, descriptor_count(b), VK_SHADER_STAGE_COMPUTE_BIT,
                                    type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER ? immutable : nullptr});
                (type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER   ? uniforms
                 : type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER ? buffers
                 : type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE  ? storage
                                                             : sampled) += descriptor_count(b);
            }
            VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
            lci.bindingCount = (uint32_t)bindings.size();
            lci.pBindings = bindings.data();
            VulkanDevice::check(vk.vkCreateDescriptorSetLayout(dev.device, &lci, dev.allocator, &set_layouts_[module]),
                                "vkCreateDescriptorSetLayout");

            VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(FramePushConstants)};
            VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
            pli.setLayoutCount = 1;
            pli.pSetLayouts = &set_layouts_[module];
            pli.pushConstantRangeCount = 1;
            pli.pPushConstantRanges = &range;
            VulkanDevice::check(vk.vkCreatePipelineLayout(dev.device, &pli, dev.allocator, &layouts_[module]), "vkCreatePipelineLayout");
        }

        VkDescriptorPoolSize sizes[4] = {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, sets * storage},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, sets * sampled},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, sets * buffers},
                                         {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, sets * uniforms}};
        VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpi.maxSets = sets * RRC_MODULE_COUNT;
        dpi.poolSizeCount = 4;
        dpi.pPoolSizes = sizes;
        VulkanDevice::check(vk.vkCreateDescriptorPool(dev.device, &dpi, dev.allocator, &pool_), "vkCreateDescriptorPool");
        // The channels' parameters, written once: host-visible and coherent, so the first
        // submission that reads them sees them (docs/design/adding-an-option.md).
        params_ = HostBuffer(dev, sizeof(KernelParamBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        KernelParamBlock block{};
        for (size_t s = 0; s < c.channels.size(); ++s) block.slot[s] = kernel_channel_params(c.channels[s]);
        std::memcpy(params_.data, &block, sizeof block);
    } catch (...) {
        release();  // the destructor does not run for a constructor that throws
        throw;
    }
}

VkPipeline AccumulatePipeline::pipeline(const KernelVariant& variant) {
    auto found = pipelines_.find(variant.key());
    if (found != pipelines_.end()) return found->second;
    auto& vk = dev_.vk;
    VulkanDevice& dev = dev_;
    const ContextConfig& c = config_;
    VkShaderModuleCreateInfo smi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    const KernelModule code = kernel_module(module_of(variant.pass), (uint32_t)c.channels.size());
    smi.codeSize = code.size;
    smi.pCode = code.code;
    VkShaderModule module = VK_NULL_HANDLE;
    VulkanDevice::check(vk.vkCreateShaderModule(dev.device, &smi, dev.allocator, &module), "vkCreateShaderModule");

    SpecBuilder spec;
    spec.add(RRC_SPEC_SOURCE, c.reprojection);
    spec.add(RRC_SPEC_DEPTH_MODE, c.depth_mode);
    spec.add(RRC_SPEC_EPS_KIND, (uint32_t)c.epsilon_kind);
    spec.add(RRC_SPEC_HAS_NOCACHE, c.use_nocache ? 1u : 0u);
    spec.add(RRC_SPEC_CHANNEL_COUNT, (uint32_t)c.channels.size());
    spec.add(RRC_SPEC_INTEROP, interop_ ? 1u : 0u);
    spec.add(RRC_SPEC_STATS, variant.stats ? 1u : 0u);
    spec.add(RRC_SPEC_COUNT_IO, variant.count_io ? 1u : 0u);
    spec.add(RRC_SPEC_HOST_AGE_MASK, variant.host_age_mask);
    spec.add(RRC_SPEC_ADAPTIVE, c.adaptive ? 1u : 0u);
    spec.add(RRC_SPEC_OBJECT_ID, c.use_object_id ? 1u : 0u);
    spec.add(RRC_SPEC_STORAGE_INPUTS, variant.storage_inputs ? 1u : 0u);
    spec.add(RRC_SPEC_PASS, variant.pass);
    spec.add(RRC_SPEC_HOST_OUT_MASK, variant.host_out_mask);
    spec.add(RRC_SPEC_COPY_MASK, variant.copy_mask ? 1u : 0u);
    spec.add(RRC_SPEC_MASK_IN_PLACE, variant.mask_in_place ? 1u : 0u);
    spec.add(RRC_SPEC_REFRESH_POLICY, c.refresh_policy);
    spec.add(RRC_SPEC_REFRESH_PERIOD, c.refresh_period);
    spec.add(RRC_SPEC_REFRESH_TILES_X, c.refresh_tiles[0]);
    spec.add(RRC_SPEC_REFRESH_TILES_Y, c.refresh_tiles[1]);
    spec.add(RRC_SPEC_MAX_LIFETIME, c.max_lifetime);
    spec.add(RRC_SPEC_GROUP_SIZE_X, kGroupX);
    spec.add(RRC_SPEC_GROUP_SIZE_Y, kGroupY);
    // Each slot's feature word (its parameters are in params_, written at creation).
    for (uint32_t slot = 0; slot < c.channels.size(); ++slot) spec.add(RRC_SPEC_CHANNEL_FEATURES + slot, channel_feature_word(c.channels[slot]));
    VkSpecializationInfo si{(uint32_t)spec.entries.size(), spec.entries.data(), spec.data.size() * 4, spec.data.data()};
    VkComputePipelineCreateInfo pci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pci.stage.module = module;
    pci.stage.pName = "main";
    pci.stage.pSpecializationInfo = &si;
    pci.layout = layouts_[module_of(variant.pass)];
    VkPipeline created = VK_NULL_HANDLE;
    VkResult r = vk.vkCreateComputePipelines(dev.device, cache_, 1, &pci, dev.allocator, &created);
    vk.vkDestroyShaderModule(dev.device, module, dev.allocator);
    VulkanDevice::check(r, "vkCreateComputePipelines");
    pipelines_[variant.key()] = created;
    return created;
}

AccumulatePipeline::~AccumulatePipeline() { release(); }

void AccumulatePipeline::release() {
    auto& vk = dev_.vk;
    if (pool_) vk.vkDestroyDescriptorPool(dev_.device, pool_, dev_.allocator);
    for (auto& p : pipelines_) vk.vkDestroyPipeline(dev_.device, p.second, dev_.allocator);
    pipelines_.clear();
    for (uint32_t module = 0; module < RRC_MODULE_COUNT; ++module) {
        if (layouts_[module]) vk.vkDestroyPipelineLayout(dev_.device, layouts_[module], dev_.allocator);
        if (set_layouts_[module]) vk.vkDestroyDescriptorSetLayout(dev_.device, set_layouts_[module], dev_.allocator);
        layouts_[module] = VK_NULL_HANDLE;
        set_layouts_[module] = VK_NULL_HANDLE;
    }
    if (sampler_) vk.vkDestroySampler(dev_.device, sampler_, dev_.allocator);
    sampler_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
}

DescriptorSets AccumulatePipeline::allocate_set() {
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = RRC_MODULE_COUNT;
    ai.pSetLayouts = set_layouts_;
    DescriptorSets sets;
    VulkanDevice::check(dev_.vk.vkAllocateDescriptorSets(dev_.device, &ai, sets.module), "vkAllocateDescriptorSets");
    return sets;
}

void AccumulatePipeline::write_set(const DescriptorSets& sets, const DescriptorViews& v) const {
    VkDescriptorImageInfo infos[RRC_MODULE_COUNT][kBindingCount][RRC_MAX_CHANNELS];
    VkDescriptorBufferInfo buffers[RRC_MODULE_COUNT][kBufferBindings];
    std::vector<VkWriteDescriptorSet> writes;
    for (uint32_t module = 0; module < RRC_MODULE_COUNT; ++module) {
        const KernelModule m = kernel_module(module, RRC_MAX_CHANNELS);  // the bindings: every count's
        for (uint32_t i = 0; i < m.binding_count; ++i) {
            const Binding b = m.bindings[i];
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = sets.module[module];
            w.dstBinding = b;
            w.descriptorCount = descriptor_count(b);
            w.descriptorType = descriptor_type(b);
            if (is_buffer_binding(b)) {
                VkDescriptorBufferInfo& info = buffers[module][b - RRC_BINDING_STATS];
                if (b == RRC_BINDING_STATS) {
                    if (!v.stats) fail(RRC_ERROR_UNSUPPORTED, "internal: the stats binding has no buffer");
                    info = {v.stats, v.stats_offset, v.stats_range};
                } else if (b == RRC_BINDING_QUADS) {
                    if (!v.quads) fail(RRC_ERROR_UNSUPPORTED, "internal: the quad list binding has no buffer");
                    info = {v.quads, v.quads_offset, v.quads_range};
                } else if (b == RRC_BINDING_FILL_LIST) {
                    if (!v.fill_list) fail(RRC_ERROR_UNSUPPORTED, "internal: the fill list binding has no buffer");
                    info = {v.fill_list, 0, VK_WHOLE_SIZE};
                } else if (b == RRC_BINDING_VIEW) {
                    if (!v.view_buffer) fail(RRC_ERROR_UNSUPPORTED, "internal: the view binding has no buffer");
                    info = {v.view_buffer, 0, RRC_VIEW_BUFFER_FLOATS * sizeof(float)};
                } else {
                    info = {params_.buffer, 0, sizeof(KernelParamBlock)};
                }
                w.pBufferInfo = &info;
            } else {
                for (uint32_t s = 0; s < binding_count(b); ++s) {
                    if (!v.view[b][s]) fail(RRC_ERROR_UNSUPPORTED, "internal: binding %u slot %u has no view", b, s);
                    VkImageLayout layout = v.layout[b][s] ? v.layout[b][s] : VK_IMAGE_LAYOUT_GENERAL;
                    infos[module][b][s] = {VK_NULL_HANDLE, v.view[b][s], layout};
                }
                w.pImageInfo = infos[module][b];
            }
            writes.push_back(w);
        }
    }
    dev_.vk.vkUpdateDescriptorSets(dev_.device, (uint32_t)writes.size(), writes.data(), 0, nullptr);
}

void AccumulatePipeline::bind(VkCommandBuffer cmd, const DescriptorSets& sets, const FramePushConstants& pc, const KernelVariant& variant) {
    auto& vk = dev_.vk;
    const uint32_t module = module_of(variant.pass);
    vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline(variant));
    vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layouts_[module], 0, 1, &sets.module[module], 0, nullptr);
    vk.vkCmdPushConstants(cmd, layouts_[module], VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, &pc);
}

void AccumulatePipeline::record(VkCommandBuffer cmd, const DescriptorSets& sets, const FramePushConstants& pc, uint32_t width, uint32_t height,
                                const KernelVariant& variant) {
    bind(cmd, sets, pc, variant);
    // Round up; the kernel bounds-checks.  The list runs one invocation a 2x2 quad.
    if (variant.pass == RRC_PASS_LIST) width = (width + 1) / 2, height = (height + 1) / 2;
    dev_.vk.vkCmdDispatch(cmd, (width + kGroupX - 1) / kGroupX, (height + kGroupY - 1) / kGroupY, 1);
}

void AccumulatePipeline::record_indirect(VkCommandBuffer cmd, const DescriptorSets& sets, const FramePushConstants& pc,
                                         const KernelVariant& variant, VkBuffer buffer, VkDeviceSize offset) {
    bind(cmd, sets, pc, variant);
    dev_.vk.vkCmdDispatchIndirect(cmd, buffer, offset);
}

}  // namespace rrc
