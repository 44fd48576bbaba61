// The C boundary: every entry point validates, catches every exception and
// turns it into an rrc_result plus a message.  Nothing throws across it.
#include "error.h"
#include "frame.h"
#include "interop_context.h"
#include "presets.h"
#include "standalone_context.h"
#include "struct_reader.h"
#include "validation.h"
#include "vk_requirements.h"

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <string>
#include <unordered_set>

// Exactly one of the two is set: the library's own device, or the host's.
struct rrc_context {
    std::unique_ptr<rrc::StandaloneContext> standalone;
    std::unique_ptr<rrc::InteropContext> interop;
    std::string last_error;
    std::atomic<bool> busy{false};  // a call is in progress (on_context)
    const rrc::ContextConfig& config() const { return standalone ? standalone->config() : interop->config(); }
    const rrc::VulkanDevice& device() const { return standalone ? standalone->device() : interop->device(); }
};

namespace {

thread_local std::string t_last_error;

// Live handles: a destroyed or foreign pointer is detected without being
// dereferenced.
std::mutex g_contexts_mutex;
std::unordered_set<const rrc_context*>& live_contexts() {
    static std::unordered_set<const rrc_context*> set;
    return set;
}
bool is_live(const rrc_context* c) {
    std::lock_guard<std::mutex> lock(g_contexts_mutex);
    return live_contexts().count(c) != 0;
}

// Runs body; maps exceptions to results and records the message.
template <typename Body>
rrc_result guarded(rrc_context* ctx, rrc_log_fn log, void* log_user, Body&& body) {
    rrc_result code = RRC_SUCCESS;
    std::string message;
    try {
        body();
        t_last_error.clear();
        return RRC_SUCCESS;
    } catch (const rrc::Error& e) {
        code = e.code;
        message = e.what();
    } catch (const std::bad_alloc&) {
        code = RRC_ERROR_OUT_OF_MEMORY;
        message = "out of host memory";
    } catch (const std::exception& e) {
        code = RRC_ERROR_DEVICE;
        message = std::string("internal error: ") + e.what();
    } catch (...) {
        code = RRC_ERROR_DEVICE;
        message = "internal error";
    }
    try {
        t_last_error = message;
        if (ctx) ctx->last_error = message;
        if (log) log(log_user, RRC_LOG_ERROR, message.c_str());
    } catch (...) {
    }
    return code;
}

rrc_context* publish(std::unique_ptr<rrc_context> ctx) {
    std::lock_guard<std::mutex> lock(g_contexts_mutex);
    live_contexts().insert(ctx.get());
    return ctx.release();
}

rrc_context* live_or_null(const rrc_context* c) { return c && is_live(c) ? const_cast<rrc_context*>(c) : nullptr; }

rrc_context* checked(rrc_context* c) {
    if (!c) rrc::fail(RRC_ERROR_INVALID_HANDLE, "context is NULL");
    if (!is_live(c)) rrc::fail(RRC_ERROR_INVALID_HANDLE, "context %p is not a live rrc context (destroyed or foreign)", (void*)c);
    return c;
}

// A create call reports to the descriptor's log callback when the
// descriptor is readable enough to hold one.
bool desc_readable(const rrc_context_desc* d) {
    return d && d->type == RRC_STRUCT_TYPE_CONTEXT_DESC && d->size >= rrc::StructInfo<rrc_context_desc>::size_0_1;
}
rrc_log_fn desc_log(const rrc_context_desc* d) { return desc_readable(d) ? d->log : nullptr; }
void* desc_log_user(const rrc_context_desc* d) { return desc_readable(d) ? d->log_user : nullptr; }

// The context's log callback, for calls on a live context.
rrc_log_fn log_of(const rrc_context* c) { return c ? c->config().log : nullptr; }
void* log_user_of(const rrc_context* c) { return c ? c->config().log_user : nullptr; }

// A context is externally synchronised (rrc.h, "Thread safety"): a call that
// finds another in progress on it (from a second thread, or from inside the
// first one's log callback) is refused and touches nothing of the context.
// The first call holds the context until its error is logged.
template <typename Body>
rrc_result on_context(rrc_context* c, Body&& body) {
    if (c && c->busy.exchange(true))
        return guarded(nullptr, log_of(c), log_user_of(c), [] {
            rrc::fail(RRC_ERROR_UNSUPPORTED,
                      "another call on this context is in progress (a second thread, or a call from its log callback): a context "
                      "is externally synchronised");
        });
    const rrc_result r = guarded(c, log_of(c), log_user_of(c), std::forward<Body>(body));
    if (c) c->busy = false;
    return r;
}

rrc::StandaloneContext& standalone(rrc_context* c) {
    if (!c->standalone) rrc::fail(RRC_ERROR_UNSUPPORTED, "this context was made by rrc_vulkan_context_create: use rrc_vulkan_record_frame");
    return *c->standalone;
}

// An entry point's frame: the live context or NULL, errors caught and
// logged (guarded), a NULL or dead handle refused; then `body(context)`.
template <typename Body>
rrc_result with_context(const rrc_context* context, Body&& body) {
    rrc_context* c = live_or_null(context);
    return on_context(c, [&] {
        checked(const_cast<rrc_context*>(context));
        body(c);
    });
}

// rrc_vulkan_record_frame and rrc_vulkan_record_resolve: a whole frame
// read and checked, then handed to `record` (standalone_call: the call a
// standalone context takes instead).
template <typename Record>
rrc_result record_vulkan_frame(rrc_context* context, const rrc_vulkan_frame_desc* frame, const char* standalone_call, Record record) {
    return with_context(context, [&](rrc_context* c) {
        if (!frame) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "frame is NULL");
        if (!c->interop) rrc::fail(RRC_ERROR_UNSUPPORTED, "this context runs standalone: use %s", standalone_call);
        const rrc::Frame f = rrc::read_frame(frame, c->config().channels.size());
        rrc::validate_frame(c->config(), f, nullptr, c->interop->stats_alignment());
        record(*c->interop, f);
    });
}

}  // namespace

