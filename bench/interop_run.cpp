#include "interop_run.h"

#include "rrc_interop.h"
#include "stats.h"

#include <cstring>
#include <stdexcept>
#include <tuple>

namespace rrc_bench {

using rrc_host::vk_check;

// Queries: 0-1 around the kernel's commands, 2-3 around the roof's.
constexpr uint32_t kQueries = 4;

// Every submission starts with a full barrier (waiting for all earlier work
// and its writes), so the kernel and the roof, which write the same outputs,
// never overlap.
using rrc_host::full_barrier;

static rrc_vulkan_image general(const Image& img) { return rrc_host::vulkan_image(img, VK_IMAGE_LAYOUT_GENERAL); }

InteropBench::InteropBench(VulkanBootstrap& vk, const Config& c, const SceneInputs& scene, const BenchImages& img, LogCounter& log)
    : vk_(vk), config_(c), scene_(scene), img_(img) {
    ContextSetup setup(c, log);
    // One frame in flight: the bench waits for every submission.
    const rrc_vulkan_device_desc dd = rrc_host::vulkan_device_desc(vk, 1);
    if (rrc_vulkan_context_create(setup.desc(), &dd, &ctx_) != RRC_SUCCESS)
        throw std::runtime_error(std::string("rrc_vulkan_context_create: ") + rrc_last_error());
    rrc_context_memory_usage(ctx_, &res_.memory_bytes);
    try {
        stats_ = vk.create_buffer(256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "bench stats");
        if (c.shading_cache == Config::Cache::Split || c.shading_cache == Config::Cache::ClassifyFused)
            quads_ = vk.create_buffer(RRC_QUAD_LIST_BYTES(c.width, c.height),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      true, "bench quad list");
        roof_ = std::make_unique<Roof>(vk, c, img);
        res_.roof_bytes_bound = roof_->bound_bytes();
        timer_ = std::make_unique<rrc_host::TimestampQueries>(vk, kQueries);
        sub_ = std::make_unique<rrc_host::FencedCommands>(vk);
        res_.timestamps = timer_->enabled();
    } catch (...) {
        release();
        throw;
    }
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        auto ci = rrc_host::rrc_struct<rrc_vulkan_channel_images>(RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES);
        ci.samples = general(img.samples[ch]);
        if (c.channels[ch].confidence) ci.confidence = general(img.confidence[ch]);
        if (c.channels[ch].residual) ci.fallback = general(img.base[ch]);  // the residual's base
        ci.output = general(img.values[ch]);
        ci.age = general(img.age_out[ch]);
        channels_.push_back(ci);
    }
}

InteropBench::~InteropBench() { release(); }

void InteropBench::release() {
    vkDeviceWaitIdle(vk_.device);
    sub_.reset();
    timer_.reset();
    roof_.reset();
    vk_.destroy(stats_);
    vk_.destroy(quads_);
    rrc_context_destroy(ctx_);
    ctx_ = nullptr;
}

// One kernel frame (pose = frame parity): {GPU ms, wall ms}.  Timed frames
// pass no statistics buffer (the library's default; counting costs the
// kernel time the roof does not spend); one untimed frame at the end does,
// for the hit/miss mix the report gives, and where the frame is one
// rrc_vulkan_record_frame it also counts the image operations (count_io).
std::pair<double, double> InteropBench::kernel(bool with_stats) {
    const int pose = (int)(frame_ % 2);
    const PoseFrame& pf = scene_.poses[pose];
    auto f = rrc_host::rrc_struct<rrc_vulkan_frame_desc>(RRC_STRUCT_TYPE_VULKAN_FRAME_DESC);
    f.frame_index = frame_;
    f.depth = general(img_.poses[pose].depth);
    if (img_.poses[pose].reprojection.image) f.reprojection = general(img_.poses[pose].reprojection);
    if (config_.nocache) f.nocache = general(img_.nocache);
    if (config_.object_id) f.object_id = general(img_.poses[pose].object_id);
    f.mask = general(img_.mask);
    // MOTION's RG32F vectors have no storage binding in the kernel (storage_inputs asks RGBA32F): sampled.
    f.storage_inputs = config_.sampled_inputs || config_.source == RRC_REPROJECTION_MOTION ? 0u : 1u;
    for (int i = 0; i < 16; ++i) {
        f.view_proj[i] = pf.view_proj[i / 4][i % 4];  // column-major, as GLM stores it
        f.prev_view_proj[i] = pf.prev_view_proj[i / 4][i % 4];
    }
    for (int k = 0; k < 3; ++k) f.camera_position[k] = pf.eye[k], f.prev_camera_position[k] = pf.prev_eye[k];
    f.channel_count = (uint32_t)channels_.size();
    f.channels = channels_.data();
    if (with_stats) f.stats_buffer = stats_.buffer, f.stats_buffer_size = 256;  // the size stated: rrc refuses a range past it
    if (with_stats && config_.records_frame_only()) f.count_io = 1;
    const double t0 = now_ms();
    f.command_buffer = sub_->begin();
    full_barrier(f.command_buffer);
    timer_->reset(f.command_buffer, 0, 2);
    timer_->write(f.command_buffer, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0);
    if (config_.shading_cache == Config::Cache::Split || config_.shading_cache == Config::Cache::ClassifyFused) {
        auto list = rrc_host::rrc_struct<rrc_vulkan_quad_list>(RRC_STRUCT_TYPE_VULKAN_QUAD_LIST);
        list.buffer = quads_.buffer;
        list.buffer_size = RRC_QUAD_LIST_BYTES(config_.width, config_.height);
        const bool split = config_.shading_cache == Config::Cache::Split;
        f.split_outputs = split && config_.split_outputs ? 1u : 0u;
        if (rrc_vulkan_record_classify(ctx_, &f, &list) != RRC_SUCCESS ||
            (split ? rrc_vulkan_record_resolve(ctx_, &f) : rrc_vulkan_record_frame(ctx_, &f)) != RRC_SUCCESS)
            throw std::runtime_error(std::string("rrc_vulkan_record_classify/resolve: ") + rrc_context_last_error(ctx_));
    } else if (rrc_vulkan_record_frame(ctx_, &f) != RRC_SUCCESS) {
        throw std::runtime_error(std::string("rrc_vulkan_record_frame: ") + rrc_context_last_error(ctx_));
    }
    timer_->write(f.command_buffer, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 1);
    sub_->submit_and_wait();
    const double wall = now_ms() - t0;
    ++frame_;
    return {timer_->enabled() ? elapsed_ms(0) : wall, wall};
}

