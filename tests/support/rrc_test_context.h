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

// What BoundOutput puts in the arrays before a call, so that a test sees what
// the call did not write.
struct OutputFill {
    uint8_t mask = 0;
    float value = 0.0f;
    uint16_t age = 0;
};

// r's arrays sized for `channels` at n pixels (weights for the channels with
// a confidence) and bound into `frame`, the output of rrc_frame_run or
// rrc_frame_resolve.  Not copyable: `frame` points into `outputs`.
struct BoundOutput {
    std::vector<rrc_channel_output> outputs;
    rrc_frame_output frame;

    BoundOutput(FrameResult& r, const std::vector<rrc_channel_desc>& channels, size_t n, OutputFill fill = {})
        : outputs(channels.size()), frame(rrc_host::frame_output()) {
        r.mask.assign(n, fill.mask);
        r.values.resize(channels.size());
        r.age.resize(channels.size());
        r.weight.resize(channels.size());
        for (size_t i = 0; i < channels.size(); ++i) {
            r.values[i].assign(n * channels[i].components, fill.value);
            r.age[i].assign(n, fill.age);
            outputs[i] = rrc_host::channel_output();
            outputs[i].values = r.values[i].data();
            outputs[i].age = r.age[i].data();
            if (channels[i].confidence) {
                r.weight[i].resize(n);
                outputs[i].weight = r.weight[i].data();
            }
        }
        frame.mask = r.mask.data();
        frame.channel_count = (uint32_t)outputs.size();
        frame.channels = outputs.data();
    }
    BoundOutput(const BoundOutput&) = delete;
    BoundOutput& operator=(const BoundOutput&) = delete;
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
        FrameResult r;
        BoundOutput o(r, channels_, (size_t)desc_.width * desc_.height);
        rrc_result res = rrc_frame_run(ctx_, &frame, &o.frame);
        EXPECT_EQ(res, RRC_SUCCESS) << rrc_result_to_string(res) << ": " << rrc_last_error();
        r.stats = o.frame.stats;
        return r;
    }

private:
    rrc_context_desc desc_;
    std::vector<rrc_channel_desc> channels_;
    ValidationLog log_;
    rrc_context* ctx_ = nullptr;
};

}  // namespace rrc_test