extern "C" {

uint32_t rrc_get_version(void) { return RRC_API_VERSION; }

const char* rrc_result_to_string(rrc_result r) {
    switch (r) {
        case RRC_SUCCESS: return "RRC_SUCCESS";
        case RRC_ERROR_INVALID_ARGUMENT: return "RRC_ERROR_INVALID_ARGUMENT";
        case RRC_ERROR_INVALID_STRUCT: return "RRC_ERROR_INVALID_STRUCT";
        case RRC_ERROR_INCOMPATIBLE_VERSION: return "RRC_ERROR_INCOMPATIBLE_VERSION";
        case RRC_ERROR_UNSUPPORTED: return "RRC_ERROR_UNSUPPORTED";
        case RRC_ERROR_OUT_OF_MEMORY: return "RRC_ERROR_OUT_OF_MEMORY";
        case RRC_ERROR_DEVICE: return "RRC_ERROR_DEVICE";
        case RRC_ERROR_DEVICE_LOST: return "RRC_ERROR_DEVICE_LOST";
        case RRC_ERROR_MISSING_INPUT: return "RRC_ERROR_MISSING_INPUT";
        case RRC_ERROR_SIZE_MISMATCH: return "RRC_ERROR_SIZE_MISMATCH";
        case RRC_ERROR_INVALID_HANDLE: return "RRC_ERROR_INVALID_HANDLE";
        default: return "RRC_ERROR_UNKNOWN";
    }
}

const char* rrc_last_error(void) { return t_last_error.c_str(); }

// Presets (rrc.h, "Presets"): the row found and the caller's header read
// before anything is written.
rrc_result rrc_channel_preset(rrc_preset preset, uint32_t flags, uint32_t tuning, rrc_channel_desc* channel) {
    return guarded(nullptr, nullptr, nullptr, [&] {
        const rrc::PresetRow* row = rrc::find_preset(preset, flags, tuning);
        rrc::read_members<rrc_channel_desc>(channel, "channel");
        rrc::write_channel_preset(*row, channel);
    });
}

rrc_result rrc_context_preset(rrc_preset preset, uint32_t flags, uint32_t tuning, rrc_context_desc* context) {
    return guarded(nullptr, nullptr, nullptr, [&] {
        const rrc::PresetRow* row = rrc::find_preset(preset, flags, tuning);
        rrc::write_context_preset(*row, rrc::read_members<rrc_context_desc>(context, "context"), context);
    });
}

rrc_result rrc_vulkan_get_requirements(rrc_vulkan_requirements* out) {
    return guarded(nullptr, nullptr, nullptr, [&] {
        rrc::read_members<rrc_vulkan_requirements>(out, "out");
        const rrc_vulkan_requirements r = rrc::device_requirements();
        using R = rrc_vulkan_requirements;
        rrc::write_member(out, offsetof(R, api_version), r.api_version);
        rrc::write_member(out, offsetof(R, features), r.features);
        rrc::write_member(out, offsetof(R, device_extension_count), r.device_extension_count);
        rrc::write_member(out, offsetof(R, device_extensions), r.device_extensions);
        rrc::write_member(out, offsetof(R, max_per_stage_storage_images), r.max_per_stage_storage_images);
        rrc::write_member(out, offsetof(R, optional_instance_extension), r.optional_instance_extension);
    });
}

rrc_result rrc_validate_context_desc(const rrc_context_desc* desc) {
    return guarded(nullptr, nullptr, nullptr, [&] { rrc::resolve_context_desc(desc); });
}

rrc_result rrc_context_create(const rrc_context_desc* desc, rrc_context** out_context) {
    return guarded(nullptr, desc_log(desc), desc_log_user(desc), [&] {
        if (!out_context) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "out_context is NULL");
        rrc::ContextConfig config = rrc::resolve_context_desc(desc);
        const char* env = std::getenv("RRC_VALIDATION");
        if (env && std::strcmp(env, "1") == 0) config.validation = true;  // documented in rrc.h
        std::unique_ptr<rrc_context> ctx(new rrc_context);
        ctx->standalone.reset(new rrc::StandaloneContext(config));
        *out_context = publish(std::move(ctx));
    });
}

