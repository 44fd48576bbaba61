// rrc-accumulate: the main loop.
#include "accumulate.h"

#include "sequence.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <new>
#include <set>
#include <thread>
#include <utility>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/stat.h>
#define RRC_CLI_HAVE_STAT 1
#endif

namespace fs = std::filesystem;

namespace rrc_cli {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Every rrc_ call goes through here: "RRC_ERROR_X : message".
void check(rrc_result r)
{
    if (r != RRC_SUCCESS)
        throw CliError(std::string(rrc_result_to_string(r)) + " : " + rrc_last_error());
}

std::string normalised(const std::string& p)
{
    std::error_code ec;
    fs::path abs = fs::absolute(p, ec);
    if (ec)
        return fs::path(p).lexically_normal().string();
    fs::path canon = fs::weakly_canonical(abs, ec);
    return (ec ? abs : canon).lexically_normal().string();
}

struct LogSink {
    std::ostream* err;
    bool verbose;
};

void log_to_stream(void* user, rrc_log_level level, const char* message)
{
    const LogSink* sink = static_cast<const LogSink*>(user);
    // Errors are also returned (and printed once by check()): only verbose shows both.
    if ((level == RRC_LOG_INFO || level == RRC_LOG_ERROR) && !sink->verbose)
        return;
    const char* tag = level == RRC_LOG_INFO      ? "info"
                      : level == RRC_LOG_WARNING ? "warning"
                      : level == RRC_LOG_ERROR   ? "error"
                                                 : "validation";
    *sink->err << "rrc-accumulate: [" << tag << "] " << (message ? message : "") << "\n";
}

struct ContextDeleter {
    void operator()(rrc_context* c) const { rrc_context_destroy(c); }
};

std::string format(const char* fmt, double a, double b = 0, double c = 0)
{
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

rrc_exr::ExrInfo header_of(const std::string& path)
{
    try {
        return rrc_exr::read_exr_info(path);
    } catch (const rrc_exr::ExrError& e) {
        throw CliError(e.what());
    }
}

} // namespace

void check_no_overwrite(const Options& o)
{
    std::map<std::string, std::string> inputs; // normalised -> as given
#ifdef RRC_CLI_HAVE_STAT
    std::map<std::pair<dev_t, ino_t>, std::string> input_ids;
#endif
    auto add_input = [&](const std::string& p) {
        inputs.emplace(normalised(p), p);
#ifdef RRC_CLI_HAVE_STAT
        struct stat st;
        if (::stat(p.c_str(), &st) == 0)
            input_ids.emplace(std::make_pair(st.st_dev, st.st_ino), p);
#endif
    };
    for (int64_t f = o.first_frame; f <= o.last_frame; ++f)
        add_input(format_frame_path(o.input_pattern, f));
    if (!o.camera_file.empty())
        add_input(o.camera_file);

    for (int64_t f = o.first_frame; f <= o.last_frame; ++f) {
        const std::string out = format_frame_path(o.output_pattern, f);
        std::string clash;
        if (auto it = inputs.find(normalised(out)); it != inputs.end())
            clash = it->second;
#ifdef RRC_CLI_HAVE_STAT
        struct stat st;
        if (clash.empty() && ::stat(out.c_str(), &st) == 0)
            if (auto it = input_ids.find(std::make_pair(st.st_dev, st.st_ino)); it != input_ids.end())
                clash = it->second;
#endif
        if (!clash.empty())
            throw CliError("output '" + out + "' (frame " + std::to_string(f) + ") is the input '" + clash +
                           "'; inputs are never overwritten: choose another --output");
    }
}

int run_accumulate(const Options& o, std::ostream& out, std::ostream& err)
{
    LogSink sink{&err, o.verbose};
    std::unique_ptr<rrc_context, ContextDeleter> context;
    try {
        const auto t_start = Clock::now();
        rrc_exr::set_thread_count(static_cast<int>(std::min(16u, std::thread::hardware_concurrency())));

        // 1. Everything that can be checked before processing.
        const std::string first_path = format_frame_path(o.input_pattern, o.first_frame);
        const rrc_exr::ExrInfo first_info = header_of(first_path);
        const SequenceLayout layout = discover_layout(first_info, first_path, o);
        for (int64_t f = o.first_frame; f <= o.last_frame; ++f) {
            const std::string path = format_frame_path(o.input_pattern, f);
            check_frame_header(f == o.first_frame ? first_info : header_of(path), path, layout);
        }
        check_no_overwrite(o);
        std::map<int64_t, CameraFrame> cameras;
        if (!o.camera_file.empty())
            cameras = load_camera_file(o.camera_file, o.first_frame, o.last_frame,
                                       layout.reprojection == RRC_REPROJECTION_CAMERA);

        std::vector<rrc_channel_desc> channel_descs;
        rrc_context_desc desc = make_context_desc(o, layout, channel_descs);
        desc.log = &log_to_stream;
        desc.log_user = &sink;
        check(rrc_validate_context_desc(&desc));

        // 2. The context.
        rrc_context* raw = nullptr;
        check(rrc_context_create(&desc, &raw));
        context.reset(raw);
        char device[256] = {0};
        check(rrc_context_device_name(context.get(), device, sizeof device));

        // 3. The frames.
        const std::size_t n = static_cast<std::size_t>(layout.width) * static_cast<std::size_t>(layout.height);
        const std::size_t k = layout.signals.size();
        CameraFrame previous_camera;
        double ratio_sum = 0.0;
        int64_t ratio_count = 0, processed = 0;
        for (int64_t f = o.first_frame; f <= o.last_frame; ++f) {
            const auto t_frame = Clock::now();
            const std::string in_path = format_frame_path(o.input_pattern, f);
            const std::string out_path = format_frame_path(o.output_pattern, f);

            rrc_exr::ExrImage image;
            try {
                image = rrc_exr::read_exr(in_path);
            } catch (const rrc_exr::ExrError& e) {
                throw CliError(e.what());
            }
            for (const RequiredChannel& r : required_channels(layout))
                if (!image.has(r.name))
                    throw CliError(in_path + ": missing channel '" + r.name + "' (" + r.reason + ")");
            const FrameData data = load_frame(image, in_path, layout);

            CameraFrame camera;
            if (auto it = cameras.find(f); it != cameras.end())
                camera = it->second;
            if (f == o.first_frame)
                previous_camera = camera;

            std::vector<rrc_channel_input> inputs(k);
            for (std::size_t s = 0; s < k; ++s) {
                inputs[s] = rrc_channel_input{};
                inputs[s].type = RRC_STRUCT_TYPE_CHANNEL_INPUT;
                inputs[s].size = sizeof(rrc_channel_input);
                inputs[s].samples = data.samples[s].data();
                inputs[s].confidence = layout.signals[s].confidence ? data.confidence[s].data() : nullptr;
            }
            rrc_frame_desc frame{};
            frame.type = RRC_STRUCT_TYPE_FRAME_DESC;
            frame.size = sizeof(rrc_frame_desc);
            frame.frame_index = static_cast<uint64_t>(f);
            frame.reset = 0;
            frame.depth = data.depth.data();
            frame.reprojection = data.reprojection.empty() ? nullptr : data.reprojection.data();
            for (int i = 0; i < 16; ++i) {
                frame.view_proj[i] = camera.view_proj[i];
                frame.prev_view_proj[i] = previous_camera.view_proj[i];
            }
            frame.jitter[0] = camera.jitter[0];
            frame.jitter[1] = camera.jitter[1];
            frame.prev_jitter[0] = previous_camera.jitter[0];
            frame.prev_jitter[1] = previous_camera.jitter[1];
            frame.nocache = layout.nocache ? data.nocache.data() : nullptr;
            frame.channel_count = static_cast<uint32_t>(k);
            frame.channels = inputs.data();

            FrameResult result;
            result.values.resize(k);
            result.age.resize(k);
            result.weight.resize(k);
            result.mask.assign(n, 0);
            std::vector<rrc_channel_output> outputs(k);
            for (std::size_t s = 0; s < k; ++s) {
                result.values[s].assign(n * layout.signals[s].rrc_components, 0.0f);
                result.age[s].assign(n, 0);
                if (layout.signals[s].confidence)
                    result.weight[s].assign(n, 0.0f);
                outputs[s] = rrc_channel_output{};
                outputs[s].type = RRC_STRUCT_TYPE_CHANNEL_OUTPUT;
                outputs[s].size = sizeof(rrc_channel_output);
                outputs[s].values = result.values[s].data();
                outputs[s].age = result.age[s].data();
                outputs[s].weight = layout.signals[s].confidence ? result.weight[s].data() : nullptr;
            }
            rrc_frame_output output{};
            output.type = RRC_STRUCT_TYPE_FRAME_OUTPUT;
            output.size = sizeof(rrc_frame_output);
            output.mask = result.mask.data();
            output.channel_count = static_cast<uint32_t>(k);
            output.channels = outputs.data();

            const auto t_run = Clock::now();
            check(rrc_frame_run(context.get(), &frame, &output));
            const double run_ms = ms_since(t_run);

            const fs::path out_dir = fs::path(out_path).parent_path();
            std::error_code ec;
            if (!out_dir.empty() && !fs::is_directory(out_dir, ec)) {
                fs::create_directories(out_dir, ec);
                if (ec)
                    throw CliError("cannot create the output directory '" + out_dir.string() + "': " + ec.message());
            }
            try {
                rrc_exr::write_exr(out_path, make_output_image(layout, result));
            } catch (const rrc_exr::ExrError& e) {
                throw CliError(e.what());
            }

            const rrc_frame_stats& st = output.stats;
            const uint64_t tested = st.hits + st.misses;
            const double ratio = tested ? 100.0 * static_cast<double>(st.hits) / static_cast<double>(tested) : 0.0;
            if (f != o.first_frame && tested) {
                ratio_sum += ratio;
                ++ratio_count;
            }
            ++processed;
            if (!o.quiet) {
                out << "frame " << f << ": hit " << (tested ? format("%.1f%%", ratio) : std::string("n/a"))
                    << format(", %.2f ms (rrc_frame_run), %.1f ms total", run_ms, ms_since(t_frame));
                if (st.invalid_samples || st.invalid_geometry)
                    out << ", " << st.invalid_samples << " invalid samples, " << st.invalid_geometry
                        << " invalid geometry";
                out << "\n" << std::flush;
            }
            previous_camera = camera;
        }

        // Also counts when validation came from RRC_VALIDATION=1 in the environment.
        uint64_t validation_messages = 0;
        check(rrc_context_validation_messages(context.get(), &validation_messages));
        out << "rrc-accumulate: " << processed << (processed == 1 ? " frame" : " frames") << ", mean hit ratio "
            << (ratio_count ? format("%.1f%%", ratio_sum / static_cast<double>(ratio_count)) : std::string("n/a"))
            << " (frames after the first)" << format(", total %.2f s", ms_since(t_start) / 1000.0)
            << ", device " << device;
        if (o.validation || validation_messages)
            out << ", " << validation_messages << " validation messages";
        out << "\n" << std::flush;
        context.reset();
        if (validation_messages) {
            err << "rrc-accumulate: the validation layer reported " << validation_messages << " message(s)\n";
            return kExitError;
        }
        return kExitOk;
    } catch (const std::bad_alloc&) {
        context.reset();
        err << "rrc-accumulate: out of memory\n";
    } catch (const std::exception& e) {
        context.reset();
        err << "rrc-accumulate: " << e.what() << "\n";
    }
    return kExitError;
}

int accumulate_main(int argc, const char* const* argv, std::ostream& out, std::ostream& err)
{
    if (argc <= 1) {
        err << usage_text();
        return kExitUsage;
    }
    const ParseResult parsed = parse_arguments(argc, argv);
    if (!parsed.ok()) {
        err << "rrc-accumulate: " << parsed.error << "\n";
        return kExitUsage;
    }
    if (parsed.options.help) {
        out << usage_text();
        return kExitOk;
    }
    return run_accumulate(parsed.options, out, err);
}

} // namespace rrc_cli
