#include "gpu.h"
#include "rrc_interop.h"

namespace rrc_sample {

void compute_to_compute(VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

namespace {

rrc_host::BootstrapOptions bootstrap_options(const GpuOptions& o) {
    rrc_host::BootstrapOptions b;
    b.application = "rrc-sample";
    b.validation = o.validation;
    b.device_name = o.device_name;
    b.features = rrc_host::rrc_features();  // what rrc needs (rrc_vulkan_get_requirements)
    return b;
}

}  // namespace

Gpu::Gpu(const GpuOptions& options) : VulkanBootstrap(bootstrap_options(options)) {}

VkShaderModule Gpu::create_shader(const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m;
    vk_check(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
    return m;
}

void Gpu::init_storage_images(const std::vector<Image*>& images) {
    immediate([&](VkCommandBuffer cmd) {
        std::vector<VkImageMemoryBarrier> to_general;
        for (Image* img : images)
            to_general.push_back(
                rrc_host::layout_change(*img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT));
        rrc_host::image_barriers(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, to_general);
        VkClearColorValue zero{};
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        for (Image* img : images) vkCmdClearColorImage(cmd, img->image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    });
}

}  // namespace rrc_sample
