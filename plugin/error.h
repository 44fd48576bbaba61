// Internal error type: thrown inside the library, caught at the C boundary
// (api.cpp) and turned into an rrc_result plus a message.  Never escapes.
#pragma once

#include <rrc/rrc.h>

#include <cstdio>
#include <stdexcept>
#include <string>

namespace rrc {

struct Error : std::runtime_error {
    rrc_result code;
    Error(rrc_result c, const std::string& message) : std::runtime_error(message), code(c) {}
};

// printf-style: fail(RRC_ERROR_INVALID_ARGUMENT, "desc.width is %u", w)
template <typename... Args>
[[noreturn]] void fail(rrc_result code, const char* format, Args... args) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, format, args...);
    throw Error(code, buffer);
}

}  // namespace rrc
