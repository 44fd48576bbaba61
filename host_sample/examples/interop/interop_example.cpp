// The interop path as an engine drives it (docs/guide/integration.md, "The interop path, step by step"): its own device (volk), a raster
// pass writing depth, previous clip position and a signal, then rrc recorded into the same command buffer; two frames, the camera pans.
// --cache: the shading cache ("The shading cache: shade only the misses"): classify, a miss shader dispatched indirectly on rrc's quad
// list, resolve.  Exits 1 on a wrong result or, with RRC_VALIDATION=1 (validation layer, synchronization validation), on any message.
#include <volk.h>

#include <rrc/rrc_vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "example_ground_frag.h"
#include "example_ground_vert.h"
#include "example_shade_misses_comp.h"

namespace {

constexpr uint32_t W = 32, H = 32;
VkPhysicalDevice physical;
VkDevice device;
std::vector<std::function<void()>> destroy;  // run in reverse before vkDestroyDevice
int messages = 0;

// A failed call ends the program; rrc's calls say why.  CREATE: `VkType name` from `info`, destroyed at the end.
#define VK(call) ((call) == VK_SUCCESS || (std::fprintf(stderr, "%s failed\n", #call), std::exit(1), false))
#define RRC(call) ((call) == RRC_SUCCESS || (std::fprintf(stderr, "%s: %s\n", #call, rrc_last_error()), std::exit(1), false))
#define CREATE(Type, name, info)                         \
    Vk##Type name;                                       \
    VK(vkCreate##Type(device, &(info), nullptr, &name)); \
    destroy.push_back([name] { vkDestroy##Type(device, name, nullptr); })

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    ++messages, std::fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

// Memory for an image or a buffer (the other is VK_NULL_HANDLE): the first type with `flags`, bound at offset 0.
VkDeviceMemory bind_memory(VkImage image, VkBuffer buffer, VkMemoryPropertyFlags flags) {
    VkMemoryRequirements need;
    image ? vkGetImageMemoryRequirements(device, image, &need) : vkGetBufferMemoryRequirements(device, buffer, &need);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical, &props);
    uint32_t i = 0;
    while (i < props.memoryTypeCount && (!(need.memoryTypeBits >> i & 1) || (props.memoryTypes[i].propertyFlags & flags) != flags)) ++i;
    if (i == props.memoryTypeCount) std::fprintf(stderr, "no suitable memory type\n"), std::exit(1);
    const VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, need.size, i};
    VkDeviceMemory memory;
    VK(vkAllocateMemory(device, &info, nullptr, &memory));
    destroy.push_back([memory] { vkFreeMemory(device, memory, nullptr); });
    VK(image ? vkBindImageMemory(device, image, memory, 0) : vkBindBufferMemory(device, buffer, memory, 0));
    return memory;
}

// How a pass uses an image; a barrier goes from one use to the next (synchronization2).
struct Use {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
};
const VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, kCopy = VK_PIPELINE_STAGE_2_COPY_BIT;
const Use kDiscard{kCompute | kCopy, 0, VK_IMAGE_LAYOUT_UNDEFINED};  // after the last frame's compute and copies; contents dropped
const Use kColour{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
const Use kStorage{kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL};                  // the miss shader's image
const Use kCopied{kCopy, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};  // rrc's outputs between frames

// An image as rrc is given it: in `use`'s layout when its commands start, and left in it; rrc's barriers move it to what its
// kernel needs and back, after any earlier stage's writes (docs/guide/integration.md, "What rrc checks and what it cannot").
rrc_vulkan_image make_image(VkFormat format, VkImageUsageFlags usage, Use use) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format, VkExtent3D{W, H, 1}, 1, 1};
    info.samples = VK_SAMPLE_COUNT_1_BIT, info.usage = usage;
    CREATE(Image, image, info);
    bind_memory(image, VK_NULL_HANDLE, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, image, VK_IMAGE_VIEW_TYPE_2D, format};
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    CREATE(ImageView, view, view_info);
    return {image, view, format, use.layout};
}

template <size_t N>
VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits which, const uint32_t (&code)[N]) {
    const VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, sizeof code, code};
    CREATE(ShaderModule, module, info);
    return {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, which, module, "main"};
}

