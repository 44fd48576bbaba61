#include "cache_run.h"

#include "fenced_commands.h"
#include "frame_state.h"
#include "gpu.h"
#include "kernel.h"
#include "raster.h"
#include "rrc_cache_shade_full_comp.h"
#include "rrc_cache_shade_miss_comp.h"
#include "rrc_descs.h"
#include "rrc_interop.h"
#include "scene.h"
#include "spec_constant.h"

#include <rrc/rrc_vulkan.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>

namespace rrc_cache {

using rrc_sample::Gpu;
using rrc_sample::Image;
using rrc_sample::vk_check;

namespace {

constexpr VkImageLayout kRO = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kGeneral = VK_IMAGE_LAYOUT_GENERAL;

// The second eye: the camera moved `separation` to the left, looking the same way.
void second_eye(const rrc_sample::Scene& scene, const rrc_sample::RenderSettings& rs, int index, float separation,
                rrc_sample::FrameState& state, const glm::mat4& first_eye_vp) {
    const double t = (double)index / rs.fps;
    const rrc_sample::Camera c = scene.camera(t);
    const glm::vec3 up(0, 1, 0), right = glm::normalize(glm::cross(c.target - c.eye, up));
    const glm::vec3 shift = -right * separation;
    const glm::mat4 view = glm::lookAt(c.eye + shift, c.target + shift, up);
    const glm::mat4 vp =
        rrc_sample::reversed_perspective(c.fov_y, (float)rs.width / (float)rs.height, scene.near_plane, scene.far_plane) * view;
    state.uniforms.view_proj = vp;
    state.uniforms.inv_view_proj = glm::inverse(vp);
    // "Previous" is the first eye at the same instant: PREV_CLIP of the same surface point in its view.
    state.uniforms.prev_view_proj = first_eye_vp;
    state.uniforms.camera_pos = glm::vec4(c.eye + shift, state.uniforms.camera_pos.w);
    for (auto& o : state.objects) o.prev_model = o.model;
}

}  // namespace

struct Bench::Impl {
    explicit Impl(const Settings& s)
        : settings(s),
          gpu(rrc_sample::GpuOptions{s.validation, ""}),
          scene(rrc_sample::Scene::make("temple")),
          render{s.width, s.height},  // the test bed's other render settings: its defaults
          gpu_scene(gpu, scene),
          gbuffer(gpu, gpu_scene, s.width, s.height),
          commands(gpu) {
        const VkImageUsageFlags storage =
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        shaded = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, s.width, s.height, storage, "shaded (rrc samples)");
        truth = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, s.width, s.height, storage, "every pixel shaded");
        out = gpu.create_image(VK_FORMAT_R32G32B32A32_SFLOAT, s.width, s.height, storage, "rrc output");
        mask = gpu.create_image(VK_FORMAT_R8_UINT, s.width, s.height,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "rrc mask");
        gpu.init_storage_images({&shaded, &truth, &out, &mask});
        list = gpu.create_buffer(
            RRC_QUAD_LIST_BYTES(s.width, s.height),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "quad list");
        counter = gpu.create_buffer(16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, "shaded quads");
    }
    ~Impl() {
        vkDeviceWaitIdle(gpu.device);
        shaders.clear();
        gpu.destroy(list);
        gpu.destroy(counter);
        for (Image* i : {&shaded, &truth, &out, &mask}) gpu.destroy(*i);
    }
    // The shader at `octaves` octaves (perlin.glsl's kOctaves), both ways: every pixel and the miss
    // shader; made on first use and kept, so a run's frames do not pay for pipeline creation.
    struct Shaders {
        rrc_sample::ComputeKernel full, miss;
    };
    Shaders& shaders_for(uint32_t octaves) {
        auto it = shaders.find(octaves);
        if (it != shaders.end()) return it->second;
        const VkDescriptorType TEX = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, IMG = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                               BUF = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        const std::vector<uint32_t> full_spv =
            with_spec_constant(rrc_cache_shade_full_comp, sizeof rrc_cache_shade_full_comp, kOctavesSpecId, octaves);
        const std::vector<uint32_t> miss_spv =
            with_spec_constant(rrc_cache_shade_miss_comp, sizeof rrc_cache_shade_miss_comp, kOctavesSpecId, octaves);
        Shaders& k = shaders[octaves];
        k.full = rrc_sample::ComputeKernel(gpu, "shade every pixel", full_spv.data(), 4 * full_spv.size(), {TEX, TEX, IMG}, 8, 2);
        k.miss = rrc_sample::ComputeKernel(gpu, "miss shader", miss_spv.data(), 4 * miss_spv.size(), {TEX, TEX, IMG, BUF, BUF}, 8, 1);
        const rrc_sample::GBuffer& g = gbuffer.images();
        for (uint32_t set = 0; set < 2; ++set) {
            k.full.bind_image(set, 0, g.position.view, kRO);
            k.full.bind_image(set, 1, g.normal.view, kRO);
            k.full.bind_image(set, 2, set == 0 ? shaded.view : truth.view, kGeneral);
        }
        k.miss.bind_image(0, 0, g.position.view, kRO);
        k.miss.bind_image(0, 1, g.normal.view, kRO);
        k.miss.bind_image(0, 2, shaded.view, kGeneral);
        k.miss.bind_buffer(0, 3, list.buffer);
        k.miss.bind_buffer(0, 4, counter.buffer);
        return k;
    }

    // Records `body` after a full barrier (the previous submission's writes
    // visible), submits, waits; the wall clock less the fastest empty one.
    template <typename Body>
    double submit(Body&& body) {
        const VkCommandBuffer cmd = commands.begin();
        rrc_host::full_barrier(cmd);
        body(cmd);
        // Its writes to the host (the list, the counter, readbacks after the fence).
        rrc_sample::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                                   VK_ACCESS_HOST_READ_BIT);
        return commands.submit_and_wait();
    }
    double timed(const std::function<void(VkCommandBuffer)>& body) {
        empty_floor = std::min(empty_floor, submit([](VkCommandBuffer) {}));
        return std::max(submit(body) - empty_floor, 0.0);
    }

    std::vector<float> read_rgba(const Image& img) {
        const std::vector<unsigned char> b = gpu.download(img, (size_t)settings.width * settings.height * 16, kGeneral);
        std::vector<float> f(b.size() / 4);
        std::memcpy(f.data(), b.data(), b.size());
        return f;
    }

    Settings settings;
    Gpu gpu;
    rrc_sample::Scene scene;
    rrc_sample::RenderSettings render;
    rrc_sample::GpuScene gpu_scene;
    rrc_sample::GBufferPass gbuffer;
    rrc_host::FencedCommands commands;
    Image shaded, truth, out, mask;
    rrc_host::Buffer list, counter;
    std::map<uint32_t, Shaders> shaders;  // by octave count
    double empty_floor = std::numeric_limits<double>::infinity();
};

