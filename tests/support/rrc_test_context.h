// Test support: rrc descriptors (the shared builders) and a context that runs under
// VK_LAYER_KHRONOS_validation with synchronization validation, recording
// every message (including those emitted while the device is destroyed).
// A test fails if any message was seen.
#pragma once

#include <rrc/rrc.h>

#include "rrc_descs.h"

#include <gtest/gtest.h>

#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace rrc_test {

// The descriptor builders rrc-sample uses too (host_sample/common/rrc_descs.h).
using rrc_host::channel;
using rrc_host::channel_input;
using rrc_host::context_desc;
using rrc_host::frame_desc;

// Messages of the validation layer; shared with the log callback.
struct ValidationLog {
    std::mutex mutex;
    std::vector<std::string> messages;
    static void callback(void* user, rrc_log_level level, const char* message) {
        if (level != RRC_LOG_VALIDATION) return;
        auto* self = static_cast<ValidationLog*>(user);
        std::lock_guard<std::mutex> lock(self->mutex);
        self->messages.push_back(message);
    }
};

// Per-frame outputs of every channel, read back as arrays.
struct FrameResult {
    std::vector<uint8_t> mask;
    std::vector<std::vector<float>> values, weight;
    std::vector<std::vector<uint16_t>> age;
    rrc_frame_stats stats{};
};

// A context under validation.  The destructor destroys it and adds a test
// failure for any validation message, leaks reported at destruction included.
class Context {
public:
    explicit Context(rrc_context_desc desc) : desc_(desc) {
        desc_.enable_validation = 1;
        desc_.log = &ValidationLog::callback;
        desc_.log_user = &log_;
        for (uint32_t i = 0; i < desc.channel_count; ++i) channels_.push_back(desc.channels[i]);
        desc_.channels = channels_.data();
        rrc_result r = rrc_context_create(&desc_, &ctx_);
        EXPECT_EQ(r, RRC_SUCCESS) << rrc_result_to_string(r) << ": " << rrc_last_error();
    }
    ~Context() {
        rrc_context_destroy(ctx_);
        std::lock_guard<std::mutex> lock(log_.mutex);
        EXPECT_TRUE(log_.messages.empty()) << log_.messages.size() << " validation messages, first: " << log_.messages.front();
    }
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    rrc_context* get() const { return ctx_; }
    explicit operator bool() const { return ctx_ != nullptr; }
    const rrc_context_desc& desc() const { return desc_; }

    // Runs a frame and reads back every output.
    FrameResult run(const rrc_frame_desc& frame) {
        const size_t n = (size_t)desc_.width * desc_.height;
        FrameResult r;
        r.mask.resize(n);
        r.values.resize(channels_.size());
        r.age.resize(channels_.size());
        r.weight.resize(channels_.size());
        std::vector<rrc_channel_output> outs(channels_.size());
        for (size_t i = 0; i < channels_.size(); ++i) {
            r.values[i].resize(n * channels_[i].components);
            r.age[i].resize(n);
            outs[i] = rrc_host::channel_output();
            outs[i].values = r.values[i].data();
            outs[i].age = r.age[i].data();
            if (channels_[i].confidence) {
                r.weight[i].resize(n);
                outs[i].weight = r.weight[i].data();
            }
        }
        rrc_frame_output o = rrc_host::frame_output();
        o.mask = r.mask.data();
        o.channel_count = (uint32_t)outs.size();
        o.channels = outs.data();
        rrc_result res = rrc_frame_run(ctx_, &frame, &o);
        EXPECT_EQ(res, RRC_SUCCESS) << rrc_result_to_string(res) << ": " << rrc_last_error();
        r.stats = o.stats;
        return r;
    }

private:
    rrc_context_desc desc_;
    std::vector<rrc_channel_desc> channels_;
    ValidationLog log_;
    rrc_context* ctx_ = nullptr;
};

}  // namespace rrc_test
