// rrc-accumulate: the main loop.
#include "accumulate.h"

#include "clean_report.h"
#include "sequence.h"

#include <png_io.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <set>
#include <thread>
#include <utility>

#if defined(__unix__) || defined(__APPLE__)
#    include <sys/stat.h>
#    define RRC_CLI_HAVE_STAT 1
#endif

namespace fs = std::filesystem;

namespace rrc_cli {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Every rrc_ call goes through here: "RRC_ERROR_X : message".
void check(rrc_result r) {
    if (r != RRC_SUCCESS) throw CliError(std::string(rrc_result_to_string(r)) + " : " + rrc_last_error());
}

std::string normalised(const std::string& p) {
    std::error_code ec;
    fs::path abs = fs::absolute(p, ec);
    if (ec) return fs::path(p).lexically_normal().string();
    fs::path canon = fs::weakly_canonical(abs, ec);
    return (ec ? abs : canon).lexically_normal().string();
}

struct LogSink {
    std::ostream* err;
    bool verbose;
};

void log_to_stream(void* user, rrc_log_level level, const char* message) {
    const LogSink* sink = static_cast<const LogSink*>(user);
    // Errors are also returned (and printed once by check()): only verbose shows both.
    if ((level == RRC_LOG_INFO || level == RRC_LOG_ERROR) && !sink->verbose) return;
    const char* tag = level == RRC_LOG_INFO      ? "info"
                      : level == RRC_LOG_WARNING ? "warning"
                      : level == RRC_LOG_ERROR   ? "error"
                                                 : "validation";
    *sink->err << "rrc-accumulate: [" << tag << "] " << (message ? message : "") << "\n";
}

struct ContextDeleter {
    void operator()(rrc_context* c) const { rrc_context_destroy(c); }
};

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

rrc_exr::ExrInfo header_of(const std::string& path) {
    try {
        return rrc_exr::read_exr_info(path);
    } catch (const rrc_exr::ExrError& e) {
        throw CliError(e.what());
    }
}

void verify_blocks(const std::string& path) {
    try {
        rrc_exr::verify_exr_chunks(path);
    } catch (const rrc_exr::ExrError& e) {
        throw CliError(e.what());
    }
}

}  // namespace

void check_no_overwrite(const Options& o) {
    std::map<std::string, std::string> inputs;  // normalised -> as given
#ifdef RRC_CLI_HAVE_STAT
    std::map<std::pair<dev_t, ino_t>, std::string> input_ids;
#endif
    auto add_input = [&](const std::string& p) {
        inputs.emplace(normalised(p), p);
#ifdef RRC_CLI_HAVE_STAT
        struct stat st;
        if (::stat(p.c_str(), &st) == 0) input_ids.emplace(std::make_pair(st.st_dev, st.st_ino), p);
#endif
    };
    for (int64_t f = o.first_frame; f <= o.last_frame; ++f) {
        add_input(format_frame_path(o.input_pattern, f));
        if (!o.reference_pattern.empty()) add_input(format_frame_path(o.reference_pattern, f));
    }
    if (!o.camera_file.empty()) add_input(o.camera_file);

    std::map<std::string, std::string> outputs;  // normalised -> what it is
    auto check_output = [&](const std::string& out, const std::string& what) {
        const std::string norm = normalised(out);
        std::string clash;
        if (auto it = inputs.find(norm); it != inputs.end()) clash = it->second;
#ifdef RRC_CLI_HAVE_STAT
        struct stat st;
        if (clash.empty() && ::stat(out.c_str(), &st) == 0)
            if (auto it = input_ids.find(std::make_pair(st.st_dev, st.st_ino)); it != input_ids.end()) clash = it->second;
#endif
        if (!clash.empty())
            throw CliError(what + " '" + out + "' is the input '" + clash + "'; inputs are never overwritten: choose another output name");
        if (auto [it, inserted] = outputs.emplace(norm, what); !inserted)
            throw CliError(what + " '" + out + "' is also the " + it->second + ": choose distinct output names");
    };
    for (int64_t f = o.first_frame; f <= o.last_frame; ++f) {
        check_output(format_frame_path(o.output_pattern, f), "output (frame " + std::to_string(f) + ")");
        if (!o.coherence_pattern.empty())
            check_output(format_frame_path(o.coherence_pattern, f), "coherence map (frame " + std::to_string(f) + ")");
    }
    if (!o.reference_pattern.empty()) check_output(metrics_path(o), "metrics file");
    if (!o.clean_report.empty()) check_output(o.clean_report, "clean report");
}