Bench::Bench(const Settings& settings) : impl_(new Impl(settings)) {}
Bench::~Bench() = default;
std::string Bench::device_name() const { return impl_->gpu.device_name(); }
std::vector<std::string> Bench::validation_messages() const { return impl_->gpu.messages(); }

RunResult Bench::run(const CacheConfig& config, void (*progress)(int, int)) {
    Impl& m = *impl_;
    const Settings& s = m.settings;
    const size_t n = (size_t)s.width * s.height;
    const uint32_t push[2] = {s.width, s.height};
    const uint64_t messages_before = m.gpu.message_count();
    RunResult result;
    result.config = config;
    if (config.octaves < 1 || config.octaves > kMaxOctaves)
        throw std::invalid_argument("rrc-cache: octaves must be in 1.." + std::to_string(kMaxOctaves));
    Impl::Shaders& k = m.shaders_for(config.octaves);

    // The cache: one 4-component channel (fp16 history) from the library's preset (REUSE, bilinear, as the
    // paper); the refresh policy is the run's (the study's grid, not the preset's).
    std::vector<rrc_channel_desc> channels{rrc_host::channel("shade", 4, 0.0f, RRC_HISTORY_FP16)};
    if (rrc_channel_preset(RRC_PRESET_SHADING_CACHE, 0, RRC_API_VERSION, &channels[0]) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_channel_preset: ") + rrc_last_error());
    rrc_context_desc desc = rrc_host::context_desc(s.width, s.height, channels);
    desc.depth_mode = RRC_DEPTH_MODE_REVERSED;
    desc.near_plane = m.scene.near_plane;
    desc.far_plane = m.scene.far_plane;
    desc.reprojection = RRC_REPROJECTION_PREV_CLIP;
    desc.refresh_policy = config.policy;
    desc.refresh_period = config.policy != RRC_REFRESH_NONE ? config.period : 0;
    desc.max_lifetime = config.lifetime;
    desc.view_count = config.stereo ? 2 : 1;
    rrc_context* ctx = nullptr;
    if (config.cache) {
        const rrc_vulkan_device_desc dd = rrc_host::vulkan_device_desc(m.gpu, 1);
        if (rrc_vulkan_context_create(&desc, &dd, &ctx) != RRC_SUCCESS)
            throw std::runtime_error(std::string("rrc-cache: rrc_vulkan_context_create: ") + rrc_last_error());
    }
    const rrc_sample::GBuffer& g = m.gbuffer.images();

    // Motion blur: sub-frame k of frame t is time (t + k / S) / fps, i.e. index t*S + k at S times the rate.
    const uint32_t S = std::max(config.subframes, 1u);
    rrc_sample::RenderSettings render = m.render;
    render.fps *= (float)S;
    for (int t = 0; t < s.frames; ++t) {
        FrameRecord rec;
        std::vector<double> blurred(S > 1 ? 4 * n : 0, 0.0), blurred_truth(S > 1 ? 4 * n : 0, 0.0);
        for (uint32_t sub = 0; sub < S; ++sub) {
            const int index = t * (int)S + (int)sub;
            rrc_sample::FrameState state = rrc_sample::make_frame_state(m.scene, render, index);
            const glm::mat4 first_eye_vp = state.uniforms.view_proj;
            for (int eye = 0; eye < (config.stereo ? 2 : 1); ++eye) {
                if (eye == 1) second_eye(m.scene, render, index, s.eye_separation, state, first_eye_vp);
                m.gpu_scene.update(state);
                rec.raster_ms += m.timed([&](VkCommandBuffer c) { m.gbuffer.record(c); });
                if (!config.cache) {
                    rec.shade_ms += m.timed([&](VkCommandBuffer c) { k.full.dispatch(c, 0, push, s.width, s.height); });
                    rec.full_shade_ms = rec.shade_ms;
                    rec.shaded_fraction += 1.0;
                    rec.pixels += n;
                    if (t + 1 == s.frames && sub + 1 == S) (eye == 0 ? result.image : result.image_left) = m.read_rgba(m.shaded);
                    continue;
                }
                rrc_vulkan_channel_images ci = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
                ci.samples = rrc_host::vulkan_image(m.shaded, kGeneral);
                ci.output = rrc_host::vulkan_image(m.out, kGeneral);
                rrc_vulkan_frame_desc f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
                f.frame_index = (uint64_t)index;
                f.depth = rrc_host::vulkan_image(g.depth, kRO);
                f.reprojection = rrc_host::vulkan_image(g.prev_clip, kRO);
                f.mask = rrc_host::vulkan_image(m.mask, kGeneral);
                f.channel_count = 1;
                f.channels = &ci;
                f.view = (uint32_t)eye;
                f.reproject_from = eye == 1 ? 1u : 0u;  // the second eye: the first eye's frame just made
                // Classify writes the HITs' outputs, resolve the listed quads': no full-frame copy (rrc_vulkan.h).
                f.split_outputs = 1;
                rrc_vulkan_quad_list list = rrc_host::rrc_struct<rrc_vulkan_quad_list>(RRC_STRUCT_TYPE_VULKAN_QUAD_LIST);
                list.buffer = m.list.buffer;
                list.buffer_size = RRC_QUAD_LIST_BYTES(s.width, s.height);  // as created: rrc refuses a list past it
                auto record = [&](VkCommandBuffer c, bool classify) {
                    f.command_buffer = c;
                    const rrc_result r = classify ? rrc_vulkan_record_classify(ctx, &f, &list) : rrc_vulkan_record_resolve(ctx, &f);
                    if (r != RRC_SUCCESS) throw std::runtime_error(std::string("rrc-cache: ") + rrc_context_last_error(ctx));
                };
                rec.classify_ms += m.timed([&](VkCommandBuffer c) { record(c, true); });
                std::memset(m.counter.mapped, 0, 16);  // host-coherent, written before the submission
                rec.shade_ms +=
                    m.timed([&](VkCommandBuffer c) { k.miss.dispatch_indirect(c, 0, push, m.list.buffer, 4 * RRC_QUAD_LIST_DISPATCH); });
                rec.resolve_ms += m.timed([&](VkCommandBuffer c) { record(c, false); });
                const uint32_t* words = static_cast<const uint32_t*>(m.list.mapped);
                const uint32_t listed = words[RRC_QUAD_LIST_COUNT], shaded_quads = *static_cast<const uint32_t*>(m.counter.mapped);
                result.list_matched = result.list_matched && listed == shaded_quads;
                rec.listed += listed;
                rec.shaded_quads += shaded_quads;
                uint64_t shaded_pixels = 0;
                for (uint32_t i = 0; i < listed; ++i) {
                    const uint32_t q = words[RRC_QUAD_LIST_FIRST_QUAD + i], x = 2 * (q & 0xFFFF), y = 2 * (q >> 16);
                    shaded_pixels += (uint64_t)std::min(2u, s.width - x) * std::min(2u, s.height - y);
                }
                rec.shaded_fraction += (double)shaded_pixels / (double)n;
                // The target: this frame shaded everywhere; timed, the paired baseline of this frame.
                rec.full_shade_ms += m.timed([&](VkCommandBuffer c) { k.full.dispatch(c, 1, push, s.width, s.height); });
                const std::vector<float> img = m.read_rgba(m.out), tru = m.read_rgba(m.truth);
                const std::vector<unsigned char> mk = m.gpu.download(m.mask, n, kGeneral);
                if (S > 1) {  // the blurred frame's error, after its last sub-frame
                    for (size_t i = 0; i < 4 * n; ++i) blurred[i] += img[i] / (double)S, blurred_truth[i] += tru[i] / (double)S;
                } else {
                    double se = 0;
                    for (size_t i = 0; i < n; ++i)
                        for (int k = 0; k < 3; ++k) se += (img[4 * i + k] - tru[4 * i + k]) * (double)(img[4 * i + k] - tru[4 * i + k]);
                    rec.rmse += std::sqrt(se / (3.0 * n));
                }
                for (unsigned char b : mk) {
                    rec.hits += (b & RRC_MASK_HIT) ? 1 : 0;
                    rec.refreshed += (b & RRC_MASK_REFRESHED) ? 1 : 0;
                }
                rec.pixels += n;
                if (t + 1 == s.frames && sub + 1 == S) {
                    (eye == 0 ? result.image : result.image_left) = img;
                    (eye == 0 ? result.mask : result.mask_left) = std::vector<uint8_t>(mk.begin(), mk.end());
                    if (eye == 0) result.truth = tru;
                }
            }
        }
        if (S > 1 && config.cache) {
            double se = 0;
            for (size_t i = 0; i < n; ++i)
                for (int k = 0; k < 3; ++k)
                    se += (blurred[4 * i + k] - blurred_truth[4 * i + k]) * (blurred[4 * i + k] - blurred_truth[4 * i + k]);
            rec.rmse = std::sqrt(se / (3.0 * n));
        }
        if (config.stereo) rec.rmse *= 0.5;
        rec.shaded_fraction /= (double)(S * (config.stereo ? 2 : 1));
        result.frames.push_back(rec);
        if (progress) progress(t + 1, s.frames);
    }
    rrc_context_destroy(ctx);
    result.validation_messages = m.gpu.message_count() - messages_before;
    return result;
}

}  // namespace rrc_cache
