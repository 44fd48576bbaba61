// rrc-bench: rrc's kernel timed against its roof (docs/PERFORMANCE.md).
// Public headers only (include/rrc/) plus the host bootstrap of
// host_sample/common, as any engine would use the library.
#include "bench_images.h"
#include "config.h"
#include "interop_run.h"
#include "options.h"
#include "scene.h"
#include "stats.h"

#include <cstdio>
#include <exception>

using namespace rrc_bench;

namespace {

std::vector<Config> selected(const Options& o) {
    std::vector<Config> all = full_sweep(), out;
    std::vector<std::string> names = o.configs;
    if (names.empty() && !o.full) names = short_sweep_names();
    for (const Config& c : all) {
        bool take = names.empty();
        for (const std::string& n : names) take |= n == c.name;
        if (take) out.push_back(c);
    }
    for (const std::string& n : names) {
        bool known = false;
        for (const Config& c : all) known |= n == c.name;
        if (!known) throw std::runtime_error("unknown configuration \"" + n + "\" (rrc-bench --list names them)");
    }
    if (o.width)
        for (Config& c : out) {
            c.width = o.width;
            c.height = o.height;
        }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse_options(argc, argv);
    try {
        if (opt.configs.size() == 1 && opt.configs[0] == "list") {
            for (const Config& c : full_sweep()) std::printf("%-20s %s\n", c.name.c_str(), c.factor.c_str());
            return 0;
        }
        const std::vector<Config> configs = selected(opt);
        const int reps = opt.reps ? opt.reps : opt.full ? 15 : 9;
        rrc_host::BootstrapOptions bo;
        bo.application = "rrc-bench";
        bo.validation = opt.validation;
        bo.device_name = opt.device;
        VulkanBootstrap vk(bo);
        std::fprintf(stderr, "rrc-bench: %s, %zu configuration(s), %d repetitions each\n", vk.device_name().c_str(), configs.size(), reps);
        LogCounter log;
        std::printf("%-20s %10s %9s %9s %7s\n", "config", "size", "kernel ms", "roof ms", "ratio");
        for (const Config& c : configs) {
            std::fprintf(stderr, "rrc-bench: %s (%ux%u)...\n", c.name.c_str(), c.width, c.height);
            const SceneInputs scene = make_scene(c);
            BenchImages images = create_images(vk, c, scene);
            const InteropResult r = run_interop(vk, c, scene, images, log, reps, opt.warmup, opt.check_roof || opt.validation);
            destroy_images(vk, images);
            const Summary k = summarize(r.kernel_ms), t = summarize(r.roof_ms), q = summarize(r.ratio);
            std::printf("%-20s %4ux%-5u %9.3f %9.3f %7.3f\n", c.name.c_str(), c.width, c.height, k.median, t.median, q.median);
            std::fflush(stdout);
            if (!r.roof_check.empty() && r.roof_check != "skipped") throw std::runtime_error("roof check failed: " + r.roof_check);
        }
        const uint64_t messages = vk.message_count() + log.messages;
        if (opt.validation && messages) {
            for (const std::string& m : vk.messages()) std::fprintf(stderr, "validation: %s\n", m.c_str());
            std::fprintf(stderr, "rrc-bench: %llu validation message(s)\n", (unsigned long long)messages);
            return 1;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rrc-bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
