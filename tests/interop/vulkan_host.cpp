#include "interop/vulkan_host.h"
#include "rrc_interop.h"

#include <stdexcept>

namespace rrc_test {
namespace {

uint32_t bytes_of(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UINT: return 1;
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_D16_UNORM: return 2;
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_D32_SFLOAT: return 4;
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        default: throw std::runtime_error("vulkan_host: unsupported format");
    }
}

rrc_host::BootstrapOptions test_host_options() {
    rrc_host::BootstrapOptions o;
    o.application = "rrc-interop-test";
    o.validation = true;  // the tests fail on any message
    o.features = rrc_host::rrc_features();  // what rrc needs (rrc_vulkan_get_requirements)
    return o;
}

}  // namespace

VulkanHost::VulkanHost() : VulkanBootstrap(test_host_options()) {}

HostImage VulkanHost::create_image(VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage) {
    HostImage img;
    img.texel_bytes = bytes_of(format);
    static_cast<rrc_host::Image&>(img) =
        VulkanBootstrap::create_image(format, w, h, usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    return img;
}

void VulkanHost::destroy(HostImage& img) {
    VulkanBootstrap::destroy(img);
    img = HostImage();
}

void VulkanHost::upload(HostImage& img, const void* data, size_t bytes, VkImageLayout layout) {
    VulkanBootstrap::upload(img, data, bytes, layout);
}

std::vector<unsigned char> VulkanHost::download(HostImage& img, VkImageLayout layout) {
    return VulkanBootstrap::download(img, (size_t)img.width * img.height * img.texel_bytes, layout);
}

}  // namespace rrc_test
