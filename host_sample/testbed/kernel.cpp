#include "kernel.h"

#include <map>
#include <utility>

namespace rrc_sample {

VkSampler create_nearest_sampler(Gpu& gpu) {
    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
    sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSampler s;
    vk_check(vkCreateSampler(gpu.device, &sci, nullptr, &s), "vkCreateSampler");
    return s;
}

ComputeKernel::ComputeKernel(Gpu& gpu, const char* name, const uint32_t* spirv, size_t bytes, std::vector<VkDescriptorType> bindings,
                             uint32_t push_bytes, uint32_t sets)
    : gpu_(&gpu), types_(std::move(bindings)), push_bytes_(push_bytes) {
    sampler_ = create_nearest_sampler(gpu);
    std::vector<VkDescriptorSetLayoutBinding> b(types_.size());
    std::map<VkDescriptorType, uint32_t> counts;
    for (uint32_t i = 0; i < types_.size(); ++i) {
        b[i].binding = i;
        b[i].descriptorType = types_[i];
        b[i].descriptorCount = 1;
        b[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        counts[types_[i]] += sets;
    }
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = (uint32_t)b.size();
    lci.pBindings = b.data();
    vk_check(vkCreateDescriptorSetLayout(gpu.device, &lci, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &set_layout_;
    plci.pushConstantRangeCount = push_bytes ? 1 : 0;
    plci.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(gpu.device, &plci, nullptr, &layout_), "vkCreatePipelineLayout");
    VkShaderModule module = gpu.create_shader(spirv, bytes);
    VkComputePipelineCreateInfo cci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    cci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cci.stage.module = module;
    cci.stage.pName = "main";
    cci.layout = layout_;
    VkResult r = vkCreateComputePipelines(gpu.device, VK_NULL_HANDLE, 1, &cci, nullptr, &pipeline_);
    vkDestroyShaderModule(gpu.device, module, nullptr);
    vk_check(r, "vkCreateComputePipelines");
    gpu.set_name(VK_OBJECT_TYPE_PIPELINE, (uint64_t)pipeline_, name);

    std::vector<VkDescriptorPoolSize> sizes;
    for (auto& [type, n] : counts) sizes.push_back({type, n});
    VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pci.maxSets = sets;
    pci.poolSizeCount = (uint32_t)sizes.size();
    pci.pPoolSizes = sizes.data();
    vk_check(vkCreateDescriptorPool(gpu.device, &pci, nullptr, &pool_), "vkCreateDescriptorPool");
    std::vector<VkDescriptorSetLayout> layouts(sets, set_layout_);
    sets_.resize(sets);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = sets;
    ai.pSetLayouts = layouts.data();
    vk_check(vkAllocateDescriptorSets(gpu.device, &ai, sets_.data()), "vkAllocateDescriptorSets");
}

ComputeKernel& ComputeKernel::operator=(ComputeKernel&& o) noexcept {
    if (this != &o) {
        release();
        gpu_ = std::exchange(o.gpu_, nullptr);
        types_ = std::move(o.types_);
        push_bytes_ = o.push_bytes_;
        sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
        set_layout_ = std::exchange(o.set_layout_, VK_NULL_HANDLE);
        layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
        pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
        pool_ = std::exchange(o.pool_, VK_NULL_HANDLE);
        sets_ = std::move(o.sets_);
    }
    return *this;
}

void ComputeKernel::release() {
    if (!gpu_) return;
    VkDevice d = gpu_->device;
    if (pool_) vkDestroyDescriptorPool(d, pool_, nullptr);
    if (pipeline_) vkDestroyPipeline(d, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(d, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(d, set_layout_, nullptr);
    if (sampler_) vkDestroySampler(d, sampler_, nullptr);
    gpu_ = nullptr;
    sets_.clear();
}

void ComputeKernel::write(uint32_t set, uint32_t binding, const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = sets_.at(set);
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = types_.at(binding);
    w.pBufferInfo = buffer;
    w.pImageInfo = image;
    vkUpdateDescriptorSets(gpu_->device, 1, &w, 0, nullptr);
}

void ComputeKernel::bind_buffer(uint32_t set, uint32_t binding, VkBuffer buffer) {
    const VkDescriptorBufferInfo info{buffer, 0, VK_WHOLE_SIZE};
    write(set, binding, &info, nullptr);
}

void ComputeKernel::bind_image(uint32_t set, uint32_t binding, VkImageView view, VkImageLayout layout) {
    const VkDescriptorImageInfo info{sampler_, view, layout};
    write(set, binding, nullptr, &info);
}

void ComputeKernel::dispatch(VkCommandBuffer cmd, uint32_t set, const void* push, uint32_t width, uint32_t height) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets_.at(set), 0, nullptr);
    if (push_bytes_) vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
    vkCmdDispatch(cmd, (width + 127) / 128, height, 1);
}

void ComputeKernel::dispatch_indirect(VkCommandBuffer cmd, uint32_t set, const void* push, VkBuffer buffer, VkDeviceSize offset) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets_.at(set), 0, nullptr);
    if (push_bytes_) vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
    vkCmdDispatchIndirect(cmd, buffer, offset);
}

}  // namespace rrc_sample