namespace {

std::string clock_text(double seconds) {
    const long s = static_cast<long>(std::lround(std::max(0.0, seconds)));
    char buf[32];
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    return buf;
}

// Progress on `out`: a bar redrawn with '\r' (terminal) or one line a frame.
class ProgressReport {
public:
    ProgressReport(std::ostream& out, Progress mode, bool quiet, int64_t total)
        : out_(out), bar_(mode == Progress::Bar), quiet_(quiet), total_(total), start_(Clock::now()) {}
    void frame(int64_t f, int64_t done, const std::string& details) {
        if (quiet_) return;
        const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
        const double eta = done ? elapsed / static_cast<double>(done) * static_cast<double>(total_ - done) : 0.0;
        if (!bar_) {
            out_ << "frame " << f << ": " << details << " [" << done << "/" << total_ << ", ETA " << clock_text(eta) << "]\n" << std::flush;
            return;
        }
        constexpr int kWidth = 28;
        const int filled = total_ ? static_cast<int>(kWidth * done / total_) : kWidth;
        std::string line = "\r[" + std::string(static_cast<std::size_t>(filled), '#') +
                           std::string(static_cast<std::size_t>(kWidth - filled), '-') + "] " + std::to_string(done) + "/" +
                           std::to_string(total_) + " frames, frame " + std::to_string(f) + ": " + details + ", ETA " + clock_text(eta);
        const std::size_t shown = line.size();
        if (shown < last_length_) line += std::string(last_length_ - shown, ' ');  // erase what the last line left
        last_length_ = shown;
        out_ << line << std::flush;
        drawn_ = true;
    }
    // Ends the bar's line (before the summary or an error).
    void finish() {
        if (drawn_) out_ << "\n" << std::flush;
        drawn_ = false;
    }

private:
    std::ostream& out_;
    bool bar_, quiet_;
    int64_t total_;
    Clock::time_point start_;
    std::size_t last_length_ = 0;
    bool drawn_ = false;
};

// Squared error sums of one signal against the reference.
struct MetricSums {
    double input_sse = 0, output_sse = 0;
    uint64_t values = 0;
};

double psnr_db(double mse, double peak) { return mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity(); }

std::string number(double v, const char* fmt = "%.6g") {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    if (std::isnan(v)) return "nan";
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

// Compares the raw input and the accumulated output of signal k with the
// reference, over pixels where all three are finite (every component but A).
MetricSums measure(const SignalLayout& s, const std::vector<float>& input, const std::vector<float>& output,
                   const rrc_exr::ExrImage& reference, const std::string& ref_path) {
    MetricSums m;
    const std::size_t n = reference.pixel_count();
    const std::vector<std::string> names = metric_channels(s);
    std::vector<std::vector<float>> ref;
    for (const std::string& name : names) ref.push_back(reference.as_float(name, ref_path));
    const std::size_t stride = s.rrc_components;
    for (std::size_t i = 0; i < n; ++i) {
        bool finite = true;
        for (std::size_t c = 0; c < names.size(); ++c)
            finite = finite && std::isfinite(ref[c][i]) && std::isfinite(input[i * stride + c]) && std::isfinite(output[i * stride + c]);
        if (!finite) continue;
        for (std::size_t c = 0; c < names.size(); ++c) {
            const double r = ref[c][i], a = input[i * stride + c] - r, b = output[i * stride + c] - r;
            m.input_sse += a * a;
            m.output_sse += b * b;
        }
        m.values += names.size();
    }
    return m;
}

void write_text_atomically(const std::string& path, const std::string& text) {
    const fs::path target(path);
    const fs::path dir = target.parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) throw CliError("cannot create the directory '" + dir.string() + "': " + ec.message());
    }
    const std::string tmp =
        (dir / ("." + target.filename().string() + ".tmp-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count())))
            .string();
    {
        std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
        os << text;
        os.flush();
        if (!os) {
            os.close();
            fs::remove(tmp, ec);
            throw CliError("cannot write '" + path + "'");
        }
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw CliError("cannot write '" + path + "': " + ec.message());
    }
}

void ensure_parent_directory(const std::string& path) {
    const fs::path dir = fs::path(path).parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) throw CliError("cannot create the output directory '" + dir.string() + "': " + ec.message());
    }
}

}  // namespace