// One roof dispatch on `pose`'s inputs.
double InteropBench::roof_pass(int pose) {
    const double t0 = now_ms();
    VkCommandBuffer cmd = sub_->begin();
    full_barrier(cmd);
    timer_->reset(cmd, 2, 2);
    timer_->write(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 2);
    roof_->record(cmd, pose);
    timer_->write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 3);
    full_barrier(cmd);  // its writes are done before anything later reads or rewrites them
    sub_->submit_and_wait();
    const double wall = now_ms() - t0;
    return timer_->enabled() ? elapsed_ms(2) : wall;
}

// Milliseconds between queries `first` and `first` + 1.
double InteropBench::elapsed_ms(uint32_t first) const {
    const std::vector<uint64_t> t = timer_->ticks(first, 2);
    return (double)(t[1] - t[0]) * vk_.properties.limits.timestampPeriod * 1e-6;
}

void InteropBench::prime(int frames) {
    for (int i = 0; i < frames; ++i) kernel(false);
}

void InteropBench::step(bool record) {
    const int pose = (int)(frame_ % 2);  // the roof reads what this pair's kernel frame reads
    double k, w, t;
    if (steps_++ % 2 == 0) {
        std::tie(k, w) = kernel(false);
        t = roof_pass(pose);
    } else {
        t = roof_pass(pose);
        std::tie(k, w) = kernel(false);
    }
    if (!record) return;
    res_.kernel_ms.push_back(k);
    res_.wall_ms.push_back(w);
    res_.roof_ms.push_back(t);
    res_.ratio.push_back(k / t);
}

// Young pixels of the statistics frame: not background (mask) and age <
// kYoungAge in channel 0's age output, the pixels the fill works on
// (docs/CONVENTIONS.md, "The spatial fill").  Read back before the roof
// check rewrites both images.
uint64_t InteropBench::count_young() {
    const VkImageLayout g = VK_IMAGE_LAYOUT_GENERAL;
    const auto age = vk_.download(img_.age_out[0], image_bytes(img_.age_out[0]), g);
    const auto mask = vk_.download(img_.mask, image_bytes(img_.mask), g);
    uint64_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        uint16_t a;
        std::memcpy(&a, &age[2 * i], sizeof a);
        n += !(mask[i] & RRC_MASK_BACKGROUND) && a < kYoungAge;
    }
    return n;
}

InteropResult InteropBench::finish(bool check_roof) {
    kernel(true);
    std::memcpy(&res_.stats, stats_.mapped, sizeof res_.stats);
    res_.io_counted = config_.records_frame_only();
    if (res_.io_counted) std::memcpy(&res_.io, static_cast<const char*>(stats_.mapped) + sizeof res_.stats, sizeof res_.io);
    if (quads_.mapped) std::memcpy(&res_.listed_quads, quads_.mapped, sizeof res_.listed_quads);
    res_.young = count_young();
    if (check_roof) {
        roof_pass(0);  // the roof is the last writer of the outputs it checks
        res_.roof_check = roof_->check(0);
    } else {
        res_.roof_check = "skipped";
    }
    return res_;
}

}  // namespace rrc_bench
