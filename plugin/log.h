// The host's log callback, and the formatting every part of the library uses.
#pragma once

#include <rrc/rrc.h>

#include <string>

namespace rrc {

struct Log {
    rrc_log_fn fn = nullptr;
    void* user = nullptr;
    void operator()(rrc_log_level level, const std::string& message) const {
        if (fn) fn(user, level, message.c_str());
    }
};

}  // namespace rrc
