// The rasterization side: the scene's geometry and per-frame buffers on the
// GPU, the depth-only shadow-map pass and the G-buffer pass.
#pragma once

#include "frame_state.h"
#include "gpu.h"
#include "scene.h"

#include <map>
#include <vector>

namespace rrc_sample {

/** Vertex/index buffers of every mesh, the frame uniform buffer, the object
 *  storage buffer, and the descriptor set the raster pipelines share. */
class GpuScene : NonCopyable {
public:
    GpuScene(Gpu& gpu, const Scene& scene);
    ~GpuScene();

    /** Copies the frame's uniforms and objects (the GPU must be idle on them). */
    void update(const FrameState& state);
    /** Binds buffers and draws every object; push constant at `object_offset` = the object's index. */
    void draw(VkCommandBuffer cmd, VkPipelineLayout layout, VkShaderStageFlags push_stages, uint32_t object_offset, const void* push_prefix,
              uint32_t prefix_bytes) const;

    VkBuffer uniforms() const { return ubo_.buffer; }
    VkBuffer objects() const { return objects_.buffer; }
    VkDescriptorSetLayout set_layout() const { return set_layout_; }
    VkDescriptorSet set() const { return set_; }

private:
    struct Range {
        uint32_t first_index, index_count;
        int32_t vertex_offset;
    };
    Gpu& gpu_;
    std::vector<Range> meshes_;
    std::vector<uint32_t> object_mesh_;
    Buffer vertices_, indices_, ubo_, objects_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

/** Depth-only pass into a D32 shadow map, left in SHADER_READ_ONLY_OPTIMAL. */
class ShadowPass : NonCopyable {
public:
    ShadowPass(Gpu& gpu, const GpuScene& scene);
    ~ShadowPass();
    /** Clears `map` and renders the scene with light_vp (standard depth, less). */
    void record(VkCommandBuffer cmd, const Image& map, const glm::mat4& light_vp);

private:
    Gpu& gpu_;
    const GpuScene& scene_;
    VkRenderPass pass_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    std::map<VkImageView, VkFramebuffer> framebuffers_;
};

/** The G-buffer images (left in SHADER_READ_ONLY_OPTIMAL by the pass). */
struct GBuffer {
    Image depth;      // D32_SFLOAT, reversed z (cleared to 0)
    Image prev_clip;  // RGBA32F: previous clip position (rrc PREV_CLIP)
    Image motion;     // RGBA32F: uv_prev - uv_cur, expected previous depth - depth (rrc MOTION / MOTION_DEPTH)
    Image normal;     // RGBA16F: world normal, material id in w
    Image position;   // RGBA32F: world position, object index + 1 in w (0: background)
    Image object_id;  // R32_UINT: object index + 1 (cleared to 0: background), rrc's object id
};

class GBufferPass : NonCopyable {
public:
    GBufferPass(Gpu& gpu, const GpuScene& scene, uint32_t width, uint32_t height);
    ~GBufferPass();
    void record(VkCommandBuffer cmd);
    const GBuffer& images() const { return g_; }

private:
    Gpu& gpu_;
    const GpuScene& scene_;
    uint32_t width_, height_;
    GBuffer g_;
    VkRenderPass pass_ = VK_NULL_HANDLE;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace rrc_sample
