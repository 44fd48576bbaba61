#include "run_info.h"

#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#ifndef RRC_BENCH_SOURCE_DIR
#define RRC_BENCH_SOURCE_DIR "."
#endif

namespace rrc_bench {

std::string source_commit() {
    FILE* p = popen("git -C \"" RRC_BENCH_SOURCE_DIR "\" describe --always --dirty --abbrev=12 2>/dev/null", "r");
    if (!p) return "unknown";
    char buf[128] = {};
    const bool got = std::fgets(buf, sizeof buf, p) != nullptr;
    pclose(p);
    std::string s = got ? buf : "";
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s.empty() ? "unknown" : s;
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    char s[32];
    std::strftime(s, sizeof s, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return s;
}

std::string cpu_description() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos) model = line.substr(colon + 2);
            break;
        }
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " CPUs";
}

double load_average() {
    std::ifstream in("/proc/loadavg");
    double one = -1.0;
    in >> one;
    return one;
}

}  // namespace rrc_bench
