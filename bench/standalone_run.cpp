#include "standalone_run.h"

#include "rrc_descs.h"
#include "stats.h"

#include <cstring>
#include <stdexcept>

namespace rrc_bench {

StandaloneBench::StandaloneBench(const Config& c, const SceneInputs& scene, LogCounter& log, const std::string& device, bool validation)
    : config_(c), scene_(scene) {
    ContextSetup setup(c, log);
    rrc_context_desc desc = *setup.desc();
    if (!device.empty()) desc.device_name = device.c_str();
    desc.enable_validation = validation ? 1u : 0u;
    if (rrc_context_create(&desc, &ctx_) != RRC_SUCCESS) throw std::runtime_error(std::string("rrc_context_create: ") + rrc_last_error());

    const size_t px = (size_t)c.width * c.height;
    // Outputs read back: every channel's values and age (weight too with
    // confidence), and the mask: what the interop path writes.
    values_.resize(c.channels.size());
    weights_.resize(c.channels.size());
    ages_.resize(c.channels.size());
    mask_.resize(px);
    uint64_t bytes = px;  // the mask
    for (size_t ch = 0; ch < c.channels.size(); ++ch) {
        values_[ch].resize(px * c.channels[ch].components);
        ages_[ch].resize(px);
        rrc_channel_output o = rrc_host::channel_output();
        o.values = values_[ch].data();
        o.age = ages_[ch].data();
        bytes += values_[ch].size() * sizeof(float) + ages_[ch].size() * sizeof(uint16_t);
        if (c.channels[ch].confidence) {
            weights_[ch].resize(px);
            o.weight = weights_[ch].data();
            bytes += px * sizeof(float);
        }
        outs_.push_back(o);
    }
    // Inputs, as arrays: depth, reprojection data, samples, confidence, bases, nocache, ids.
    bytes += px * sizeof(float) + scene.poses[0].reprojection.size() * sizeof(float);
    for (size_t ch = 0; ch < c.channels.size(); ++ch)
        bytes += (scene.samples[ch].size() + scene.confidence[ch].size() + scene.base[ch].size()) * sizeof(float);
    bytes += scene.nocache.size() + scene.poses[0].object_id.size() * sizeof(uint32_t);
    res_.bytes = bytes;
    src_.assign(bytes, 1);  // touched once, so the timed copy faults nothing in
    dst_.assign(bytes, 0);
    char name[256] = {};
    rrc_context_device_name(ctx_, name, sizeof name);
    res_.device = name;
}

StandaloneBench::~StandaloneBench() { rrc_context_destroy(ctx_); }

double StandaloneBench::run_frame() {
    const PoseFrame& pf = scene_.poses[frame_ % 2];
    std::vector<rrc_channel_input> ins;
    for (size_t ch = 0; ch < config_.channels.size(); ++ch) {
        ins.push_back(rrc_host::channel_input(scene_.samples[ch].data(), scene_.confidence[ch].empty() ? nullptr : scene_.confidence[ch].data()));
        if (!scene_.base[ch].empty()) ins.back().fallback = scene_.base[ch].data();  // the residual's base
    }
    rrc_frame_desc f = rrc_host::frame_desc();
    f.frame_index = frame_;
    f.depth = pf.depth.data();
    f.reprojection = pf.reprojection.empty() ? nullptr : pf.reprojection.data();
    for (int i = 0; i < 16; ++i) {
        f.view_proj[i] = pf.view_proj[i / 4][i % 4];
        f.prev_view_proj[i] = pf.prev_view_proj[i / 4][i % 4];
    }
    for (int k = 0; k < 3; ++k) f.camera_position[k] = pf.eye[k], f.prev_camera_position[k] = pf.prev_eye[k];
    f.nocache = scene_.nocache.empty() ? nullptr : scene_.nocache.data();
    f.object_id = pf.object_id.empty() ? nullptr : pf.object_id.data();
    f.channel_count = (uint32_t)ins.size();
    f.channels = ins.data();
    rrc_frame_output o = rrc_host::frame_output();
    o.mask = mask_.data();
    o.channel_count = (uint32_t)outs_.size();
    o.channels = outs_.data();
    const double t0 = now_ms();
    // The shading cache's rows make the interop path's calls (interop_run.cpp):
    // classify, then resolve (Split) or the fused frame (ClassifyFused).
    if (config_.shading_cache == Config::Cache::Split || config_.shading_cache == Config::Cache::ClassifyFused) {
        quads_.resize(RRC_QUAD_LIST_BYTES(config_.width, config_.height) / 4 - RRC_QUAD_LIST_FIRST_QUAD);
        auto classified = rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT);
        classified.quads = quads_.data();
        classified.quad_capacity = (uint32_t)quads_.size();
        if (rrc_frame_classify(ctx_, &f, &classified) != RRC_SUCCESS)
            throw std::runtime_error(std::string("rrc_frame_classify: ") + rrc_context_last_error(ctx_));
    }
    if (config_.shading_cache == Config::Cache::Split) {
        auto resolve = rrc_host::rrc_struct<rrc_resolve_desc>(RRC_STRUCT_TYPE_RESOLVE_DESC);
        resolve.channel_count = f.channel_count;
        resolve.channels = f.channels;
        if (rrc_frame_resolve(ctx_, &resolve, &o) != RRC_SUCCESS)
            throw std::runtime_error(std::string("rrc_frame_resolve: ") + rrc_context_last_error(ctx_));
    } else if (rrc_frame_run(ctx_, &f, &o) != RRC_SUCCESS) {
        throw std::runtime_error(std::string("rrc_frame_run: ") + rrc_context_last_error(ctx_));
    }
    const double ms = now_ms() - t0;
    res_.hit_fraction = (double)o.stats.hits / ((double)config_.width * config_.height);
    ++frame_;
    return ms;
}

double StandaloneBench::copy() {
    const double t0 = now_ms();
    std::memcpy(dst_.data(), src_.data(), dst_.size());
    const double ms = now_ms() - t0;
    src_[frame_ % src_.size()] ^= dst_[(frame_ * 7) % dst_.size()];  // the copy's result is used: it cannot be elided
    return ms;
}

void StandaloneBench::step(bool record) {
    const double f = run_frame(), m = copy();
    if (!record) return;
    res_.frame_ms.push_back(f);
    res_.memcpy_ms.push_back(m);
}

StandaloneResult StandaloneBench::result() const {
    StandaloneResult r = res_;
    rrc_context_memory_usage(ctx_, &r.memory_bytes);
    rrc_context_validation_messages(ctx_, &r.validation_messages);
    return r;
}

}  // namespace rrc_bench
