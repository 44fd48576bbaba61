// libFuzzer target: the EXR reading of rrc-accumulate (host_sample/common/exr_io.cpp),
// which refuses what OpenEXR's own checkers refuse before decoding anything.
// Each input is presented as a file (an in-memory memfd, reached by its
// /proc/self/fd path) to every reading entry point; each must return or throw
// rrc_exr::ExrError naming the file, never crash, leak or read out of bounds.
#include "exr_io.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>

namespace {

// One memfd for the whole run, rewritten for each input.
const std::string& input_path() {
    static const std::string path = [] {
        int fd = memfd_create("rrc_fuzz_exr", 0);
        if (fd < 0) std::abort();
        return "/proc/self/fd/" + std::to_string(fd);
    }();
    return path;
}

void write_input(const uint8_t* data, size_t size) {
    const std::string& path = input_path();
    int fd = std::stoi(path.substr(path.rfind('/') + 1));
    if (ftruncate(fd, 0) != 0) std::abort();
    size_t done = 0;
    while (done < size) {
        ssize_t n = pwrite(fd, data + done, size - done, (off_t)done);
        if (n <= 0) std::abort();
        done += (size_t)n;
    }
}

template <typename F>
void expect_clean(F&& read) {
    try {
        read();
    } catch (const rrc_exr::ExrError& e) {
        if (e.path() != input_path() || std::string(e.what()).find(input_path()) == std::string::npos) std::abort();
    }
    // Any other exception escapes and libFuzzer reports it as a crash.
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    rrc_exr::set_thread_count(0);  // deterministic, and no worker threads to leak
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    write_input(data, size);
    const std::string& path = input_path();
    expect_clean([&] { rrc_exr::read_exr_info(path); });
    expect_clean([&] { rrc_exr::verify_exr_chunks(path); });
    expect_clean([&] { rrc_exr::channel_names(path); });
    expect_clean([&] {
        rrc_exr::ExrImage image = rrc_exr::read_exr(path);
        // What was decoded is what the header promised.
        for (const auto& c : image.channels)
            if (c.second.size() != image.pixel_count()) std::abort();
        for (const auto& c : image.uint_channels)
            if (c.second.size() != image.pixel_count()) std::abort();
    });
    return 0;
}
