// The rrc context descriptor of a configuration, the same for the interop
// and the standalone path (so both time the same kernel), and a log sink
// that counts what the library reports.
#pragma once

#include "config.h"

#include <atomic>
#include <vector>

namespace rrc_bench {

/** Counts rrc's warnings, errors and validation messages (the smoke test fails on any). */
struct LogCounter {
    std::atomic<uint64_t> messages{0};
    static void callback(void* user, rrc_log_level level, const char* message);
};

class ContextSetup {
public:
    ContextSetup(const Config& config, LogCounter& log);
    /** The descriptor (its channels point into this object: keep it alive during create). */
    const rrc_context_desc* desc() {
        desc_.channels = channels_.data();
        return &desc_;
    }

private:
    std::vector<rrc_channel_desc> channels_;
    rrc_context_desc desc_;
};

}  // namespace rrc_bench
