// rrc-bench: rrc's kernel timed against its roof (docs/measurements/PERFORMANCE.md).
// Public headers only (include/rrc/) plus the host bootstrap of
// host_sample/common, as any engine would use the library.
#include "analysis.h"
#include "rrc_interop.h"
#include "bench_images.h"
#include "config.h"
#include "interop_run.h"
#include "options.h"
#include "options_parser.h"
#include "report.h"
#include "result.h"
#include "run_info.h"
#include "scene.h"
#include "standalone_run.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>

using namespace rrc_bench;

namespace {

std::vector<Config> selected(const Options& o) {
    std::vector<Config> all = full_sweep(), out;
    std::vector<std::string> names = o.configs;
    if (names.empty() && !o.full) names = short_sweep_names();
    for (const std::string& n : names) {
        bool known = false;
        for (const Config& c : all) known |= n == c.name;
        if (!known) throw std::runtime_error("option --config '" + n + "': unknown configuration (rrc-bench --list names them)");
    }
    for (const Config& c : all) {
        bool take = names.empty();
        for (const std::string& n : names) take |= n == c.name;
        if (take) out.push_back(c);
    }
    if (o.nocache_share >= 0)
        for (Config& c : out)
            if (c.young) c.nocache_share = o.nocache_share;
    if (o.width)
        for (Config& c : out) {
            c.width = o.width;
            c.height = o.height;
        }
    return out;
}

bool young_sensitive(const Config& c) {
    bool fill = false;
    for (const ChannelConfig& ch : c.channels) fill |= ch.fill_age != 0;
    return fill || c.young;
}

// One configuration's inputs, images and contexts, alive for the whole run.
struct Job {
    Config config;
    std::unique_ptr<SceneInputs> scene;
    BenchImages images;
    std::unique_ptr<StandaloneBench> standalone;
    std::unique_ptr<InteropBench> interop;
};

// Frees a scene's per-pixel arrays, keeping the camera matrices: with every
// configuration alive at once (--full) they would otherwise double the memory.
void drop_arrays(SceneInputs& s) {
    for (PoseFrame& p : s.poses) {
        std::vector<float>().swap(p.depth);
        std::vector<float>().swap(p.reprojection);
        std::vector<uint32_t>().swap(p.object_id);
    }
    std::vector<std::vector<float>>().swap(s.samples);
    std::vector<std::vector<float>>().swap(s.confidence);
    std::vector<uint8_t>().swap(s.nocache);
}

// Every configuration is set up first, then the repetitions go round all of
// them (rep-major): a shared machine's drift hits every row alike, so times
// of different rows (the CAMERA/MOTION and linearity targets) compare
// repetition by repetition, not only the kernel/roof pairs within a row.
std::vector<Row> measure_all(VulkanBootstrap& vk, const std::vector<Config>& configs, const Options& opt, int reps, LogCounter& log) {
    std::vector<Job> jobs(configs.size());
    const double start = now_ms();
    auto cleanup = [&]() {
        for (Job& j : jobs) {
            j.interop.reset();
            j.standalone.reset();
            destroy_images(vk, j.images);
        }
    };
    std::vector<Row> rows;
    try {
        for (size_t i = 0; i < configs.size(); ++i) {
            Job& j = jobs[i];
            j.config = configs[i];
            std::fprintf(stderr, "rrc-bench: set up [%zu/%zu] %s (%ux%u, %s)\n", i + 1, configs.size(), j.config.name.c_str(),
                         j.config.width, j.config.height, channels_text(j.config).c_str());
            j.scene = std::make_unique<SceneInputs>(make_scene(j.config));
            if (j.config.standalone) j.standalone = std::make_unique<StandaloneBench>(j.config, *j.scene, log, opt.device, opt.validation);
            j.images = create_images(vk, j.config, *j.scene);
            j.interop = std::make_unique<InteropBench>(vk, j.config, *j.scene, j.images, log);
            // A pixel is young until kYoungAge frames of history: before that the
            // fill works on every surface pixel, so rows whose cost depends on the
            // young fraction start from a steady state (docs/measurements/PERFORMANCE.md, "What is timed").
            if (young_sensitive(j.config)) j.interop->prime((int)kYoungAge);
            if (!j.standalone) drop_arrays(*j.scene);  // on the device now; the interop frames need only the matrices
        }
        for (int r = -opt.warmup; r < reps; ++r) {
            const bool record = r >= 0;
            for (Job& j : jobs) {
                j.interop->step(record);
                if (j.standalone) j.standalone->step(record);
            }
            std::fprintf(stderr, "rrc-bench: %s %d/%d done (%.0f s so far)\n", record ? "repetition" : "warm-up", record ? r + 1 : r + opt.warmup + 1,
                         record ? reps : opt.warmup, (now_ms() - start) / 1000.0);
        }
        for (Job& j : jobs) {
            Row row;
            row.config = j.config;
            row.api_bytes = roof_bytes_from_api(j.config);
            row.interop = j.interop->finish(opt.check_roof || opt.validation);
            if (j.standalone) {
                row.has_standalone = true;
                row.standalone = j.standalone->result();
            }
            std::fprintf(stderr, "rrc-bench: %-18s kernel %.2f ms, roof %.2f ms, ratio %.3f\n", j.config.name.c_str(), row.kernel().median,
                         row.roof().median, row.ratio().median);
            rows.push_back(std::move(row));
        }
    } catch (...) {
        cleanup();
        throw;
    }
    cleanup();
    return rows;
}

// bench/plot.py needs python3 with matplotlib; without them the run still
// succeeds.  The first python3 on PATH may be a virtual environment or
// pyenv without it while the system's has it (Debian: python3-matplotlib).
void plot(const Options& opt, const std::string& json, const std::string& png) {
    if (!opt.plot) return;
    std::string python;
    for (const char* candidate : {"python3", "/usr/bin/python3"}) {
        const std::string probe = std::string(candidate) + " -c 'import matplotlib' >/dev/null 2>&1";
        if (std::system(probe.c_str()) == 0) {
            python = candidate;
            break;
        }
    }
    if (python.empty()) {
        std::fprintf(stderr, "rrc-bench: no plot: python3 with matplotlib not found (Debian: python3-matplotlib)\n");
        return;
    }
    const std::string cmd = python + " \"" + opt.plot_script + "\" \"" + json + "\" \"" + png + "\"";
    if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "rrc-bench: %s failed\n", cmd.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse_options(argc, argv);
    try {
        if (opt.configs.size() == 1 && opt.configs[0] == "list") {
            const auto quick = short_sweep_names();
            for (const Config& c : full_sweep()) {
                bool in_short = false;
                for (const std::string& n : quick) in_short |= n == c.name;
                std::printf("%-20s %-11s %s\n", c.name.c_str(), c.factor.c_str(), in_short ? "(default run)" : "");
            }
            return 0;
        }
        const std::vector<Config> configs = selected(opt);
        if (opt.check_options) {
            rrc_host::print_options_ok("rrc-bench");
            return 0;
        }
        RunInfo info;
        info.command = opt.command_line;
        info.reps = opt.reps ? opt.reps : opt.full ? 15 : 9;
        info.warmup = opt.warmup;
        info.validation = opt.validation;
        info.size_override = opt.width != 0;
        info.commit = source_commit();
        info.date = utc_now();
        info.cpu = cpu_description();
        info.load_start = load_average();

        rrc_host::BootstrapOptions bo;
        bo.application = "rrc-bench";
        bo.validation = opt.validation;
        bo.device_name = opt.device;
        bo.features = rrc_host::rrc_features();  // what rrc needs (rrc_vulkan_get_requirements)
        VulkanBootstrap vk(bo);
        info.device = vk.device_name();
        std::fprintf(stderr, "rrc-bench: %s, commit %s, %zu configuration(s), %d repetitions each\n", info.device.c_str(),
                     info.commit.c_str(), configs.size(), info.reps);
        if (!vk.timestamps) std::fprintf(stderr, "rrc-bench: the device has no timestamps: GPU times are wall clock of each submission\n");

        LogCounter log;
        const double start = now_ms();
        const std::vector<Row> rows = measure_all(vk, configs, opt, info.reps, log);
        bool bookkeeping_ok = true, roof_ok = true;
        for (const Row& r : rows) {
            const Config& c = r.config;
            if (r.interop.roof_bytes_bound.read != r.api_bytes.read || r.interop.roof_bytes_bound.written != r.api_bytes.written) {
                std::fprintf(stderr, "rrc-bench: %s: the roof binds %llu+%llu bytes, the API implies %llu+%llu\n", c.name.c_str(),
                             (unsigned long long)r.interop.roof_bytes_bound.read, (unsigned long long)r.interop.roof_bytes_bound.written,
                             (unsigned long long)r.api_bytes.read, (unsigned long long)r.api_bytes.written);
                bookkeeping_ok = false;
            }
            if (r.interop.roof_check != "skipped" && !r.interop.roof_check.empty()) {
                std::fprintf(stderr, "rrc-bench: %s: the roof's outputs are not copies of its inputs: %s\n", c.name.c_str(),
                             r.interop.roof_check.c_str());
                roof_ok = false;
            }
        }
        info.load_end = load_average();
        info.validation_messages = vk.message_count() + log.messages;
        for (const Row& r : rows) info.validation_messages += r.standalone.validation_messages;

        // With --size every row has the same size: there is no line to fit.
        const Linearity lin = info.size_override ? Linearity{} : analyze_linearity(rows);
        const std::vector<Target> targets = evaluate_targets(rows, lin);
        print_table(rows);
        std::printf("\n");
        for (const Target& t : targets)
            std::printf("target %-16s %-12s %s%s%s\n", t.name.c_str(), t.status.c_str(), t.measured.c_str(), t.margin.empty() ? "" : "; ",
                        t.margin.c_str());

        std::filesystem::create_directories(opt.out);
        const std::string json = opt.out + "/bench.json";
        write_csv(opt.out + "/bench.csv", rows);
        write_json(json, info, rows, lin, targets);
        write_markdown(opt.out + "/report.md", info, rows, lin, targets);
        plot(opt, json, opt.out + "/bench.png");
        std::fprintf(stderr, "rrc-bench: wrote %s/{bench.csv,bench.json,report.md} in %.0f s\n", opt.out.c_str(), (now_ms() - start) / 1000.0);

        if (opt.validation && info.validation_messages) {
            for (const std::string& m : vk.messages()) std::fprintf(stderr, "validation: %s\n", m.c_str());
            std::fprintf(stderr, "rrc-bench: %llu validation message(s)\n", (unsigned long long)info.validation_messages);
            return 1;
        }
        if (!bookkeeping_ok || !roof_ok) return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nrrc-bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
