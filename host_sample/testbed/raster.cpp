#include "raster.h"

#include "rrc_sample_gbuffer_frag.h"
#include "rrc_sample_gbuffer_vert.h"
#include "rrc_sample_shadow_vert.h"

#include <cstring>
#include <stdexcept>

namespace rrc_sample {
namespace {

// Render passes synchronise with whatever touched their attachments before
// (compute reads and writes, transfers of the readback, earlier passes) and
// make their results visible to compute, fragment and transfer reads after.
std::vector<VkSubpassDependency> external_dependencies() {
    const VkPipelineStageFlags attachment_stages = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                                                   VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubpassDependency in{};
    in.srcSubpass = VK_SUBPASS_EXTERNAL;
    in.dstSubpass = 0;
    in.srcStageMask =
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | attachment_stages;
    in.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                       VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    in.dstStageMask = attachment_stages;
    in.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                       VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    VkSubpassDependency out{};
    out.srcSubpass = 0;
    out.dstSubpass = VK_SUBPASS_EXTERNAL;
    out.srcStageMask = attachment_stages;
    out.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    out.dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    out.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    return {in, out};
}

struct PipelineDesc {
    VkRenderPass pass;
    VkPipelineLayout layout;
    const uint32_t* vert;
    size_t vert_bytes;
    const uint32_t* frag = nullptr;
    size_t frag_bytes = 0;
    uint32_t colour_attachments = 0;
    VkCompareOp depth_compare;
    bool normals = true;  // the vertex shader reads location 1
};

VkPipeline make_pipeline(Gpu& gpu, const PipelineDesc& d) {
    VkShaderModule vs = gpu.create_shader(d.vert, d.vert_bytes);
    VkShaderModule fs = d.frag ? gpu.create_shader(d.frag, d.frag_bytes) : VK_NULL_HANDLE;
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";

    VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attrs[2] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                                                  {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)}};
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = d.normals ? 2 : 1;
    vi.pVertexAttributeDescriptions = attrs;
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;  // closed meshes; no winding assumptions under the y flip
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = d.depth_compare;
    std::vector<VkPipelineColorBlendAttachmentState> blend(d.colour_attachments);
    for (auto& b : blend) b.colorWriteMask = 0xF;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = d.colour_attachments;
    cb.pAttachments = blend.data();
    VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dy.dynamicStateCount = 2;
    dy.pDynamicStates = dyn;

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.stageCount = d.frag ? 2 : 1;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dy;
    ci.layout = d.layout;
    ci.renderPass = d.pass;
    VkPipeline p;
    VkResult r = vkCreateGraphicsPipelines(gpu.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p);
    vkDestroyShaderModule(gpu.device, vs, nullptr);
    if (fs) vkDestroyShaderModule(gpu.device, fs, nullptr);
    vk_check(r, "vkCreateGraphicsPipelines");
    return p;
}

void set_viewport(VkCommandBuffer cmd, uint32_t w, uint32_t h) {
    VkViewport v{0.0f, 0.0f, (float)w, (float)h, 0.0f, 1.0f};
    VkRect2D s{{0, 0}, {w, h}};
    vkCmdSetViewport(cmd, 0, 1, &v);
    vkCmdSetScissor(cmd, 0, 1, &s);
}

// Every attachment is cleared, stored, and left for compute and fragment
// sampling (what rrc and the compute passes read).
VkAttachmentDescription cleared_attachment(VkFormat format) {
    return VkAttachmentDescription{0,
                                   format,
                                   VK_SAMPLE_COUNT_1_BIT,
                                   VK_ATTACHMENT_LOAD_OP_CLEAR,
                                   VK_ATTACHMENT_STORE_OP_STORE,
                                   VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                   VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                   VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

// One subpass over `attachments`, synchronised by external_dependencies().
VkRenderPass make_render_pass(Gpu& gpu, const std::vector<VkAttachmentDescription>& attachments, const VkSubpassDescription& sub) {
    std::vector<VkSubpassDependency> deps = external_dependencies();
    VkRenderPassCreateInfo rci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rci.attachmentCount = (uint32_t)attachments.size();
    rci.pAttachments = attachments.data();
    rci.subpassCount = 1;
    rci.pSubpasses = &sub;
    rci.dependencyCount = (uint32_t)deps.size();
    rci.pDependencies = deps.data();
    VkRenderPass pass = VK_NULL_HANDLE;
    vk_check(vkCreateRenderPass(gpu.device, &rci, nullptr, &pass), "vkCreateRenderPass");
    return pass;
}

// The scene's descriptor set and `push_bytes` of vertex push constants.
VkPipelineLayout scene_pipeline_layout(Gpu& gpu, const GpuScene& scene, uint32_t push_bytes) {
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, push_bytes};
    VkDescriptorSetLayout sl = scene.set_layout();
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &sl;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    vk_check(vkCreatePipelineLayout(gpu.device, &plci, nullptr, &layout), "vkCreatePipelineLayout");
    return layout;
}

}  // namespace