rrc_result rrc_vulkan_context_create(const rrc_context_desc* desc, const rrc_vulkan_device_desc* device, rrc_context** out_context) {
    return guarded(nullptr, desc_log(desc), desc_log_user(desc), [&] {
        if (!out_context) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "out_context is NULL");
        rrc::ContextConfig config = rrc::resolve_context_desc(desc);
        const rrc_vulkan_device_desc host = rrc::validate_vulkan_device_desc(device);
        const char* env = std::getenv("RRC_VALIDATION");
        if (env && std::strcmp(env, "1") == 0) config.validation = true;  // asked for: InteropContext says where it applies
        std::unique_ptr<rrc_context> ctx(new rrc_context);
        ctx->interop.reset(new rrc::InteropContext(config, host));
        *out_context = publish(std::move(ctx));
    });
}

void rrc_context_destroy(rrc_context* context) {
    if (!context) return;
    {
        std::lock_guard<std::mutex> lock(g_contexts_mutex);
        if (!live_contexts().erase(context)) return;  // destroyed twice or foreign: ignore, never free
    }
    try {
        delete context;
    } catch (...) {
    }
}

const char* rrc_context_last_error(const rrc_context* context) {
    if (!context || !is_live(context)) return "context is NULL or not a live rrc context";
    return context->last_error.c_str();
}

rrc_result rrc_context_device_name(const rrc_context* context, char* out_name, size_t capacity) {
    rrc_context* c = live_or_null(context);
    return on_context(c, [&] {
        checked(const_cast<rrc_context*>(context));
        if (!out_name) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "out_name is NULL");
        const std::string& name = c->device().name;
        if (capacity < name.size() + 1)
            rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "capacity is %zu, the name needs %zu bytes", capacity, name.size() + 1);
        std::memcpy(out_name, name.c_str(), name.size() + 1);
    });
}

rrc_result rrc_context_validation_messages(const rrc_context* context, uint64_t* out_count) {
    rrc_context* c = live_or_null(context);
    return on_context(c, [&] {
        checked(const_cast<rrc_context*>(context));
        if (!out_count) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "out_count is NULL");
        // The layer's messages about an interop context's commands go to the
        // host's own messenger: a count here would be 0 whatever happened.
        if (c->interop)
            rrc::fail(RRC_ERROR_UNSUPPORTED,
                      "an interop context cannot count validation messages: the layer reports to the host's own instance "
                      "(docs/guide/integration.md, \"What rrc checks and what it cannot\")");
        *out_count = c->device().validation_messages();
    });
}

rrc_result rrc_frame_run(rrc_context* context, const rrc_frame_desc* frame, rrc_frame_output* output) {
    return rrc_frame_run_batch(context, 1, frame, output);
}

rrc_result rrc_vulkan_record_frame(rrc_context* context, const rrc_vulkan_frame_desc* frame) {
    return record_vulkan_frame(context, frame, "rrc_frame_run", [](rrc::InteropContext& ctx, const rrc::Frame& f) { ctx.record_frame(f); });
}

rrc_result rrc_frame_classify(rrc_context* context, const rrc_frame_desc* frame, rrc_classify_output* output) {
    return with_context(context, [&](rrc_context* c) {
        rrc::StandaloneContext& s = standalone(c);
        if (!frame) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "frame is NULL");
        const rrc::Frame f = rrc::read_frame(frame, 0);  // channels are not read
        rrc::validate_geometry(c->config(), f, 0);
        rrc::StandaloneContext::Classified out;
        if (output) {
            const rrc_classify_output o = rrc::read_struct<rrc_classify_output>(output, "output");
            out = {output, o.mask, o.quads, o.quad_capacity};
            if (o.quads && o.quad_capacity == 0) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "output.quads is set with quad_capacity 0");
        }
        s.classify(f, out);
    });
}