int run_accumulate(const Options& o, std::ostream& out, std::ostream& err) {
    LogSink sink{&err, o.verbose};
    std::unique_ptr<rrc_context, ContextDeleter> context;
    ProgressReport progress(out, o.progress, o.quiet, o.last_frame - o.first_frame + 1);
    int64_t first_written = -1, last_written = -1;
    try {
        const auto t_start = Clock::now();
        rrc_exr::set_thread_count(static_cast<int>(std::min(16u, std::thread::hardware_concurrency())));

        // 1. Everything that can be checked before processing: every header
        //    and block table (a truncated file fails here), sizes, channels.
        const std::string first_path = format_frame_path(o.input_pattern, o.first_frame);
        const rrc_exr::ExrInfo first_info = header_of(first_path);
        const SequenceLayout layout = discover_layout(first_info, first_path, o);
        std::vector<RequiredChannel> reference_channels;
        for (const SignalLayout& s : layout.signals)
            for (const std::string& c : metric_channels(s))
                reference_channels.push_back({c, "--reference: the converged " + s.options.layer});
        for (int64_t f = o.first_frame; f <= o.last_frame; ++f) {
            const std::string path = format_frame_path(o.input_pattern, f);
            const rrc_exr::ExrInfo info = f == o.first_frame ? first_info : header_of(path);
            check_frame_header(info, path, layout);
            verify_blocks(path);
            if (!o.reference_pattern.empty()) {
                const std::string ref = format_frame_path(o.reference_pattern, f);
                const rrc_exr::ExrInfo ri = header_of(ref);
                if (ri.width != layout.width || ri.height != layout.height)
                    throw CliError(ref + ": the reference frame is " + std::to_string(ri.width) + "x" + std::to_string(ri.height) +
                                   ", the input " + std::to_string(layout.width) + "x" + std::to_string(layout.height));
                for (const RequiredChannel& r : reference_channels)
                    if (!ri.has(r.name))
                        throw CliError(ref + ": missing channel '" + r.name + "' (" + r.reason + "); the file has: " + list_channels(ri));
                verify_blocks(ref);
            }
        }
        check_no_overwrite(o);
        std::map<int64_t, CameraFrame> cameras;
        if (!o.camera_file.empty())
            cameras = load_camera_file(o.camera_file, o.first_frame, o.last_frame, layout.reprojection == RRC_REPROJECTION_CAMERA);
        const std::set<int64_t> cuts(o.cuts.begin(), o.cuts.end());

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

        // 3. The frames.  Whether ids are used changes which pixels may hit,
        //    so the run says so before the first frame (and in the summary).
        if (!layout.object_id_report.empty() && !o.quiet) out << "rrc-accumulate: " << layout.object_id_report << "\n";
        const std::size_t n = static_cast<std::size_t>(layout.width) * static_cast<std::size_t>(layout.height);
        const std::size_t k = layout.signals.size();
        CameraFrame previous_camera;
        double ratio_sum = 0.0;
        int64_t ratio_count = 0, processed = 0;
        std::vector<MetricSums> metric_totals(k);
        std::vector<uint32_t> fill_ages;
        for (const rrc_channel_desc& c : channel_descs) fill_ages.push_back(c.fill_age);
        std::unique_ptr<CleanReport> clean;
        if (!o.clean_report.empty()) clean.reset(new CleanReport(o, layout, fill_ages));
        std::string csv = "frame,layer,hit_ratio,values,input_rmse,input_psnr_db,output_rmse,output_psnr_db\n";
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
                if (!image.has(r.name)) throw CliError(in_path + ": missing channel '" + r.name + "' (" + r.reason + ")");
            const FrameData data = load_frame(image, in_path, layout);
            image = rrc_exr::ExrImage{};  // the arrays are in `data` now
            rrc_exr::ExrImage reference;
            const std::string ref_path = o.reference_pattern.empty() ? std::string() : format_frame_path(o.reference_pattern, f);
            if (!ref_path.empty()) {
                try {
                    reference = rrc_exr::read_exr(ref_path);
                } catch (const rrc_exr::ExrError& e) {
                    throw CliError(e.what());
                }
                if (reference.width != layout.width || reference.height != layout.height)
                    throw CliError(ref_path + ": the size changed while reading");
            }

            CameraFrame camera;
            if (auto it = cameras.find(f); it != cameras.end()) camera = it->second;
            if (f == o.first_frame) previous_camera = camera;

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
            frame.reset = cuts.count(f) ? 1u : 0u;
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
            frame.object_id = data.object_id.empty() ? nullptr : data.object_id.data();
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
                if (layout.signals[s].confidence) result.weight[s].assign(n, 0.0f);
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

            // Outputs: each written under a temporary name, then renamed.
            ensure_parent_directory(out_path);
            try {
                rrc_exr::write_exr(out_path, make_output_image(layout, result));
            } catch (const rrc_exr::ExrError& e) {
                throw CliError(e.what());
            }
            if (!o.coherence_pattern.empty()) {
                const std::string png = format_frame_path(o.coherence_pattern, f);
                ensure_parent_directory(png);
                rrc_png::RgbImage map;
                map.width = layout.width;
                map.height = layout.height;
                map.rgb = coherence_rgb(result.mask);
                try {
                    rrc_png::write_png(png, map);
                } catch (const rrc_png::PngError& e) {
                    throw CliError(e.what());
                }
            }
            if (first_written < 0) first_written = f;
            last_written = f;

            const rrc_frame_stats& st = output.stats;
            const uint64_t tested = st.hits + st.misses;
            const double ratio = tested ? 100.0 * static_cast<double>(st.hits) / static_cast<double>(tested) : 0.0;
            if (f != o.first_frame && tested) {
                ratio_sum += ratio;
                ++ratio_count;
            }
            std::string details = "hit " + (tested ? format("%.1f%%", ratio) : std::string("n/a"));
            if (frame.reset) details += " (cut)";
            if (!ref_path.empty()) {
                for (std::size_t s = 0; s < k; ++s) {
                    const MetricSums m = measure(layout.signals[s], data.samples[s], result.values[s], reference, ref_path);
                    metric_totals[s].input_sse += m.input_sse;
                    metric_totals[s].output_sse += m.output_sse;
                    metric_totals[s].values += m.values;
                    const double in_mse = m.values ? m.input_sse / double(m.values) : 0.0;
                    const double out_mse = m.values ? m.output_sse / double(m.values) : 0.0;
                    csv += std::to_string(f) + "," + layout.signals[s].options.layer + "," +
                           (tested ? number(ratio / 100.0) : std::string()) + "," + std::to_string(m.values) + "," +
                           number(std::sqrt(in_mse)) + "," + number(psnr_db(in_mse, o.psnr_peak)) + "," + number(std::sqrt(out_mse)) + "," +
                           number(psnr_db(out_mse, o.psnr_peak)) + "\n";
                    if (s == 0)
                        details += ", PSNR " + number(psnr_db(in_mse, o.psnr_peak), "%.1f") + " -> " +
                                   number(psnr_db(out_mse, o.psnr_peak), "%.1f") + " dB";
                }
            }
            if (clean) clean->add_frame(f, data, result);
            details += format(", %.2f ms (rrc_frame_run), %.1f ms total", run_ms, ms_since(t_frame));
            if (st.invalid_samples || st.invalid_geometry)
                details += ", " + std::to_string(st.invalid_samples) + " invalid samples, " + std::to_string(st.invalid_geometry) +
                           " invalid geometry";
            ++processed;
            progress.frame(f, processed, details);
            previous_camera = camera;
        }
        progress.finish();

        // Also counts when validation came from RRC_VALIDATION=1 in the environment.
        uint64_t validation_messages = 0;
        check(rrc_context_validation_messages(context.get(), &validation_messages));
        if (!o.reference_pattern.empty()) {
            const std::string csv_path = metrics_path(o);
            write_text_atomically(csv_path, csv);
            for (std::size_t s = 0; s < k; ++s) {
                const MetricSums& m = metric_totals[s];
                const double in_mse = m.values ? m.input_sse / double(m.values) : 0.0;
                const double out_mse = m.values ? m.output_sse / double(m.values) : 0.0;
                out << "rrc-accumulate: " << layout.signals[s].options.layer << " against the reference over " << processed
                    << (processed == 1 ? " frame" : " frames") << ": input RMSE " << number(std::sqrt(in_mse), "%.4g") << " (PSNR "
                    << number(psnr_db(in_mse, o.psnr_peak), "%.2f") << " dB), accumulated RMSE " << number(std::sqrt(out_mse), "%.4g")
                    << " (PSNR " << number(psnr_db(out_mse, o.psnr_peak), "%.2f") << " dB); per frame in " << csv_path << "\n";
            }
        }
        if (clean) clean->finish(out);
        out << "rrc-accumulate: " << processed << (processed == 1 ? " frame" : " frames") << ", mean hit ratio "
            << (ratio_count ? format("%.1f%%", ratio_sum / static_cast<double>(ratio_count)) : std::string("n/a"))
            << " (frames after the first)" << format(", total %.2f s", ms_since(t_start) / 1000.0) << ", device " << device;
        if (o.validation || validation_messages) out << ", " << validation_messages << " validation messages";
        if (!layout.object_id_report.empty()) out << ", " << layout.object_id_report;
        out << "\n" << std::flush;
        context.reset();
        if (validation_messages) {
            err << "rrc-accumulate: the validation layer reported " << validation_messages << " message(s)\n";
            return kExitError;
        }
        return kExitOk;
    } catch (const std::bad_alloc&) {
        progress.finish();
        context.reset();
        err << "rrc-accumulate: out of memory\n";
    } catch (const std::exception& e) {
        progress.finish();
        context.reset();
        err << "rrc-accumulate: " << e.what() << "\n";
    }
    if (first_written >= 0)
        err << "rrc-accumulate: frames " << first_written << "-" << last_written
            << " were written completely before the error; no partial file was left\n";
    return kExitError;
}

int accumulate_main(int argc, const char* const* argv, std::ostream& out, std::ostream& err, bool out_is_terminal) {
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
    if (parsed.options.check_options) {
        out << "rrc-accumulate: options ok\n";
        return kExitOk;
    }
    Options options = parsed.options;
    if (options.progress == Progress::Auto) options.progress = out_is_terminal ? Progress::Bar : Progress::Lines;
    return run_accumulate(options, out, err);
}

}  // namespace rrc_cli