// The raster pass: a strip, no vertex buffers, no depth test (one plane); reversed depth to a colour target, rrc reads .r ("Inputs").
VkPipeline ground_pipeline(VkPipelineLayout layout) {
    const VkPipelineShaderStageCreateInfo stages[2] = {stage(VK_SHADER_STAGE_VERTEX_BIT, example_ground_vert),
                                                       stage(VK_SHADER_STAGE_FRAGMENT_BIT, example_ground_frag)};
    const VkPipelineVertexInputStateCreateInfo vertices{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo strip{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    strip.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    const VkViewport viewport{0, 0, W, H, 0, 1};
    const VkRect2D scissor{VkOffset2D{0, 0}, VkExtent2D{W, H}};
    VkPipelineViewportStateCreateInfo view{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, nullptr, 0, 1, &viewport, 1, &scissor};
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.lineWidth = 1;
    VkPipelineMultisampleStateCreateInfo samples{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    samples.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendAttachmentState writes[3] = {};
    for (auto& w : writes) w.colorWriteMask = 0xF;  // no blending
    const VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO, nullptr, 0, 0, {}, 3, writes};
    const VkFormat colours[3] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32_SFLOAT};
    const VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO, nullptr, 0, 3, colours};
    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering, 0, 2, stages, &vertices, &strip};
    info.pViewportState = &view, info.pRasterizationState = &raster, info.pMultisampleState = &samples;
    info.pColorBlendState = &blend, info.layout = layout;
    VkPipeline pipeline;
    VK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    destroy.push_back([pipeline] { vkDestroyPipeline(device, pipeline, nullptr); });
    return pipeline;
}

VkImageMemoryBarrier2 transition(const rrc_vulkan_image& img, Use a, Use b) {
    VkImageMemoryBarrier2 r{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, nullptr, a.stage, a.access, b.stage, b.access, a.layout, b.layout};
    r.srcQueueFamilyIndex = r.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    r.image = img.image, r.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    return r;
}

void barrier(VkCommandBuffer cmd, std::initializer_list<VkImageMemoryBarrier2> images, const VkMemoryBarrier2* memory = nullptr) {
    VkDependencyInfo info{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, memory ? 1u : 0u, memory};
    info.imageMemoryBarrierCount = (uint32_t)images.size(), info.pImageMemoryBarriers = images.begin();
    vkCmdPipelineBarrier2(cmd, &info);
}

// Looking straight down from 2 units up, 90 degrees, panning along x; reversed depth: near and far swapped.
glm::mat4 view_proj(int t) {
    const glm::vec3 eye(1.4f * (float)t, 2.0f, 0.0f), down(0, -2, 0), up(0, 0, -1);
    return glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 100.0f, 0.1f) * glm::lookAtRH(eye, eye + down, up);
}

}  // namespace