// ---- GpuScene ----------------------------------------------------------------

GpuScene::GpuScene(Gpu& gpu, const Scene& scene) : gpu_(gpu) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    for (const MeshData& m : scene.meshes) {
        meshes_.push_back({(uint32_t)indices.size(), (uint32_t)m.indices.size(), (int32_t)vertices.size()});
        vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
        indices.insert(indices.end(), m.indices.begin(), m.indices.end());
    }
    for (const SceneObject& o : scene.objects) object_mesh_.push_back(o.mesh);
    // Small and written once: host-visible memory is good enough on every device.
    vertices_ = gpu.create_buffer(vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true, "vertices");
    indices_ = gpu.create_buffer(indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, true, "indices");
    std::memcpy(vertices_.mapped, vertices.data(), vertices.size() * sizeof(Vertex));
    std::memcpy(indices_.mapped, indices.data(), indices.size() * sizeof(uint32_t));
    ubo_ = gpu.create_buffer(sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, "frame uniforms");
    objects_ = gpu.create_buffer(scene.objects.size() * sizeof(GpuObject), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, "objects");

    VkDescriptorSetLayoutBinding b[2] = {};
    b[0] = {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    b[1] = {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = 2;
    lci.pBindings = b;
    vk_check(vkCreateDescriptorSetLayout(gpu.device, &lci, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pci.maxSets = 1;
    pci.poolSizeCount = 2;
    pci.pPoolSizes = sizes;
    vk_check(vkCreateDescriptorPool(gpu.device, &pci, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &set_layout_;
    vk_check(vkAllocateDescriptorSets(gpu.device, &ai, &set_), "vkAllocateDescriptorSets");
    VkDescriptorBufferInfo infos[2] = {{ubo_.buffer, 0, VK_WHOLE_SIZE}, {objects_.buffer, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    for (uint32_t i = 0; i < 2; ++i) {
        w[i].dstSet = set_;
        w[i].dstBinding = i;
        w[i].descriptorCount = 1;
        w[i].descriptorType = b[i].descriptorType;
        w[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(gpu.device, 2, w, 0, nullptr);
}

GpuScene::~GpuScene() {
    vkDestroyDescriptorPool(gpu_.device, pool_, nullptr);
    vkDestroyDescriptorSetLayout(gpu_.device, set_layout_, nullptr);
    for (Buffer* b : {&vertices_, &indices_, &ubo_, &objects_}) gpu_.destroy(*b);
}

void GpuScene::update(const FrameState& state) {
    std::memcpy(ubo_.mapped, &state.uniforms, sizeof(FrameUniforms));
    std::memcpy(objects_.mapped, state.objects.data(), state.objects.size() * sizeof(GpuObject));
}

void GpuScene::draw(VkCommandBuffer cmd, VkPipelineLayout layout, VkShaderStageFlags stages, uint32_t object_offset, const void* prefix,
                    uint32_t prefix_bytes) const {
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices_.buffer, &zero);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set_, 0, nullptr);
    if (prefix_bytes) vkCmdPushConstants(cmd, layout, stages, 0, prefix_bytes, prefix);
    for (uint32_t i = 0; i < object_mesh_.size(); ++i) {
        const Range& r = meshes_[object_mesh_[i]];
        vkCmdPushConstants(cmd, layout, stages, object_offset, sizeof(uint32_t), &i);
        vkCmdDrawIndexed(cmd, r.index_count, 1, r.first_index, r.vertex_offset, 0);
    }
}

// ---- ShadowPass ---------------------------------------------------------------

ShadowPass::ShadowPass(Gpu& gpu, const GpuScene& scene) : gpu_(gpu), scene_(scene) {
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.pDepthStencilAttachment = &ref;
    pass_ = make_render_pass(gpu, {cleared_attachment(VK_FORMAT_D32_SFLOAT)}, sub);
    layout_ = scene_pipeline_layout(gpu, scene, 64 + 4);
    PipelineDesc d{pass_, layout_, rrc_sample_shadow_vert, sizeof rrc_sample_shadow_vert};
    d.depth_compare = VK_COMPARE_OP_LESS;
    d.normals = false;
    pipeline_ = make_pipeline(gpu, d);
}

ShadowPass::~ShadowPass() {
    for (auto& [view, fb] : framebuffers_) vkDestroyFramebuffer(gpu_.device, fb, nullptr);
    vkDestroyPipeline(gpu_.device, pipeline_, nullptr);
    vkDestroyPipelineLayout(gpu_.device, layout_, nullptr);
    vkDestroyRenderPass(gpu_.device, pass_, nullptr);
}

void ShadowPass::record(VkCommandBuffer cmd, const Image& map, const glm::mat4& light_vp) {
    VkFramebuffer& fb = framebuffers_[map.view];
    if (!fb) {
        VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fci.renderPass = pass_;
        fci.attachmentCount = 1;
        fci.pAttachments = &map.view;
        fci.width = map.width;
        fci.height = map.height;
        fci.layers = 1;
        vk_check(vkCreateFramebuffer(gpu_.device, &fci, nullptr, &fb), "vkCreateFramebuffer");
    }
    VkClearValue clear{};
    clear.depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = pass_;
    bi.framebuffer = fb;
    bi.renderArea = {{0, 0}, {map.width, map.height}};
    bi.clearValueCount = 1;
    bi.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    set_viewport(cmd, map.width, map.height);
    scene_.draw(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 64, &light_vp, 64);
    vkCmdEndRenderPass(cmd);
}

// ---- GBufferPass --------------------------------------------------------------

GBufferPass::GBufferPass(Gpu& gpu, const GpuScene& scene, uint32_t w, uint32_t h) : gpu_(gpu), scene_(scene), width_(w), height_(h) {
    const VkImageUsageFlags colour = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    g_.depth = gpu.create_image(VK_FORMAT_D32_SFLOAT, w, h, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                "gbuffer depth");
    g_.prev_clip = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, colour, "gbuffer prev_clip");
    g_.motion = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, colour, "gbuffer motion");
    g_.normal = gpu.create_image(VK_FORMAT_R16G16B16A16_SFLOAT, w, h, colour, "gbuffer normal+material");
    g_.position = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, colour, "gbuffer position");
    g_.object_id = gpu.create_image(VK_FORMAT_R32_UINT, w, h, colour, "gbuffer object id");
    constexpr uint32_t kColours = 5;
    const Image* colours[kColours] = {&g_.prev_clip, &g_.motion, &g_.normal, &g_.position, &g_.object_id};

    std::vector<VkAttachmentDescription> a;
    for (const Image* c : colours) a.push_back(cleared_attachment(c->format));
    a.push_back(cleared_attachment(VK_FORMAT_D32_SFLOAT));
    VkAttachmentReference refs[kColours], dref{kColours, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    for (uint32_t i = 0; i < kColours; ++i) refs[i] = {i, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = kColours;
    sub.pColorAttachments = refs;
    sub.pDepthStencilAttachment = &dref;
    pass_ = make_render_pass(gpu, a, sub);

    VkImageView views[kColours + 1] = {g_.prev_clip.view, g_.motion.view,    g_.normal.view,
                                       g_.position.view,  g_.object_id.view, g_.depth.view};
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = pass_;
    fci.attachmentCount = kColours + 1;
    fci.pAttachments = views;
    fci.width = w;
    fci.height = h;
    fci.layers = 1;
    vk_check(vkCreateFramebuffer(gpu.device, &fci, nullptr, &framebuffer_), "vkCreateFramebuffer");

    layout_ = scene_pipeline_layout(gpu, scene, 4);
    // Blending stays off on every attachment (the object id's is an integer format).
    PipelineDesc d{
        pass_,   layout_, rrc_sample_gbuffer_vert, sizeof rrc_sample_gbuffer_vert, rrc_sample_gbuffer_frag, sizeof rrc_sample_gbuffer_frag,
        kColours};
    d.depth_compare = VK_COMPARE_OP_GREATER;  // reversed z
    pipeline_ = make_pipeline(gpu, d);
}

GBufferPass::~GBufferPass() {
    vkDestroyPipeline(gpu_.device, pipeline_, nullptr);
    vkDestroyPipelineLayout(gpu_.device, layout_, nullptr);
    vkDestroyFramebuffer(gpu_.device, framebuffer_, nullptr);
    vkDestroyRenderPass(gpu_.device, pass_, nullptr);
    for (Image* i : {&g_.depth, &g_.prev_clip, &g_.motion, &g_.normal, &g_.position, &g_.object_id}) gpu_.destroy(*i);
}

void GBufferPass::record(VkCommandBuffer cmd) {
    VkClearValue clears[6] = {};
    clears[2].color = {{0.0f, 0.0f, 1.0f, 0.0f}};  // material 0: background
    clears[4].color.uint32[0] = 0;                 // object id 0: background
    clears[5].depthStencil = {0.0f, 0};            // reversed z: far = 0
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = pass_;
    bi.framebuffer = framebuffer_;
    bi.renderArea = {{0, 0}, {width_, height_}};
    bi.clearValueCount = 6;
    bi.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    set_viewport(cmd, width_, height_);
    scene_.draw(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, nullptr, 0);
    vkCmdEndRenderPass(cmd);
}

}  // namespace rrc_sample