rrc_result rrc_frame_resolve(rrc_context* context, const rrc_resolve_desc* resolve, rrc_frame_output* output) {
    return with_context(context, [&](rrc_context* c) {
        rrc::StandaloneContext& s = standalone(c);
        if (!resolve) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "resolve is NULL");
        const rrc::Frame f = rrc::read_resolve(resolve, c->config().channels.size());
        rrc::validate_channels(c->config(), f);
        const rrc::FrameOutputs out = rrc::read_outputs(output, c->config().channels.size());
        rrc::validate_outputs(c->config(), &out);
        s.resolve(f, out);
    });
}

rrc_result rrc_vulkan_record_classify(rrc_context* context, const rrc_vulkan_frame_desc* frame, const rrc_vulkan_quad_list* list) {
    return with_context(context, [&](rrc_context* c) {
        if (!frame) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "frame is NULL");
        if (!c->interop) rrc::fail(RRC_ERROR_UNSUPPORTED, "this context runs standalone: use rrc_frame_classify");
        const rrc::Frame f = rrc::read_frame(frame, c->config().channels.size());
        rrc::validate_geometry(c->config(), f, c->interop->stats_alignment());
        // With split_outputs a shading cache's classify writes the host's outputs at the HITs.
        if (f.split_outputs && rrc::all_reuse(c->config())) rrc::validate_channels(c->config(), f);
        const rrc_vulkan_quad_list l = rrc::read_struct<rrc_vulkan_quad_list>(list, "list");
        if (!l.buffer) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "list.buffer is VK_NULL_HANDLE");
        if (l.buffer_size)
            rrc::check_range("list.offset", l.offset, RRC_QUAD_LIST_BYTES(c->config().width, c->config().height), "list.buffer_size",
                             l.buffer_size, "the quad list (RRC_QUAD_LIST_BYTES)");
        if (c->interop->stats_alignment() && l.offset % c->interop->stats_alignment() != 0)
            rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "list.offset is %llu, not a multiple of the device's minStorageBufferOffsetAlignment %llu",
                      (unsigned long long)l.offset, (unsigned long long)c->interop->stats_alignment());
        c->interop->record_classify(f, l.buffer, l.offset);
    });
}

rrc_result rrc_vulkan_record_resolve(rrc_context* context, const rrc_vulkan_frame_desc* frame) {
    return record_vulkan_frame(context, frame, "rrc_frame_resolve",
                               [](rrc::InteropContext& ctx, const rrc::Frame& f) { ctx.record_resolve(f); });
}

rrc_result rrc_context_memory_usage(const rrc_context* context, uint64_t* out_bytes) {
    rrc_context* c = live_or_null(context);
    return on_context(c, [&] {
        checked(const_cast<rrc_context*>(context));
        if (!out_bytes) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "out_bytes is NULL");
        *out_bytes = c->standalone ? c->standalone->memory_bytes() : c->interop->memory_bytes();
    });
}

rrc_result rrc_get_memory_usage(const rrc_context* context, uint64_t* out_bytes) { return rrc_context_memory_usage(context, out_bytes); }

rrc_result rrc_frame_run_batch(rrc_context* context, uint32_t count, const rrc_frame_desc* frames, rrc_frame_output* outputs) {
    rrc_context* c = live_or_null(context);
    return on_context(c, [&] {
        checked(context);
        const rrc::ContextConfig& config = c->config();
        if (count == 0) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "count is 0");
        if (count > 65536) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "count is %u, at most 65536 frames a batch", count);
        if (!frames) rrc::fail(RRC_ERROR_INVALID_ARGUMENT, "frame%s is NULL", count == 1 ? "" : "s");
        // Frames and outputs are arrays of tagged structs: strided by their
        // first element's size (rrc.h Versioning, rule 3).
        std::vector<rrc::Frame> f;
        std::vector<rrc::FrameOutputs> out;
        for (uint32_t i = 0; i < count; ++i) {
            try {
                const rrc_frame_desc* frame = rrc::strided_element(frames, i, "frames", "frame");
                rrc_frame_output* output = outputs ? rrc::strided_element(outputs, i, "outputs", "output") : nullptr;
                f.push_back(rrc::read_frame(frame, config.channels.size()));
                out.push_back(rrc::read_outputs(output, config.channels.size()));
                rrc::validate_frame(config, f.back(), &out.back(), 0);
            } catch (const rrc::Error& e) {
                if (count == 1) throw;
                throw rrc::Error(e.code, "frames[" + std::to_string(i) + "]: " + e.what());
            }
        }
        standalone(c).run_frames(f, out);
    });
}

}  // extern "C"