int main(int argc, char** argv) {
    const bool cache = argc > 1 && std::strcmp(argv[1], "--cache") == 0;
    const bool validation = std::getenv("RRC_VALIDATION") && std::strcmp(std::getenv("RRC_VALIDATION"), "1") == 0;
    // With validation: the layer, synchronization validation, a messenger counting warnings and errors (chained into vkCreateInstance too).
    VK(volkInitialize());
    const VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "rrc interop example", 0, nullptr, 0, VK_API_VERSION_1_3};
    VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = 7, messenger_info.pfnUserCallback = on_message;  // 7: every type
    const VkValidationFeatureEnableEXT sync_validation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    const VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messenger_info, 1, &sync_validation};
    const char *layer = "VK_LAYER_KHRONOS_validation", *debug_utils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const VkInstanceCreateInfo instance_info{
        VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, validation ? &features : nullptr, 0, &app, validation, &layer, validation, &debug_utils};
    VkInstance instance;
    VK(vkCreateInstance(&instance_info, nullptr, &instance));
    volkLoadInstance(instance);
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    if (validation) VK(vkCreateDebugUtilsMessengerEXT(instance, &messenger_info, nullptr, &messenger));
    // The first device, family 0 (graphics + compute; an engine chooses), with the features rrc asks for.
    uint32_t count = 1, family = 0;
    vkEnumeratePhysicalDevices(instance, &count, &physical);
    const float priority = 1;
    const VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &priority};
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.synchronization2 = features13.dynamicRendering = VK_TRUE;
    rrc_vulkan_requirements needs{RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS, nullptr, sizeof needs};  // what rrc needs: Vulkan 1.1, features
    RRC(rrc_vulkan_get_requirements(&needs));
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13, needs.features};
    const char* extension = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;  // this program's, as are dynamic rendering, synchronization2
    const VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features2, 0, 1, &queue_info, 0, nullptr, 1, &extension};
    VK(vkCreateDevice(physical, &device_info, nullptr, &device));
    volkLoadDevice(device);
    VkQueue queue;
    vkGetDeviceQueue(device, family, 0, &queue);
    const VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, family};
    CREATE(CommandPool, pool, pool_info);
    // rrc on the engine's device (step 1); --cache: one REUSE channel, a pure shading cache.
    // The channel's settings from rrc's presets (docs/guide/): a shadow-like signal with no base to render, or the cache.
    rrc_channel_desc channel{RRC_STRUCT_TYPE_CHANNEL_DESC, nullptr, sizeof channel, "signal", 1, RRC_HISTORY_FP32};
    RRC(rrc_channel_preset(cache ? RRC_PRESET_SHADING_CACHE : RRC_PRESET_PCF_SHADOWS, 0, RRC_API_VERSION, &channel));
    rrc_context_desc desc{RRC_STRUCT_TYPE_CONTEXT_DESC, nullptr, sizeof desc, RRC_API_VERSION, W, H, RRC_DEPTH_MODE_REVERSED};
    desc.reprojection = RRC_REPROJECTION_PREV_CLIP, desc.channel_count = 1, desc.channels = &channel;
    if (cache) RRC(rrc_context_preset(RRC_PRESET_SHADING_CACHE, 0, RRC_API_VERSION, &desc));  // its refresh policy
    rrc_vulkan_device_desc host{RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC, nullptr, sizeof host, instance, physical, device, family};
    host.vulkan_api_version = VK_API_VERSION_1_3, host.get_instance_proc_addr = vkGetInstanceProcAddr;
    host.max_frames_in_flight = 1, host.debug_utils_enabled = validation;  // with validation, rrc labels its dispatches
    host.enabled_features = &features2.features;                          // what this device enabled: rrc checks its own
    rrc_context* ctx;
    RRC(rrc_vulkan_context_create(&desc, &host, &ctx));
    const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT, target = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | sampled,
                            result = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    // The render pass's targets, handed to rrc in the layout the pass left them in.
    const auto depth = make_image(VK_FORMAT_R32_SFLOAT, target, kColour), signal = make_image(VK_FORMAT_R32_SFLOAT, target, kColour);
    const auto clip = make_image(VK_FORMAT_R32G32B32A32_SFLOAT, target, kColour);
    const auto shaded = make_image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | sampled, kStorage);  // the miss shader's (--cache)
    const auto output = make_image(VK_FORMAT_R32_SFLOAT, result, kCopied), mask = make_image(VK_FORMAT_R8_UINT, result, kCopied);
    rrc_vulkan_channel_images images{RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES, nullptr, sizeof images, cache ? shaded : signal, {}, output};
    // One host-visible buffer: rrc's quad list, then the output and the mask copied back.
    const VkDeviceSize kOutput = (RRC_QUAD_LIST_BYTES(W, H) + 255) / 256 * 256;
    const VkDeviceSize kMask = kOutput + W * H * sizeof(float), bytes = kMask + W * H;
    const VkBufferUsageFlags usage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    const VkBufferCreateInfo buffer_info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, bytes, usage};
    CREATE(Buffer, buffer, buffer_info);
    const VkMemoryPropertyFlags host_visible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    char* mapped;
    VK(vkMapMemory(device, bind_memory(VK_NULL_HANDLE, buffer, host_visible), 0, bytes, 0, (void**)&mapped));
    // The miss shader's bindings (push descriptors): rrc's quad list and the image it shades.
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorType storage_buffer = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage_image = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    const VkDescriptorSetLayoutBinding bindings[2] = {{0, storage_buffer, 1, cs}, {1, storage_image, 1, cs}};
    const VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr,
                                                   VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR, 2, bindings};
    CREATE(DescriptorSetLayout, set_layout, set_info);
    const VkDescriptorBufferInfo list_at{buffer, 0, kOutput};
    const VkDescriptorImageInfo shaded_at{VK_NULL_HANDLE, shaded.view, kStorage.layout};
    const VkStructureType write = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    const VkWriteDescriptorSet writes[2] = {{write, nullptr, VK_NULL_HANDLE, 0, 0, 1, storage_buffer, nullptr, &list_at},
                                            {write, nullptr, VK_NULL_HANDLE, 1, 0, 1, storage_image, &shaded_at}};
    const VkPushConstantRange push{cs, 0, sizeof(float)};  // the value it shades
    const VkPipelineLayoutCreateInfo miss_layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1, &set_layout, 1, &push};
    CREATE(PipelineLayout, miss_layout, miss_layout_info);
    const VkComputePipelineCreateInfo miss_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, nullptr, 0,
                                                stage(VK_SHADER_STAGE_COMPUTE_BIT, example_shade_misses_comp), miss_layout};
    VkPipeline miss;
    VK(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &miss_info, nullptr, &miss));
    destroy.push_back([miss] { vkDestroyPipeline(device, miss, nullptr); });
    const VkPushConstantRange cameras{VK_SHADER_STAGE_VERTEX_BIT, 0, 2 * sizeof(glm::mat4)};  // now and the previous frame's
    const VkPipelineLayoutCreateInfo ground_layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 0, nullptr, 1, &cameras};
    CREATE(PipelineLayout, ground_layout, ground_layout_info);
    const VkPipeline ground = ground_pipeline(ground_layout);
    int failures = 0;
    float previous = 0;  // frame 0's value at every pixel: the history frame 1 reads
    for (int t = 0; t < 2; ++t) {
        const float value = cache ? 0.25f + 0.5f * (float)t : 1.0f + 2.0f * (float)t;  // ground.vert's signal; --cache: the miss shader's
        const VkCommandBufferAllocateInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                                   VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
        VkCommandBuffer cmd;  // one per frame, freed with the pool
        VK(vkAllocateCommandBuffers(device, &cmd_info, &cmd));
        const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        VK(vkBeginCommandBuffer(cmd, &begin));
        barrier(cmd, {transition(depth, kDiscard, kColour), transition(clip, kDiscard, kColour), transition(signal, kDiscard, kColour)});
        VkRenderingAttachmentInfo targets[3] = {{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, depth.view, kColour.layout},
                                                {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, clip.view, kColour.layout},
                                                {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, signal.view, kColour.layout}};
        for (auto& a : targets) a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR, a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        targets[2].clearValue.color.float32[0] = value;  // the background's signal; depth clears to 0 (reversed: far, the sky)
        const VkRenderingInfo pass{VK_STRUCTURE_TYPE_RENDERING_INFO, nullptr, 0, VkRect2D{{0, 0}, {W, H}}, 1, 0, 3, targets};
        vkCmdBeginRendering(cmd, &pass);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ground);
        const glm::mat4 camera[2] = {view_proj(t), view_proj(t > 0 ? t - 1 : 0)};  // now, and the previous frame's
        vkCmdPushConstants(cmd, ground_layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof camera, camera);
        vkCmdDraw(cmd, 4, 1, 0, (uint32_t)t);
        vkCmdEndRendering(cmd);
        // No barrier of the host's: rrc's own make the pass's writes visible and move each image between the layout it is
        // given and its final_layout (here the same).  On the first frame the outputs' contents are UNDEFINED: discarded.
        rrc_vulkan_frame_desc frame{RRC_STRUCT_TYPE_VULKAN_FRAME_DESC, nullptr, sizeof frame, cmd, (uint64_t)t};
        frame.depth = depth, frame.reprojection = clip, frame.mask = mask, frame.channel_count = 1, frame.channels = &images;
        images.output.layout = frame.mask.layout = t == 0 ? VK_IMAGE_LAYOUT_UNDEFINED : kCopied.layout;
        images.output.final_layout = frame.mask.final_layout = kCopied.layout;
        frame.split_outputs = 1;  // classify writes the hits, resolve the listed quads ("What each call writes")
        if (!cache) {
            RRC(rrc_vulkan_record_frame(ctx, &frame));
        } else {
            const rrc_vulkan_quad_list list{RRC_STRUCT_TYPE_VULKAN_QUAD_LIST, nullptr, sizeof list, buffer, 0};
            RRC(rrc_vulkan_record_classify(ctx, &frame, &list));  // ends with a barrier to the indirect read and the shader
            barrier(cmd, {transition(shaded, kDiscard, kStorage)});  // the miss shader's own image, for its writes
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, miss);
            vkCmdPushDescriptorSetKHR(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, miss_layout, 0, 2, writes);
            vkCmdPushConstants(cmd, miss_layout, cs, 0, sizeof value, &value);
            vkCmdDispatchIndirect(cmd, buffer, 4 * RRC_QUAD_LIST_DISPATCH);
            images.output.layout = frame.mask.layout = kCopied.layout;  // where classify left them
            RRC(rrc_vulkan_record_resolve(ctx, &frame));                 // its barriers make the miss shader's writes visible to it
        }
        // rrc's last barriers made its writes visible to any later stage: copy them out for the host.
        VkBufferImageCopy region{kOutput, 0, 0, VkImageSubresourceLayers{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {}, VkExtent3D{W, H, 1}};
        vkCmdCopyImageToBuffer(cmd, output.image, kCopied.layout, buffer, 1, &region);
        region.bufferOffset = kMask;
        vkCmdCopyImageToBuffer(cmd, mask.image, kCopied.layout, buffer, 1, &region);
        const VkAccessFlags2 written = VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;  // the copies, the list
        const VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, kCopy | kCompute, written, VK_PIPELINE_STAGE_2_HOST_BIT,
                                       VK_ACCESS_2_HOST_READ_BIT};
        barrier(cmd, {}, &to_host);
        VK(vkEndCommandBuffer(cmd));
        const VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd};
        VK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
        VK(vkQueueWaitIdle(queue));  // an engine waits for the frame's fence
        // --cache: a hit keeps frame 0's value, any other pixel (a refreshed one too) takes this frame's.  Otherwise the preset blends a hit's history
        // with this frame's sample, shows young pixels as a mean of their neighbours and may drop a history that changed this
        // much (docs/reference/presets.md): every value lies between frame 0's and this frame's.  A quad is listed iff a pixel
        // of it is not a hit ("Classify, the quad list and resolve").
        const float* out = (const float*)(mapped + kOutput);
        const uint8_t* bits = (const uint8_t*)(mapped + kMask);
        uint32_t hits = 0, background = 0, quads = 0, wrong = 0;
        for (uint32_t i = 0; i < W * H; ++i) {
            hits += bits[i] == RRC_MASK_HIT;
            background += bits[i] == RRC_MASK_BACKGROUND;
            wrong += bits[i] != 0 && bits[i] != RRC_MASK_HIT && bits[i] != RRC_MASK_BACKGROUND && bits[i] != RRC_MASK_REFRESHED;
            const float lo = t ? std::min(previous, value) : value, hi = t ? std::max(previous, value) : value;
            wrong += cache ? std::abs(out[i] - (bits[i] != RRC_MASK_HIT ? value : previous)) > 1e-6f
                           : !(out[i] >= lo - 1e-6f && out[i] <= hi + 1e-6f);
            const uint32_t q = 2 * (i / (W / 2)) * W + 2 * (i % (W / 2));  // top-left pixel of quad i of W * H / 4
            quads += i < W * H / 4 && (bits[q] & bits[q + 1] & bits[q + W] & bits[q + W + 1] & RRC_MASK_HIT) == 0;
        }
        const uint32_t misses = W * H - hits - background;
        std::printf("frame %d: %u hits, %u misses, %u background", t, hits, misses, background);
        const uint32_t listed = ((const uint32_t*)mapped)[RRC_QUAD_LIST_COUNT];  // the quads the miss shader shaded
        if (cache) std::printf(", %u of %u quads shaded", listed, W * H / 4);
        const bool seen = t == 0 ? hits == 0 : hits > 0 && misses > 0 && background > 0;  // frame 1 has all three
        const bool ok = wrong == 0 && seen && (!cache || listed == quads);
        std::printf(ok ? "\n" : ": WRONG (%u pixels)\n", wrong);
        failures += !ok;
        previous = value;
    }
    VK(vkDeviceWaitIdle(device));
    rrc_context_destroy(ctx);
    for (auto it = destroy.rbegin(); it != destroy.rend(); ++it) (*it)();
    vkDestroyDevice(device, nullptr);
    if (messenger) vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
    vkDestroyInstance(instance, nullptr);
    std::printf("%d frames wrong, %d validation messages\n", failures, messages);
    return failures == 0 && messages == 0 ? 0 : 1;
}
