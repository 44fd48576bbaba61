// Tests of rrc-accumulate's option parser, of rrc_exr_io, and of the tool's
// checks (which run before any rrc context exists), of the clean report's
// regions on hand-made frames; end-to-end tests run small sequences through
// the library (--clean-report among them).
//
// Links: rrc_accumulate_core (which brings rrc and rrc_exr_io), GTest::gtest_main.
#include "accumulate.h"
#include "options.h"
#include "sequence.h"

#include <clean_regions.h>
#include <exr_io.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using rrc_cli::Options;
using rrc_cli::parse_arguments;
using rrc_cli::ParseResult;
using rrc_cli::SignalOptions;

namespace {

using namespace rrc_cli_test;

ParseResult parse(std::initializer_list<const char*> args) {
    std::vector<const char*> argv = {"rrc-accumulate"};
    argv.insert(argv.end(), args.begin(), args.end());
    return parse_arguments(static_cast<int>(argv.size()), argv.data());
}

// The three required options plus `extra`.
ParseResult parse_with(std::initializer_list<const char*> extra) {
    std::vector<const char*> argv = {"rrc-accumulate", "--input", "in/f_%04d.exr", "--output", "out/o_%04d.exr", "--frames", "1-3"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return parse_arguments(static_cast<int>(argv.size()), argv.data());
}

void expect_error(const ParseResult& r, const std::string& fragment) {
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error.find(fragment), std::string::npos) << "error '" << r.error << "' lacks '" << fragment << "'";
}

rrc_exr::ExrImage sample_image(int w, int h) {
    rrc_exr::ExrImage img;
    img.width = w;
    img.height = h;
    const std::size_t n = std::size_t(w) * h;
    auto& a = img.channels["color.R"];
    auto& b = img.channels["Z"];
    auto& u = img.uint_channels["id"];
    for (std::size_t i = 0; i < n; ++i) {
        a.push_back(0.1f * float(i) - 3.0f);
        b.push_back(1.0f / float(i + 1));
        u.push_back(static_cast<uint32_t>(i * 2654435761u));
    }
    if (n < 5) return img;
    // Values a format could mangle.
    a[0] = std::numeric_limits<float>::infinity();
    a[1] = -0.0f;
    a[2] = std::numeric_limits<float>::denorm_min();
    a[3] = std::numeric_limits<float>::quiet_NaN();
    a[4] = 123456789.0f;
    img.attributes["comment"] = "rrc round trip";
    return img;
}

bool bitwise_equal(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// ---- a sequence on disk for the tool ------------------------------------

struct SceneOptions {
    int w = 16, h = 12;
    bool motion = false;  // mv.X/mv.Y(/mv.Z) instead of prevclip
    bool motion_z = true;
    bool rgb_only = false;  // color.R/G/B without A
    bool conf = false;
    const char* drop = nullptr;  // a channel left out of frame `drop_frame`
    int drop_frame = -1;

    // mv.X/mv.Y, with mv.Z when `z`, instead of prevclip.
    static SceneOptions motion_vectors(bool z) {
        SceneOptions s;
        s.motion = true;
        s.motion_z = z;
        return s;
    }
    // color.R/G/B without A, and a confidence when `confidence`.
    static SceneOptions rgb(bool confidence = false) {
        SceneOptions s;
        s.rgb_only = true;
        s.conf = confidence;
        return s;
    }
    // `channel` left out of frame `frame`.
    static SceneOptions dropping(const char* channel, int frame) {
        SceneOptions s;
        s.drop = channel;
        s.drop_frame = frame;
        return s;
    }
};

// A static camera looking at a plane at standard NDC depth 0.5: every pixel
// reprojects onto itself, so every pixel after the first frame is a hit.
void write_static_sequence(const std::string& pattern, int first, int last, const SceneOptions& s) {
    for (int f = first; f <= last; ++f) {
        rrc_exr::ExrImage img;
        img.width = s.w;
        img.height = s.h;
        const std::size_t n = std::size_t(s.w) * s.h;
        auto ch = [&](const std::string& name) -> std::vector<float>& { return img.channels[name] = std::vector<float>(n, 0.0f); };
        auto& z = ch("Z");
        std::vector<float>* px = nullptr;
        std::vector<float>* py = nullptr;
        std::vector<float>* pz = nullptr;
        std::vector<float>* pw = nullptr;
        if (s.motion) {
            ch("mv.X");
            ch("mv.Y");
            if (s.motion_z) ch("mv.Z");
        } else {
            px = &ch("prevclip.X");
            py = &ch("prevclip.Y");
            pz = &ch("prevclip.Z");
            pw = &ch("prevclip.W");
        }
        auto& y = ch("shadow.Y");
        auto& r = ch("color.R");
        auto& g = ch("color.G");
        auto& b = ch("color.B");
        std::vector<float>* a = s.rgb_only ? nullptr : &ch("color.A");
        std::vector<float>* conf = s.conf ? &ch("color.conf") : nullptr;
        for (int j = 0; j < s.h; ++j)
            for (int i = 0; i < s.w; ++i) {
                const std::size_t k = std::size_t(j) * s.w + i;
                z[k] = 0.5f;
                if (px) {
                    (*px)[k] = 2.0f * (i + 0.5f) / s.w - 1.0f;
                    (*py)[k] = 2.0f * (j + 0.5f) / s.h - 1.0f;
                    (*pz)[k] = 0.5f;
                    (*pw)[k] = 1.0f;
                }
                y[k] = float((i + j + f) % 2);
                r[k] = 0.25f * f;
                g[k] = 0.5f;
                b[k] = float(i) / s.w;
                if (a) (*a)[k] = 1.0f;
                if (conf) (*conf)[k] = 1.0f;
            }
        if (s.drop && f == s.drop_frame) img.channels.erase(s.drop);
        const std::string path = rrc_cli::format_frame_path(pattern, f);
        fs::create_directories(fs::path(path).parent_path());
        rrc_exr::write_exr(path, img);
    }
}

// The sequence and depth options every parse test checks first.
struct SequenceOptions {
    const char* input;
    const char* output;
    int64_t first, last;
    rrc_depth_mode depth_mode;
    rrc_depth_format depth_format;
};

void expect_sequence(const Options& o, const SequenceOptions& want) {
    EXPECT_EQ(o.input_pattern, want.input);
    EXPECT_EQ(o.output_pattern, want.output);
    EXPECT_EQ(o.first_frame, want.first);
    EXPECT_EQ(o.last_frame, want.last);
    EXPECT_EQ(o.depth_mode, want.depth_mode);
    EXPECT_EQ(o.depth_format, want.depth_format);
}

}  // namespace

// ======================================================================
// Option parser
// ======================================================================

TEST(AccumulateOptions, RequiredOnlyGivesDefaults) {
    ParseResult r = parse_with({});
    ASSERT_TRUE(r.ok()) << r.error;
    const Options& o = r.options;
    expect_sequence(o, {"in/f_%04d.exr", "out/o_%04d.exr", 1, 3, RRC_DEPTH_MODE_STANDARD, RRC_DEPTH_FORMAT_FLOAT32});
    EXPECT_EQ(o.epsilon, 0.0f);
    EXPECT_EQ(o.epsilon_scale, 0.0f);
    EXPECT_EQ(o.tau, 0.0f);
    EXPECT_EQ(o.background_threshold, 0.0f);
    EXPECT_EQ(o.near_plane, 0.0f);
    EXPECT_EQ(o.far_plane, 0.0f);
    EXPECT_EQ(o.reproject, rrc_cli::Reproject::PrevClip);
    EXPECT_EQ(o.motion_scale[0], 1.0f);
    EXPECT_EQ(o.motion_scale[1], 1.0f);
    EXPECT_TRUE(o.camera_file.empty());
    EXPECT_TRUE(o.signals.empty());
    EXPECT_TRUE(o.device.empty());
    EXPECT_FALSE(o.validation);
    EXPECT_FALSE(o.quiet);
    EXPECT_FALSE(o.verbose);
    EXPECT_FALSE(o.help);
    EXPECT_EQ(o.depth_test, RRC_DEPTH_TEST_DEFAULT);  // the library decides (rrc.h)
    EXPECT_TRUE(o.object_id_channel.empty());
    EXPECT_FALSE(o.no_object_id);
}

TEST(AccumulateOptions, EveryOptionParsed) {
    ParseResult r = parse({"--input",
                           "a/%d.exr",
                           "--frames",
                           "7-19",
                           "--output",
                           "b/%05d.exr",
                           "--depth-mode",
                           "reversed",
                           "--depth-format",
                           "unorm24",
                           "--epsilon",
                           "1e-6",
                           "--epsilon-scale",
                           "2",
                           "--tau",
                           "0.05",
                           "--background-threshold",
                           "5000",
                           "--near",
                           "0.1",
                           "--far",
                           "inf",
                           "--reproject",
                           "motion",
                           "--motion-scale",
                           "0.0078125,-0.0104166",
                           "--camera",
                           "cam.json",
                           "--signal",
                           "shadow:lambda=0.8,blend=age_aware,filter=catmull_rom,history=fp32,max_age=64",
                           "--signal",
                           "color",
                           "--device",
                           "llvmpipe",
                           "--validation",
                           "--quiet",
                           "--verbose"});
    ASSERT_TRUE(r.ok()) << r.error;
    const Options& o = r.options;
    expect_sequence(o, {"a/%d.exr", "b/%05d.exr", 7, 19, RRC_DEPTH_MODE_REVERSED, RRC_DEPTH_FORMAT_UNORM24});
    EXPECT_FLOAT_EQ(o.epsilon, 1e-6f);
    EXPECT_FLOAT_EQ(o.epsilon_scale, 2.0f);
    EXPECT_FLOAT_EQ(o.tau, 0.05f);
    EXPECT_FLOAT_EQ(o.background_threshold, 5000.0f);
    EXPECT_FLOAT_EQ(o.near_plane, 0.1f);
    EXPECT_TRUE(std::isinf(o.far_plane));
    EXPECT_EQ(o.reproject, rrc_cli::Reproject::Motion);
    EXPECT_FLOAT_EQ(o.motion_scale[0], 0.0078125f);
    EXPECT_FLOAT_EQ(o.motion_scale[1], -0.0104166f);
    EXPECT_EQ(o.camera_file, "cam.json");
    ASSERT_EQ(o.signals.size(), 2u);
    EXPECT_EQ(o.signals[0].layer, "shadow");
    EXPECT_FLOAT_EQ(o.signals[0].lambda, 0.8f);
    EXPECT_EQ(o.signals[0].blend, RRC_BLEND_AGE_AWARE);
    EXPECT_EQ(o.signals[0].filter, RRC_HISTORY_FILTER_CATMULL_ROM);
    EXPECT_EQ(o.signals[0].history, RRC_HISTORY_FP32);
    EXPECT_EQ(o.signals[0].max_age, 64u);
    EXPECT_EQ(o.signals[1].layer, "color");
    EXPECT_EQ(o.device, "llvmpipe");
    EXPECT_TRUE(o.validation);
    EXPECT_TRUE(o.quiet);
    EXPECT_TRUE(o.verbose);
}

TEST(AccumulateOptions, EnumValues) {
    EXPECT_EQ(parse_with({"--depth-mode", "standard"}).options.depth_mode, RRC_DEPTH_MODE_STANDARD);
    EXPECT_EQ(parse_with({"--depth-mode", "linear"}).options.depth_mode, RRC_DEPTH_MODE_LINEAR);
    EXPECT_EQ(parse_with({"--depth-format", "float32"}).options.depth_format, RRC_DEPTH_FORMAT_FLOAT32);
    EXPECT_EQ(parse_with({"--depth-format", "unorm16"}).options.depth_format, RRC_DEPTH_FORMAT_UNORM16);
    EXPECT_EQ(parse_with({"--reproject", "prev_clip"}).options.reproject, rrc_cli::Reproject::PrevClip);
    ParseResult cam = parse_with({"--reproject", "camera", "--camera", "c.json"});
    ASSERT_TRUE(cam.ok()) << cam.error;
    EXPECT_EQ(cam.options.reproject, rrc_cli::Reproject::Camera);
}

TEST(AccumulateOptions, ObjectIdAndDepthTest) {
    ParseResult r = parse_with({"--object-id", "L.IndexOB.X", "--depth-test", "adaptive"});
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.options.object_id_channel, "L.IndexOB.X");
    EXPECT_EQ(r.options.depth_test, RRC_DEPTH_TEST_ADAPTIVE);
    EXPECT_TRUE(parse_with({"--no-object-id"}).options.no_object_id);
    for (rrc_depth_test t : {RRC_DEPTH_TEST_DEFAULT, RRC_DEPTH_TEST_ADAPTIVE, RRC_DEPTH_TEST_FIXED}) {
        const std::string name = rrc_cli::depth_test_name(t);
        const ParseResult named = parse_with({"--depth-test", name.c_str()});
        ASSERT_TRUE(named.ok()) << named.error;
        EXPECT_EQ(named.options.depth_test, t) << name;
    }
    // fixed goes with explicit tolerances; adaptive sets its own (rrc.h), so
    // the tool refuses the mix before the library would.
    EXPECT_TRUE(parse_with({"--depth-test", "fixed", "--tau", "0.02", "--epsilon", "1e-5"}).ok());
    expect_error(parse_with({"--depth-test", "paper"}), "--depth-test");
    expect_error(parse_with({"--depth-test", "adaptive", "--tau", "0.02"}), "--tau");
    expect_error(parse_with({"--depth-test", "adaptive", "--epsilon", "1e-5"}), "--epsilon");
    expect_error(parse_with({"--depth-test", "adaptive", "--epsilon-scale", "2"}), "--epsilon-scale");
    expect_error(parse_with({"--depth-test", "adaptive", "--preset", "blender"}), "--preset blender");
    EXPECT_TRUE(parse_with({"--depth-test", "fixed", "--preset", "blender"}).ok());
    expect_error(parse_with({"--object-id", "id.X", "--no-object-id"}), "--no-object-id");
    expect_error(parse_with({"--object-id", ""}), "--object-id");
    expect_error(parse_with({"--no-object-id=1"}), "--no-object-id");
}

TEST(AccumulateOptions, InlineValues) {
    ParseResult r = parse({"--input=i_%03d.exr", "--output=o_%03d.exr", "--frames=4", "--epsilon=0.001", "--signal=shadow:lambda=0.5"});
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.options.input_pattern, "i_%03d.exr");
    EXPECT_EQ(r.options.first_frame, 4);
    EXPECT_EQ(r.options.last_frame, 4);
    EXPECT_FLOAT_EQ(r.options.epsilon, 0.001f);
    ASSERT_EQ(r.options.signals.size(), 1u);
    EXPECT_FLOAT_EQ(r.options.signals[0].lambda, 0.5f);
    expect_error(parse_with({"--quiet=1"}), "--quiet");
}

TEST(AccumulateOptions, HelpNeedsNothingElse) {
    ParseResult r = parse({"--help"});
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_TRUE(r.options.help);
    EXPECT_TRUE(parse({"-h"}).options.help);
}

TEST(AccumulateOptions, UsageDocumentsEveryOption) {
    const std::string u = rrc_cli::usage_text();
    // Every option the parser takes a value for, then the flags, keys and names.
    for (const std::string& opt : rrc_cli::value_options()) EXPECT_NE(u.find(opt), std::string::npos) << "usage does not mention " << opt;
    for (const char* opt :
         {"--input",        "--validation", "--quiet",    "--verbose",    "--help",      "lambda=",   "blend=",  "filter=",
          "history=",       "max_age=",     "age_aware",  "running_mean", "catmull_rom", "nearest",   "unorm16", "unorm24",
          "prev_clip",      "rrc.mask",     ".age",       "nocache.Y",    "jitter",      "view_proj", "mv.Z",    "prevclip",
          "--no-object-id", "IndexOB.X",    "4294967295", "adaptive",     "fixed"})
        EXPECT_NE(u.find(opt), std::string::npos) << "usage does not mention " << opt;
}

TEST(AccumulateOptions, MissingRequired) {
    expect_error(parse({"--output", "o_%d.exr", "--frames", "1-2"}), "--input");
    expect_error(parse({"--input", "i_%d.exr", "--frames", "1-2"}), "--output");
    expect_error(parse({"--input", "i_%d.exr", "--output", "o_%d.exr"}), "--frames");
    expect_error(parse_with({"--reproject", "camera"}), "--camera");
}

TEST(AccumulateOptions, BadOptionsNameTheOption) {
    expect_error(parse_with({"--bogus"}), "--bogus");
    expect_error(parse_with({"-x"}), "-x");
    expect_error(parse_with({"stray"}), "stray");
    expect_error(parse_with({"--epsilon"}), "--epsilon");           // no value
    expect_error(parse_with({"--camera", "--quiet"}), "--camera");  // an option is not a value
    // Values each option refuses: the message names the option.
    const std::vector<std::pair<const char*, std::vector<const char*>>> refused = {
        {"--epsilon", {"abc", "-1", "0", "1e-3x", "nan", "1e99"}},
        {"--epsilon-scale", {"0"}},
        {"--tau", {"-0.1", "inf"}},
        {"--background-threshold", {"x"}},
        {"--near", {"0"}},
        {"--far", {"-inf"}},
        {"--depth-mode", {"inverted"}},
        {"--depth-format", {"unorm32"}},
        {"--reproject", {"flow"}},
        {"--motion-scale", {"1", "a,b", "0,1", "1,2,3"}},
        {"--camera", {""}},
        {"--device", {""}},
    };
    for (const auto& option : refused)
        for (const char* value : option.second) {
            SCOPED_TRACE(std::string(option.first) + " " + value);
            expect_error(parse_with({option.first, value}), option.first);
        }
    expect_error(parse_with({"--near", "10", "--far", "1"}), "--far");
    expect_error(parse_with({"--depth-mode", "linear", "--depth-mode", "reversed"}), "--depth-mode");
    expect_error(parse_with({"--frames", "2-4"}), "--frames");  // given twice
    expect_error(parse({"--input", "f_%04d.exr", "--output", "f_%04d.exr", "--frames", "1"}), "--output");
}

TEST(AccumulateOptions, Patterns) {
    std::string err;
    EXPECT_TRUE(rrc_cli::validate_pattern("frames/f_%04d.exr", err)) << err;
    EXPECT_TRUE(rrc_cli::validate_pattern("f%d", err)) << err;
    EXPECT_TRUE(rrc_cli::validate_pattern("100%%/f_%3i_%%.exr", err)) << err;
    EXPECT_TRUE(rrc_cli::validate_pattern("%u", err)) << err;
    EXPECT_FALSE(rrc_cli::validate_pattern("frames/f.exr", err));
    EXPECT_NE(err.find("exactly one"), std::string::npos) << err;
    EXPECT_FALSE(rrc_cli::validate_pattern("f_%d_%d.exr", err));
    EXPECT_FALSE(rrc_cli::validate_pattern("f_%s.exr", err));
    EXPECT_NE(err.find("%s"), std::string::npos) << err;
    EXPECT_FALSE(rrc_cli::validate_pattern("f_%-4d.exr", err));
    EXPECT_FALSE(rrc_cli::validate_pattern("f_%04", err));
    EXPECT_FALSE(rrc_cli::validate_pattern("f_%n", err));
    EXPECT_FALSE(rrc_cli::validate_pattern("f_%999d", err));
    EXPECT_FALSE(rrc_cli::validate_pattern("", err));

    EXPECT_EQ(rrc_cli::format_frame_path("frames/f_%04d.exr", 7), "frames/f_0007.exr");
    EXPECT_EQ(rrc_cli::format_frame_path("frames/f_%04d.exr", 123456), "frames/f_123456.exr");
    EXPECT_EQ(rrc_cli::format_frame_path("f%d", 0), "f0");
    EXPECT_EQ(rrc_cli::format_frame_path("f%3d", 5), "f  5");
    EXPECT_EQ(rrc_cli::format_frame_path("100%%/f_%02i_%%.exr", 3), "100%/f_03_%.exr");

    expect_error(parse({"--input", "frames/f.exr", "--output", "o_%d.exr", "--frames", "1"}), "--input");
    expect_error(parse({"--input", "f_%d.exr", "--output", "o_%s.exr", "--frames", "1"}), "--output");
}

TEST(AccumulateOptions, FrameRanges) {
    int64_t a = -1, b = -1;
    std::string err;
    struct Range {
        const char* text;
        int64_t first, last;
    };
    for (const Range& r : {Range{"10-20", 10, 20}, Range{"7", 7, 7}, Range{"0-0", 0, 0}, Range{"0012-0013", 12, 13}}) {
        EXPECT_TRUE(rrc_cli::parse_frame_range(r.text, a, b, err)) << r.text;
        EXPECT_EQ(a, r.first) << r.text;
        EXPECT_EQ(b, r.last) << r.text;
    }
    for (const char* bad :
         {"5-3", "-3", "a-b", "1-", "-", "", "1-2-3", "1 - 2", "+1-2", "1.5-3", "99999999999999999999-1", "0-1000000000"}) {
        EXPECT_FALSE(rrc_cli::parse_frame_range(bad, a, b, err)) << bad;
        EXPECT_NE(err.find("--frames"), std::string::npos) << err;
        expect_error(parse({"--input", "i%d", "--output", "o%d", "--frames", bad}), "--frames");
    }
}

TEST(AccumulateOptions, SignalSpecs) {
    SignalOptions s;
    std::string err;
    ASSERT_TRUE(rrc_cli::parse_signal_spec("shadow", s, err)) << err;
    EXPECT_EQ(s.layer, "shadow");
    EXPECT_FLOAT_EQ(s.lambda, 0.6f);
    EXPECT_EQ(s.blend, RRC_BLEND_FIXED);
    EXPECT_EQ(s.filter, RRC_HISTORY_FILTER_BILINEAR);
    EXPECT_EQ(s.history, RRC_HISTORY_FP16);
    EXPECT_EQ(s.max_age, 255u);

    ASSERT_TRUE(rrc_cli::parse_signal_spec("diffuse.indirect:blend=running_mean,filter=nearest", s, err)) << err;
    EXPECT_EQ(s.layer, "diffuse.indirect");
    EXPECT_EQ(s.blend, RRC_BLEND_RUNNING_MEAN);
    EXPECT_EQ(s.filter, RRC_HISTORY_FILTER_NEAREST);
    EXPECT_FLOAT_EQ(s.lambda, 0.6f);

    ASSERT_TRUE(rrc_cli::parse_signal_spec("a:lambda=0,max_age=65535,history=fp16,filter=bilinear,blend=fixed", s, err)) << err;
    EXPECT_EQ(s.lambda, 0.0f);
    EXPECT_EQ(s.max_age, 65535u);
    EXPECT_EQ(s.fill_age, 0u);

    ASSERT_TRUE(rrc_cli::parse_signal_spec("c:fill=4,fill_radius=3,fill_tolerance=0.05", s, err)) << err;
    EXPECT_EQ(s.fill_age, 4u);
    EXPECT_EQ(s.fill_radius, 3u);
    EXPECT_FLOAT_EQ(s.fill_depth_tolerance, 0.05f);
    ASSERT_TRUE(rrc_cli::parse_signal_spec("c:max_age=8,fill=9", s, err)) << err;
    EXPECT_EQ(s.fill_age, 9u);
    EXPECT_EQ(s.fill_radius, 0u);
    EXPECT_EQ(s.rectify, 0u);
    EXPECT_EQ(s.antilag, 0u);
    EXPECT_EQ(s.blur_bound, 0.0f);

    ASSERT_TRUE(rrc_cli::parse_signal_spec("c:rectify=on,rectify_gamma=1.5,antilag=on,antilag_gamma=0.25,antilag_threshold=2,blur_bound=64",
                                           s, err))
        << err;
    EXPECT_EQ(s.rectify, 1u);
    EXPECT_FLOAT_EQ(s.rectify_gamma, 1.5f);
    EXPECT_EQ(s.antilag, 1u);
    EXPECT_FLOAT_EQ(s.antilag_gamma, 0.25f);
    EXPECT_FLOAT_EQ(s.antilag_threshold, 2.0f);
    EXPECT_FLOAT_EQ(s.blur_bound, 64.0f);
    ASSERT_TRUE(rrc_cli::parse_signal_spec("c:rectify=off,antilag=off,blur_bound=0.25", s, err)) << err;
    EXPECT_EQ(s.rectify, 0u);
    EXPECT_EQ(s.antilag, 0u);
    EXPECT_FLOAT_EQ(s.blur_bound, 0.25f);
    EXPECT_EQ(s.gate_kappa, 0.0f);
    ASSERT_TRUE(rrc_cli::parse_signal_spec("c:gate=2", s, err)) << err;
    EXPECT_FLOAT_EQ(s.gate_kappa, 2.0f);

    struct Bad {
        const char* spec;
        const char* fragment;
    };
    for (const Bad& b : std::initializer_list<Bad>{{"", "empty"},
                                                   {":lambda=0.5", "empty"},
                                                   {"s:", "key=value"},
                                                   {"s:lambda", "key=value"},
                                                   {"s:lambda=", "key=value"},
                                                   {"s:=0.5", "key=value"},
                                                   {"s:lambda=0.5,", "key=value"},
                                                   {"s:lamda=0.5", "lamda"},
                                                   {"s:lambda=1", "lambda"},
                                                   {"s:lambda=1.5", "lambda"},
                                                   {"s:lambda=-0.1", "lambda"},
                                                   {"s:lambda=x", "lambda"},
                                                   {"s:lambda=nan", "lambda"},
                                                   {"s:lambda=0.5,lambda=0.4", "twice"},
                                                   {"s:blend=mean", "blend"},
                                                   {"s:filter=cubic", "filter"},
                                                   {"s:history=fp64", "history"},
                                                   {"s:max_age=0", "max_age"},
                                                   {"s:max_age=65536", "max_age"},
                                                   {"s:max_age=-3", "max_age"},
                                                   {"s:max_age=1.5", "max_age"},
                                                   {"s:fill=0", "fill"},
                                                   {"s:fill=2.5", "fill"},
                                                   {"s:max_age=8,fill=10", "max_age + 1"},
                                                   {"s:fill=4,fill_radius=0", "fill_radius"},
                                                   {"s:fill=4,fill_radius=5", "fill_radius"},
                                                   {"s:fill_radius=2", "needs fill"},
                                                   {"s:fill_tolerance=0.1", "needs fill"},
                                                   {"s:fill=4,fill_tolerance=0", "fill_tolerance"},
                                                   {"s:fill=4,fill_tolerance=2", "fill_tolerance"},
                                                   {"s:rectify=1", "on or off"},
                                                   {"s:antilag=yes", "on or off"},
                                                   {"s:rectify_gamma=1", "needs rectify=on"},
                                                   {"s:rectify=off,rectify_gamma=1", "needs rectify=on"},
                                                   {"s:rectify=on,rectify_gamma=0", "rectify_gamma"},
                                                   {"s:rectify=on,rectify_gamma=16.5", "rectify_gamma"},
                                                   {"s:antilag_gamma=1", "needs antilag=on"},
                                                   {"s:antilag_threshold=0.5", "needs antilag=on"},
                                                   {"s:antilag=on,antilag_gamma=17", "antilag_gamma"},
                                                   {"s:antilag=on,antilag_threshold=0", "antilag_threshold"},
                                                   {"s:antilag=on,antilag_threshold=2.5", "antilag_threshold"},
                                                   {"s:blur_bound=0", "blur_bound"},
                                                   {"s:blur_bound=-1", "blur_bound"},
                                                   {"s:blur_bound=65", "blur_bound"},
                                                   {"s:blur_bound=nan", "blur_bound"},
                                                   {"s:blur_bound=inf", "blur_bound"},
                                                   {"s:gate=0", "gate"},
                                                   {"s:gate=17", "gate"},
                                                   {"s:gate=nan", "gate"},
                                                   {"mv", "reserved"},
                                                   {"prevclip", "reserved"},
                                                   {"nocache", "reserved"},
                                                   {"rrc", "reserved"},
                                                   {".x", "invalid"},
                                                   {"x.", "invalid"}}) {
        EXPECT_FALSE(rrc_cli::parse_signal_spec(b.spec, s, err)) << b.spec;
        EXPECT_NE(err.find(b.fragment), std::string::npos) << b.spec << " -> " << err;
        EXPECT_NE(err.find("--signal"), std::string::npos) << err;
        expect_error(parse_with({"--signal", b.spec}), "--signal");
    }
    const std::string long_name(RRC_MAX_NAME, 'x');
    EXPECT_FALSE(rrc_cli::parse_signal_spec(long_name, s, err));
    EXPECT_TRUE(rrc_cli::parse_signal_spec(std::string(RRC_MAX_NAME - 1, 'x'), s, err)) << err;
}

TEST(AccumulateOptions, SignalList) {
    ParseResult r = parse_with({"--signal", "a", "--signal", "b:lambda=0.9", "--signal", "c", "--signal", "d"});
    ASSERT_TRUE(r.ok()) << r.error;
    ASSERT_EQ(r.options.signals.size(), 4u);
    EXPECT_FLOAT_EQ(r.options.signals[1].lambda, 0.9f);
    expect_error(parse_with({"--signal", "a", "--signal", "a:lambda=0.1"}), "twice");
    expect_error(parse_with({"--signal", "a", "--signal", "b", "--signal", "c", "--signal", "d", "--signal", "e"}), "at most");
}

// ======================================================================
// rrc_exr_io
// ======================================================================

TEST(ExrIo, RoundTripIsExact) {
    TempDir dir;
    const rrc_exr::ExrImage img = sample_image(37, 23);
    for (rrc_exr::Compression c : {rrc_exr::Compression::Zip, rrc_exr::Compression::None, rrc_exr::Compression::Piz,
                                   rrc_exr::Compression::Zips, rrc_exr::Compression::Rle}) {
        rrc_exr::set_thread_count(c == rrc_exr::Compression::Zip ? 2 : 0);
        rrc_exr::WriteOptions wo;
        wo.compression = c;
        const std::string path = dir / "round.exr";
        rrc_exr::write_exr(path, img, wo);
        const rrc_exr::ExrImage back = rrc_exr::read_exr(path);
        EXPECT_EQ(back.width, 37);
        EXPECT_EQ(back.height, 23);
        ASSERT_EQ(back.channels.size(), img.channels.size());
        for (const auto& kv : img.channels) {
            ASSERT_NE(back.find(kv.first), nullptr) << kv.first;
            EXPECT_TRUE(bitwise_equal(*back.find(kv.first), kv.second)) << kv.first;
        }
        EXPECT_EQ(back.uint_channels, img.uint_channels);
        ASSERT_EQ(back.attributes.count("comment"), 1u);
        EXPECT_EQ(back.attributes.at("comment"), "rrc round trip");
    }
    rrc_exr::set_thread_count(0);
    EXPECT_EQ(dir_entries(dir.path()), std::vector<std::string>{"round.exr"});  // no temporary left
}

TEST(ExrIo, HeaderInfoAndChannelNames) {
    TempDir dir;
    const rrc_exr::ExrImage img = sample_image(5, 4);
    rrc_exr::write_exr(dir / "a.exr", img);
    const rrc_exr::ExrInfo info = rrc_exr::read_exr_info(dir / "a.exr");
    EXPECT_EQ(info.width, 5);
    EXPECT_EQ(info.height, 4);
    EXPECT_EQ(info.parts, 1);
    ASSERT_EQ(info.channels.size(), 3u);
    EXPECT_EQ(info.channels[0].name, "Z");
    EXPECT_EQ(info.channels[0].type, rrc_exr::PixelType::Float);
    EXPECT_EQ(info.channels[2].name, "id");
    EXPECT_EQ(info.channels[2].type, rrc_exr::PixelType::Uint);
    EXPECT_TRUE(info.has("color.R"));
    EXPECT_FALSE(info.has("color.G"));
    const std::vector<std::string> expected = {"Z", "color.R", "id"};
    EXPECT_EQ(rrc_exr::channel_names(dir / "a.exr"), expected);
    EXPECT_EQ(rrc_exr::channel_names(img), expected);
    EXPECT_TRUE(img.has("id"));
    EXPECT_EQ(img.find("id"), nullptr);
    EXPECT_EQ(img.as_float("id")[1], float(uint32_t(2654435761u)));
    EXPECT_THROW(img.as_float("nope", "x.exr"), rrc_exr::ExrError);
}

TEST(ExrIo, OverwriteReplacesAtomically) {
    TempDir dir;
    const std::string path = dir / "f.exr";
    rrc_exr::write_exr(path, sample_image(4, 4));
    rrc_exr::ExrImage second = sample_image(6, 2);
    second.channels.erase("Z");
    rrc_exr::write_exr(path, second);
    const rrc_exr::ExrImage back = rrc_exr::read_exr(path);
    EXPECT_EQ(back.width, 6);
    EXPECT_FALSE(back.has("Z"));
    EXPECT_EQ(dir_entries(dir.path()), std::vector<std::string>{"f.exr"});
}

TEST(ExrIo, WriteErrorsLeaveNothing) {
    TempDir dir;
    const std::string path = dir / "keep.exr";
    rrc_exr::write_exr(path, sample_image(4, 3));
    const std::vector<char> before = file_bytes(path);

    rrc_exr::ExrImage bad = sample_image(4, 3);
    bad.channels["short"] = std::vector<float>(5, 0.0f);
    try {
        rrc_exr::write_exr(path, bad);
        ADD_FAILURE() << "no error for a short channel";
    } catch (const rrc_exr::ExrError& e) {
        EXPECT_NE(std::string(e.what()).find("short"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    rrc_exr::ExrImage both = sample_image(4, 3);
    both.uint_channels["Z"] = std::vector<uint32_t>(12, 0);
    EXPECT_THROW(rrc_exr::write_exr(path, both), rrc_exr::ExrError);
    rrc_exr::ExrImage empty;
    EXPECT_THROW(rrc_exr::write_exr(path, empty), rrc_exr::ExrError);
    rrc_exr::ExrImage nochannels;
    nochannels.width = nochannels.height = 2;
    EXPECT_THROW(rrc_exr::write_exr(path, nochannels), rrc_exr::ExrError);
    rrc_exr::ExrImage clash = sample_image(4, 3);  // "channels" is a standard attribute of another type
    clash.attributes["channels"] = "x";
    EXPECT_THROW(rrc_exr::write_exr(path, clash), rrc_exr::ExrError);
    EXPECT_THROW(rrc_exr::write_exr(dir / "no/such/dir/f.exr", sample_image(2, 2)), rrc_exr::ExrError);
    EXPECT_THROW(rrc_exr::write_exr(dir.path().string(), sample_image(2, 2)), rrc_exr::ExrError);

    EXPECT_EQ(file_bytes(path), before);
    EXPECT_EQ(dir_entries(dir.path()), std::vector<std::string>{"keep.exr"});
}

TEST(ExrIo, TruncatedAndGarbageFilesGiveClearErrors) {
    TempDir dir;
    const std::string good = dir / "good.exr";
    rrc_exr::ExrImage big = sample_image(64, 64);
    rrc_exr::write_exr(good, big, rrc_exr::WriteOptions{rrc_exr::Compression::None});
    const std::vector<char> bytes = file_bytes(good);
    ASSERT_GT(bytes.size(), 1000u);

    std::vector<std::string> bad_files;
    for (std::size_t keep :
         {bytes.size() - 1, bytes.size() / 2, std::size_t(400), std::size_t(100), std::size_t(20), std::size_t(4), std::size_t(0)}) {
        const std::string p = dir / ("trunc_" + std::to_string(keep) + ".exr");
        write_bytes(p, std::vector<char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(keep)));
        bad_files.push_back(p);
    }
    std::vector<char> garbage(4096);
    uint32_t x = 12345;
    for (char& c : garbage) c = static_cast<char>((x = x * 1664525u + 1013904223u) >> 24);
    write_bytes(dir / "garbage.exr", garbage);
    bad_files.push_back(dir / "garbage.exr");
    std::vector<char> magic_garbage = garbage;  // valid magic, garbage after
    std::memcpy(magic_garbage.data(), bytes.data(), 8);
    write_bytes(dir / "magic_garbage.exr", magic_garbage);
    bad_files.push_back(dir / "magic_garbage.exr");
    std::vector<char> corrupt = bytes;  // a valid header with a corrupted offset table and pixels
    for (std::size_t i = bytes.size() / 3; i < bytes.size(); i += 7) corrupt[i] = static_cast<char>(~corrupt[i]);
    write_bytes(dir / "corrupt.exr", corrupt);
    bad_files.push_back(dir / "corrupt.exr");
    std::ofstream(dir / "text.exr") << "this is not an image\n";
    bad_files.push_back(dir / "text.exr");

    for (const std::string& p : bad_files) {
        try {
            rrc_exr::read_exr(p);
            ADD_FAILURE() << "read_exr accepted " << p;
        } catch (const rrc_exr::ExrError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(p + ": ", 0), 0u) << e.what();
            EXPECT_EQ(e.path(), p);
        }
    }
    // The header-only reader refuses what has no valid header.
    for (const char* name : {"trunc_20.exr", "trunc_4.exr", "trunc_0.exr", "garbage.exr", "text.exr", "magic_garbage.exr"}) {
        try {
            rrc_exr::read_exr_info(dir / name);
            ADD_FAILURE() << "read_exr_info accepted " << name;
        } catch (const rrc_exr::ExrError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

TEST(ExrIo, MissingFileAndDirectory) {
    TempDir dir;
    for (const std::string& p : {dir / "nope.exr", dir.path().string()}) {
        EXPECT_THROW(rrc_exr::read_exr(p), rrc_exr::ExrError);
        EXPECT_THROW(rrc_exr::read_exr_info(p), rrc_exr::ExrError);
        EXPECT_THROW(rrc_exr::channel_names(p), rrc_exr::ExrError);
    }
    try {
        rrc_exr::read_exr(dir / "nope.exr");
    } catch (const rrc_exr::ExrError& e) {
        EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    }
}

// ======================================================================
// The tool's checks (no device needed: they fail before rrc_context_create)
// ======================================================================

TEST(AccumulateTool, HelpAndUsageErrors) {
    std::string out, err;
    EXPECT_EQ(run_tool({"--help"}, &out, &err), rrc_cli::kExitOk);
    EXPECT_NE(out.find("--signal"), std::string::npos);
    EXPECT_EQ(run_tool({}, &out, &err), rrc_cli::kExitUsage);  // no argument: the usage, on stderr
    EXPECT_NE(err.find("Usage: rrc-accumulate"), std::string::npos) << err;
    EXPECT_EQ(run_tool({"--frames", "x"}, &out, &err), rrc_cli::kExitUsage);
    EXPECT_NE(err.find("rrc-accumulate: "), std::string::npos) << err;
    EXPECT_NE(err.find("--frames"), std::string::npos) << err;
}

TEST(AccumulateTool, RefusesToOverwriteInputs) {
    TempDir dir;
    write_static_sequence(dir / "f_%02d.exr", 1, 3, {});
    const std::vector<char> before = file_bytes(dir / "f_02.exr");
    std::string err;
    // Frame 2's output is frame 2's input, spelled differently.
    const std::string in = dir / "f_%02d.exr";
    const std::string out = (dir.path() / "." / "f_%02d.exr").string();
    EXPECT_EQ(run_tool({"--input", in, "--output", out, "--frames", "1-3", "--quiet"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("never overwritten"), std::string::npos) << err;
    // Another pattern naming the same files.
    const std::string shifted = dir / "f_0%d.exr";
    EXPECT_EQ(run_tool({"--input", in, "--output", shifted, "--frames", "1-3"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("never overwritten"), std::string::npos) << err;
    EXPECT_EQ(file_bytes(dir / "f_02.exr"), before);
    // The camera file is an input too.
    std::ofstream(dir / "cam_2.json") << "{}";
    EXPECT_EQ(run_tool({"--input", in, "--output", dir / "cam_%d.json", "--frames", "1-3", "--camera", dir / "cam_2.json"}, nullptr, &err),
              rrc_cli::kExitError);
    EXPECT_NE(err.find("never overwritten"), std::string::npos) << err;
}

TEST(AccumulateTool, NamesTheMissingChannelOrFile) {
    TempDir dir;
    const std::string in = dir / "f_%d.exr", out = dir / "out/o_%d.exr";
    write_static_sequence(in, 1, 4, SceneOptions::dropping("prevclip.W", 3));
    std::string err;
    EXPECT_EQ(run_tool({"--input", in, "--output", out, "--frames", "1-4"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("'prevclip.W'"), std::string::npos) << err;
    EXPECT_NE(err.find("f_3.exr"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / "out")) << "processing started before the check";

    // mv.* for --reproject motion.
    EXPECT_EQ(run_tool({"--input", in, "--output", out, "--frames", "1-2", "--reproject", "motion"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("'mv.X'"), std::string::npos) << err;

    // A frame of the range that does not exist.
    EXPECT_EQ(run_tool({"--input", in, "--output", out, "--frames", "4-9"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("f_5.exr"), std::string::npos) << err;
    EXPECT_NE(err.find("no such file"), std::string::npos) << err;

    // An unknown --signal layer.
    EXPECT_EQ(run_tool({"--input", in, "--output", out, "--frames", "1-2", "--signal", "albedo"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("'albedo'"), std::string::npos) << err;

    // A frame whose size differs.
    rrc_exr::ExrImage small = rrc_exr::read_exr(dir / "f_1.exr");
    small.height = 1;
    for (auto& kv : small.channels) kv.second.resize(std::size_t(small.width));
    rrc_exr::write_exr(dir / "f_2.exr", small);
    EXPECT_EQ(run_tool({"--input", in, "--output", out, "--frames", "1-2"}, nullptr, &err), rrc_cli::kExitError);
    EXPECT_NE(err.find("f_2.exr"), std::string::npos) << err;
    EXPECT_NE(err.find("differs"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(AccumulateTool, MotionWithoutDepthChangeNeedsPlanes) {
    TempDir dir;
    write_static_sequence(dir / "f_%d.exr", 1, 2, SceneOptions::motion_vectors(false));
    std::string err;
    EXPECT_EQ(
        run_tool({"--input", dir / "f_%d.exr", "--output", dir / "o_%d.exr", "--frames", "1-2", "--reproject", "motion"}, nullptr, &err),
        rrc_cli::kExitError);
    EXPECT_NE(err.find("--near"), std::string::npos) << err;
}

TEST(AccumulateTool, CameraFileErrors) {
    TempDir dir;
    write_static_sequence(dir / "f_%d.exr", 1, 2, {});
    struct Case {
        const char* json;
        const char* fragment;
    };
    const std::string vp = "[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]";
    for (const Case& c :
         std::initializer_list<Case>{{"{", "invalid JSON"},
                                     {"[]", "expected an object"},
                                     {"{\"one\": {}}", "frame numbers"},
                                     {"{\"-1\": {}}", "frame numbers"},
                                     {"{\"1\": 5}", "expected an object"},
                                     {"{\"1\": {\"view_proj\": [1,2,3]}}", "16 numbers"},
                                     {"{\"1\": {\"view_proj\": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,\"x\"]}}", "not a number"},
                                     {"{\"1\": {\"jitter\": [0.5]}}", "jitter"},
                                     {"{\"1\": {\"view_proj\": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}}", "frame 2"},
                                     {"{\"1\": {\"view_proj\": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}, \"01\": {}}", "twice"}}) {
        std::ofstream(dir / "cam.json", std::ios::trunc) << c.json;
        std::string err;
        EXPECT_EQ(run_tool({"--input", dir / "f_%d.exr", "--output", dir / "o_%d.exr", "--frames", "1-2", "--reproject", "camera",
                            "--camera", dir / "cam.json"},
                           nullptr, &err),
                  rrc_cli::kExitError)
            << c.json;
        EXPECT_NE(err.find(c.fragment), std::string::npos) << c.json << " -> " << err;
        EXPECT_NE(err.find("cam.json"), std::string::npos) << err;
    }
    std::string err;
    EXPECT_EQ(run_tool({"--input", dir / "f_%d.exr", "--output", dir / "o_%d.exr", "--frames", "1-2", "--reproject", "camera", "--camera",
                        dir / "missing.json"},
                       nullptr, &err),
              rrc_cli::kExitError);
    EXPECT_NE(err.find("missing.json"), std::string::npos) << err;

    // A good file parses, keys with leading zeros included.
    std::ofstream(dir / "cam.json", std::ios::trunc)
        << "{\"1\": {\"view_proj\": " << vp << ", \"jitter\": [0.25, -0.5]}, \"0002\": {\"view_proj\": " << vp << "}}";
    auto frames = rrc_cli::load_camera_file(dir / "cam.json", 1, 2, true);
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[1].jitter[0], 0.25f);
    EXPECT_EQ(frames[1].jitter[1], -0.5f);
    EXPECT_EQ(frames[2].jitter[0], 0.0f);
    EXPECT_EQ(frames[2].view_proj[15], 1.0);
}

TEST(AccumulateTool, LayoutDiscovery) {
    TempDir dir;
    write_static_sequence(dir / "f_%d.exr", 1, 1, SceneOptions::rgb(true));
    rrc_cli::Options o;
    const rrc_exr::ExrInfo info = rrc_exr::read_exr_info(dir / "f_1.exr");
    const rrc_cli::SequenceLayout layout = rrc_cli::discover_layout(info, dir / "f_1.exr", o);
    EXPECT_EQ(layout.reprojection, RRC_REPROJECTION_PREV_CLIP);
    EXPECT_FALSE(layout.nocache);
    ASSERT_EQ(layout.signals.size(), 2u);  // color, shadow: alphabetical
    EXPECT_EQ(layout.signals[0].options.layer, "color");
    EXPECT_EQ(layout.signals[0].rrc_components, 4u);
    EXPECT_EQ(layout.signals[0].components, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_TRUE(layout.signals[0].confidence);
    EXPECT_EQ(layout.signals[1].options.layer, "shadow");
    EXPECT_EQ(layout.signals[1].rrc_components, 1u);
    EXPECT_FALSE(layout.signals[1].confidence);

    // RGB is padded with A = 1 for the library.
    const rrc_cli::FrameData data = rrc_cli::load_frame(rrc_exr::read_exr(dir / "f_1.exr"), dir / "f_1.exr", layout);
    ASSERT_EQ(data.samples[0].size(), std::size_t(16 * 12 * 4));
    EXPECT_EQ(data.samples[0][3], 1.0f);
    EXPECT_EQ(data.samples[0][4 * 5 + 2], 5.0f / 16.0f);
    EXPECT_EQ(data.reprojection.size(), std::size_t(16 * 12 * 4));

    std::vector<rrc_channel_desc> channels;
    o.depth_mode = RRC_DEPTH_MODE_REVERSED;
    o.signals = {};
    const rrc_context_desc d = rrc_cli::make_context_desc(o, layout, channels);
    EXPECT_EQ(d.type, RRC_STRUCT_TYPE_CONTEXT_DESC);
    EXPECT_EQ(d.size, sizeof(rrc_context_desc));
    EXPECT_EQ(d.api_version, RRC_API_VERSION);
    EXPECT_EQ(d.width, 16u);
    EXPECT_EQ(d.height, 12u);
    EXPECT_EQ(d.depth_mode, RRC_DEPTH_MODE_REVERSED);
    EXPECT_EQ(d.channel_count, 2u);
    EXPECT_EQ(d.channels, channels.data());
    EXPECT_STREQ(channels[0].name, "color");
    EXPECT_EQ(channels[0].components, 4u);
    EXPECT_EQ(channels[0].confidence, 1u);
    EXPECT_FLOAT_EQ(channels[0].lambda, 0.6f);
    EXPECT_EQ(channels[0].age_cap, 255u);
    EXPECT_EQ(d.device_name, nullptr);
    EXPECT_EQ(d.use_nocache_mask, 0u);

    // The output image writes back only the input's channels.
    rrc_cli::FrameResult result;
    const std::size_t n = 16 * 12;
    result.values = {std::vector<float>(n * 4, 0.5f), std::vector<float>(n, 0.25f)};
    result.age = {std::vector<uint16_t>(n, 3), std::vector<uint16_t>(n, 65535)};
    result.weight = {std::vector<float>(n, 0.75f), {}};
    result.mask.assign(n, RRC_MASK_HIT | RRC_MASK_REFRESHED);
    const rrc_exr::ExrImage img = rrc_cli::make_output_image(layout, result);
    EXPECT_EQ(rrc_exr::channel_names(img), (std::vector<std::string>{"color.B", "color.G", "color.R", "color.age", "color.weight",
                                                                     "rrc.mask", "shadow.Y", "shadow.age"}));
    EXPECT_EQ(img.channels.at("rrc.mask")[0], 3.0f);
    EXPECT_EQ(img.channels.at("shadow.age")[0], 65535.0f);
    EXPECT_EQ(img.channels.at("color.weight")[0], 0.75f);

    // A nocache.Y channel turns the mask on; non-zero (NaN included) means do not cache.
    {
        rrc_exr::ExrImage with_mask = rrc_exr::read_exr(dir / "f_1.exr");
        std::vector<float> m(n, 0.0f);
        m[1] = 1.0f;
        m[2] = -0.5f;
        m[3] = std::numeric_limits<float>::quiet_NaN();
        with_mask.channels["nocache.Y"] = m;
        rrc_exr::write_exr(dir / "mask.exr", with_mask);
        const rrc_cli::SequenceLayout ml = rrc_cli::discover_layout(rrc_exr::read_exr_info(dir / "mask.exr"), "m", o);
        EXPECT_TRUE(ml.nocache);
        EXPECT_EQ(ml.signals.size(), 2u);  // nocache is not a signal
        bool required = false;
        for (const rrc_cli::RequiredChannel& r : rrc_cli::required_channels(ml)) required = required || r.name == "nocache.Y";
        EXPECT_TRUE(required);
        const rrc_cli::FrameData md = rrc_cli::load_frame(rrc_exr::read_exr(dir / "mask.exr"), "m", ml);
        ASSERT_EQ(md.nocache.size(), n);
        EXPECT_EQ(md.nocache[0], 0);
        EXPECT_EQ(md.nocache[1], 1);
        EXPECT_EQ(md.nocache[2], 1);
        EXPECT_EQ(md.nocache[3], 1);
        std::vector<rrc_channel_desc> mc;
        EXPECT_EQ(rrc_cli::make_context_desc(o, ml, mc).use_nocache_mask, 1u);
    }

    // Five layers without --signal is too many.
    rrc_exr::ExrImage many = rrc_exr::read_exr(dir / "f_1.exr");
    for (const char* l : {"a.Y", "b.Y", "c.Y"}) many.channels[l] = std::vector<float>(n, 0.0f);
    many.channels["d.X"] = many.channels["d.Y"] = std::vector<float>(n, 0.0f);
    rrc_exr::write_exr(dir / "many.exr", many);
    EXPECT_THROW(rrc_cli::discover_layout(rrc_exr::read_exr_info(dir / "many.exr"), "many.exr", o), rrc_cli::CliError);
    o.signals.resize(1);
    o.signals[0].layer = "d";  // d.X + d.Y is neither Y nor RGB
    try {
        rrc_cli::discover_layout(rrc_exr::read_exr_info(dir / "many.exr"), "many.exr", o);
        ADD_FAILURE() << "layer d accepted";
    } catch (const rrc_cli::CliError& e) {
        EXPECT_NE(std::string(e.what()).find("d.X"), std::string::npos) << e.what();
    }
}

// Object ids: the preset's IndexOB when present, --object-id by name,
// --no-object-id; float ids rounded, bad ones refused naming the pixel.
TEST(AccumulateTool, ObjectIdChannel) {
    TempDir dir;
    const int w = 4, h = 3;
    rrc_exr::ExrImage img;
    img.width = w;
    img.height = h;
    for (const char* c : {"ViewLayer.Depth.Z", "ViewLayer.Vector.X", "ViewLayer.Vector.Y", "ViewLayer.Combined.R", "ViewLayer.Combined.G",
                          "ViewLayer.Combined.B", "ViewLayer.Combined.A"})
        img.channels[c] = std::vector<float>(std::size_t(w) * h, 1.0f);
    std::vector<float> index = {0.0f, 1.0f, 2.4f, 2.5f, 2.6f, -0.0f, 7.0f, 16777216.0f, 4294967040.0f, 3.0f, 0.49f, 1.0f};
    img.channels["ViewLayer.IndexOB.X"] = index;
    rrc_exr::write_exr(dir / "b_1.exr", img);
    const std::string path = dir / "b_1.exr";
    const rrc_exr::ExrInfo info = rrc_exr::read_exr_info(path);

    Options o = parse_with({"--preset", "blender"}).options;
    rrc_cli::SequenceLayout layout = rrc_cli::discover_layout(info, path, o);
    EXPECT_EQ(layout.channels.object_id, "ViewLayer.IndexOB.X");
    EXPECT_NE(layout.object_id_report.find("object ids from 'ViewLayer.IndexOB.X'"), std::string::npos) << layout.object_id_report;
    bool required = false;
    for (const rrc_cli::RequiredChannel& r : rrc_cli::required_channels(layout)) required = required || r.name == "ViewLayer.IndexOB.X";
    EXPECT_TRUE(required) << "every frame needs the ids once the first has them";
    const rrc_cli::FrameData data = rrc_cli::load_frame(rrc_exr::read_exr(path), path, layout);
    EXPECT_EQ(data.object_id, (std::vector<uint32_t>{0, 1, 2, 3, 3, 0, 7, 16777216u, 4294967040u, 3, 0, 1}));
    std::vector<rrc_channel_desc> channels;
    rrc_context_desc d = rrc_cli::make_context_desc(o, layout, channels);
    EXPECT_EQ(d.use_object_id, 1u);
    EXPECT_EQ(d.depth_test, RRC_DEPTH_TEST_DEFAULT);

    // --no-object-id: none, and said so.
    o = parse_with({"--preset", "blender", "--no-object-id", "--depth-test", "fixed"}).options;
    layout = rrc_cli::discover_layout(info, path, o);
    EXPECT_TRUE(layout.channels.object_id.empty());
    EXPECT_NE(layout.object_id_report.find("--no-object-id"), std::string::npos) << layout.object_id_report;
    EXPECT_TRUE(rrc_cli::load_frame(rrc_exr::read_exr(path), path, layout).object_id.empty());
    d = rrc_cli::make_context_desc(o, layout, channels);
    EXPECT_EQ(d.use_object_id, 0u);
    EXPECT_EQ(d.depth_test, RRC_DEPTH_TEST_FIXED);

    // A file without IndexOB: the preset goes without ids and says why.
    rrc_exr::ExrImage plain = img;
    plain.channels.erase("ViewLayer.IndexOB.X");
    rrc_exr::write_exr(dir / "p_1.exr", plain);
    o = parse_with({"--preset", "blender"}).options;
    layout = rrc_cli::discover_layout(rrc_exr::read_exr_info(dir / "p_1.exr"), dir / "p_1.exr", o);
    EXPECT_TRUE(layout.channels.object_id.empty());
    EXPECT_NE(layout.object_id_report.find("no object ids: " + dir / "p_1.exr" + " has no 'ViewLayer.IndexOB.X'"), std::string::npos)
        << layout.object_id_report;
    EXPECT_EQ(rrc_cli::make_context_desc(o, layout, channels).use_object_id, 0u);

    // By name, without the preset: required, and not a signal.
    o = parse_with({"--object-id", "ViewLayer.IndexOB.X", "--depth-mode", "linear", "--reproject", "motion", "--motion-channels",
                    "ViewLayer.Vector.X,ViewLayer.Vector.Y", "--depth-channel", "ViewLayer.Depth.Z"})
            .options;
    layout = rrc_cli::discover_layout(info, path, o);
    EXPECT_EQ(layout.channels.object_id, "ViewLayer.IndexOB.X");
    ASSERT_EQ(layout.signals.size(), 1u);
    EXPECT_EQ(layout.signals[0].options.layer, "ViewLayer.Combined");
    try {
        rrc_cli::check_frame_header(rrc_exr::read_exr_info(dir / "p_1.exr"), dir / "p_1.exr", layout);
        ADD_FAILURE() << "a frame without the named id channel passed";
    } catch (const rrc_cli::CliError& e) {
        EXPECT_NE(std::string(e.what()).find("missing channel 'ViewLayer.IndexOB.X'"), std::string::npos) << e.what();
    }

    // UINT ids are exact, beyond float's 2^24 too.
    rrc_exr::ExrImage u;
    u.width = 2;
    u.height = 1;
    u.uint_channels["id"] = {16777217u, 4294967295u};
    EXPECT_EQ(rrc_cli::object_ids_of(u, "id", "u.exr"), (std::vector<uint32_t>{16777217u, 4294967295u}));

    // Not an object id: the file, the channel and the pixel (x, y) are named.
    struct Bad {
        float value;
        const char* shown;
    };
    for (const Bad& b : {Bad{-1.0f, "holds -1"}, Bad{-0.25f, "holds -0.25"}, Bad{std::numeric_limits<float>::quiet_NaN(), "holds nan"},
                         Bad{std::numeric_limits<float>::infinity(), "holds inf"}, Bad{4294967296.0f, "holds 4294967296"}}) {
        rrc_exr::ExrImage bad = rrc_exr::read_exr(path);
        bad.channels["ViewLayer.IndexOB.X"][std::size_t(1) * w + 2] = b.value;  // pixel (2, 1)
        try {
            rrc_cli::object_ids_of(bad, "ViewLayer.IndexOB.X", "frames/b_0007.exr");
            ADD_FAILURE() << b.shown << " accepted";
        } catch (const rrc_cli::CliError& e) {
            const std::string m = e.what();
            for (const std::string& part : {std::string("frames/b_0007.exr: "), std::string("'ViewLayer.IndexOB.X'"),
                                            std::string("pixel (2, 1)"), std::string(b.shown)})
                EXPECT_NE(m.find(part), std::string::npos) << "'" << m << "' lacks '" << part << "'";
        }
    }
}

// ======================================================================
// End to end through the library (skipped when no Vulkan device exists)
// ======================================================================

// --preset blender without --signal accumulates <view layer>.Combined with
// the preset's own lambda, blend and filter (docs/measurements/OFFLINE.md, section 7:
// chosen from the error against render time on Cycles sequences), and they
// reach the library's channel description; an explicit --signal keeps the
// tool's defaults and its own keys.
TEST(AccumulateTool, BlenderPresetSignalDefaults) {
    // The values section 7 documents: a change here is a change there.
    EXPECT_FLOAT_EQ(rrc_cli::blender_preset_channel().lambda, 0.85f);
    EXPECT_EQ(rrc_cli::blender_preset_channel().blend, RRC_BLEND_AGE_AWARE);
    EXPECT_EQ(rrc_cli::blender_preset_channel().filter, RRC_HISTORY_FILTER_BILINEAR);
    EXPECT_EQ(rrc_cli::blender_preset_channel().fill_age, 4u);
    EXPECT_EQ(rrc_cli::blender_preset_channel().rectify, 1u);

    TempDir dir;
    rrc_exr::ExrImage img;
    img.width = 4;
    img.height = 3;
    for (const char* c : {"ViewLayer.Depth.Z", "ViewLayer.Vector.X", "ViewLayer.Vector.Y", "ViewLayer.Combined.R", "ViewLayer.Combined.G",
                          "ViewLayer.Combined.B", "ViewLayer.Combined.A", "ViewLayer.Shadow.X"})
        img.channels[c] = std::vector<float>(12, 1.0f);
    rrc_exr::write_exr(dir / "b_1.exr", img);
    const std::string path = dir / "b_1.exr";
    const rrc_exr::ExrInfo info = rrc_exr::read_exr_info(path);

    Options o = parse_with({"--preset", "blender"}).options;
    rrc_cli::SequenceLayout layout = rrc_cli::discover_layout(info, path, o);
    ASSERT_EQ(layout.signals.size(), 1u);
    EXPECT_EQ(layout.signals[0].options.layer, "ViewLayer.Combined");
    EXPECT_FLOAT_EQ(layout.signals[0].options.lambda, 0.85f);
    EXPECT_EQ(layout.signals[0].options.blend, RRC_BLEND_AGE_AWARE);
    EXPECT_EQ(layout.signals[0].options.filter, RRC_HISTORY_FILTER_BILINEAR);
    EXPECT_EQ(layout.signals[0].options.fill_age, 4u);
    EXPECT_EQ(layout.signals[0].options.rectify, 1u);
    EXPECT_EQ(layout.signals[0].options.rectify_gamma, 0.0f);  // the library's default
    EXPECT_EQ(layout.signals[0].options.history, RRC_HISTORY_FP16);  // the tool's default
    EXPECT_EQ(layout.signals[0].options.max_age, 255u);
    std::vector<rrc_channel_desc> channels;
    const rrc_context_desc preset_desc = rrc_cli::make_context_desc(o, layout, channels);
    ASSERT_EQ(channels.size(), 1u);
    EXPECT_FLOAT_EQ(channels[0].lambda, 0.85f);
    EXPECT_EQ(channels[0].blend, RRC_BLEND_AGE_AWARE);
    EXPECT_EQ(channels[0].filter, RRC_HISTORY_FILTER_BILINEAR);
    EXPECT_EQ(channels[0].fill_age, 4u);
    EXPECT_EQ(channels[0].fill_radius, 0u);  // the library's default window
    EXPECT_EQ(channels[0].rectify, 1u);
    EXPECT_EQ(channels[0].antilag, 0u);
    EXPECT_EQ(channels[0].blur_bound, 0.0f);
    EXPECT_EQ(rrc_validate_context_desc(&preset_desc), RRC_SUCCESS) << rrc_last_error();
    EXPECT_NE(rrc_cli::usage_text().find("lambda=0.85,blend=age_aware,filter=bilinear,fill=4,rectify=on"), std::string::npos);

    // Explicit signals: the tool's defaults where no key is given, the keys where they are.
    o = parse_with({"--preset", "blender", "--signal", "ViewLayer.Combined", "--signal", "ViewLayer.Shadow:lambda=0.7,filter=nearest"}).options;
    layout = rrc_cli::discover_layout(info, path, o);
    ASSERT_EQ(layout.signals.size(), 2u);
    EXPECT_FLOAT_EQ(layout.signals[0].options.lambda, 0.6f);
    EXPECT_EQ(layout.signals[0].options.blend, RRC_BLEND_FIXED);
    EXPECT_EQ(layout.signals[0].options.filter, RRC_HISTORY_FILTER_BILINEAR);
    EXPECT_FLOAT_EQ(layout.signals[1].options.lambda, 0.7f);
    EXPECT_EQ(layout.signals[1].options.blend, RRC_BLEND_FIXED);
    EXPECT_EQ(layout.signals[1].options.filter, RRC_HISTORY_FILTER_NEAREST);
    EXPECT_EQ(layout.signals[0].options.fill_age, 0u);
    EXPECT_EQ(layout.signals[0].options.rectify, 0u);
    o = parse_with({"--preset", "blender", "--signal", "ViewLayer.Combined:fill=8,fill_radius=1,fill_tolerance=0.01"}).options;
    layout = rrc_cli::discover_layout(info, path, o);
    rrc_cli::make_context_desc(o, layout, channels);
    ASSERT_EQ(channels.size(), 1u);
    EXPECT_EQ(channels[0].fill_age, 8u);
    EXPECT_EQ(channels[0].fill_radius, 1u);
    EXPECT_FLOAT_EQ(channels[0].fill_depth_tolerance, 0.01f);
    EXPECT_EQ(channels[0].rectify, 0u);
    EXPECT_EQ(channels[0].antilag, 0u);
    EXPECT_EQ(channels[0].blur_bound, 0.0f);
    // The cures reach the channel, and the library accepts them as given.
    o = parse_with({"--preset", "blender", "--signal",
                    "ViewLayer.Combined:lambda=0.85,blend=age_aware,rectify=on,rectify_gamma=1.5,antilag=on,antilag_gamma=0.5,"
                    "antilag_threshold=0.25,blur_bound=0.5,gate=2"})
            .options;
    layout = rrc_cli::discover_layout(info, path, o);
    const rrc_context_desc cured = rrc_cli::make_context_desc(o, layout, channels);
    ASSERT_EQ(channels.size(), 1u);
    EXPECT_EQ(channels[0].rectify, 1u);
    EXPECT_FLOAT_EQ(channels[0].rectify_gamma, 1.5f);
    EXPECT_EQ(channels[0].antilag, 1u);
    EXPECT_FLOAT_EQ(channels[0].antilag_gamma, 0.5f);
    EXPECT_FLOAT_EQ(channels[0].antilag_threshold, 0.25f);
    EXPECT_FLOAT_EQ(channels[0].blur_bound, 0.5f);
    EXPECT_FLOAT_EQ(channels[0].gate_kappa, 2.0f);
    EXPECT_EQ(rrc_validate_context_desc(&cured), RRC_SUCCESS) << rrc_last_error();

    // Without the preset the automatic signals keep the tool's defaults too.
    const rrc_cli::SignalOptions plain;
    EXPECT_FLOAT_EQ(plain.lambda, 0.6f);
    EXPECT_EQ(plain.blend, RRC_BLEND_FIXED);
}

TEST(AccumulateTool, StaticSequenceEndToEnd) {
    TempDir dir;
    write_static_sequence(dir / "in/f_%03d.exr", 5, 7, SceneOptions::rgb());
    std::string out, err;
    const int rc = run_tool({"--input", dir / "in/f_%03d.exr", "--output", dir / "out/acc_%03d.exr", "--frames", "5-7", "--signal",
                             "shadow:history=fp32", "--signal", "color:history=fp32,lambda=0.5"},
                            &out, &err);
    ASSERT_EQ(rc, 0) << err;  // the suite runs on lavapipe: no device is a failure
    EXPECT_NE(out.find("frame 5:"), std::string::npos) << out;
    EXPECT_NE(out.find("frame 7:"), std::string::npos) << out;
    EXPECT_NE(out.find("3 frames"), std::string::npos) << out;
    EXPECT_NE(out.find("device"), std::string::npos) << out;

    const std::size_t n = 16 * 12;
    std::vector<rrc_exr::ExrImage> res;
    for (int f = 5; f <= 7; ++f) {
        res.push_back(rrc_exr::read_exr(rrc_cli::format_frame_path(dir / "out/acc_%03d.exr", f)));
        EXPECT_EQ(rrc_exr::channel_names(res.back()),
                  (std::vector<std::string>{"color.B", "color.G", "color.R", "color.age", "rrc.mask", "shadow.Y", "shadow.age"}));
    }
    // Frame 5 is a full miss: out = sample, age 1.
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(int(res[0].channels["rrc.mask"][i]) & RRC_MASK_HIT, 0);
        EXPECT_EQ(res[0].channels["shadow.age"][i], 1.0f);
        EXPECT_EQ(res[0].channels["color.R"][i], 1.25f);
    }
    // Static geometry: every later pixel hits and blends.  color.R is 0.25 f.
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_NE(int(res[1].channels["rrc.mask"][i]) & RRC_MASK_HIT, 0) << i;
        EXPECT_EQ(res[1].channels["color.age"][i], 2.0f);
        EXPECT_EQ(res[2].channels["color.age"][i], 3.0f);
        EXPECT_NEAR(res[1].channels["color.R"][i], 0.5f * 1.25f + 0.5f * 1.5f, 1e-4f);
        EXPECT_NEAR(res[2].channels["color.R"][i], 0.5f * 1.375f + 0.5f * 1.75f, 1e-4f);
        EXPECT_NEAR(res[1].channels["color.G"][i], 0.5f, 1e-4f);
    }
    // The inputs are untouched and nothing else was written.
    EXPECT_EQ(dir_entries(dir.path() / "out"), (std::vector<std::string>{"acc_005.exr", "acc_006.exr", "acc_007.exr"}));
}

namespace {

// Frames 5-7 of write_static_sequence (RGB color) with object ids obj.X: 1 everywhere, from frame 6
// 2 on the right half.  clean_color: color.R the same every frame (color then never changes).
void write_object_id_sequence(const std::string& pattern, int w, int h, bool clean_color) {
    write_static_sequence(pattern, 5, 7, SceneOptions::rgb());
    for (int f = 5; f <= 7; ++f) {
        const std::string path = rrc_cli::format_frame_path(pattern, f);
        rrc_exr::ExrImage img = rrc_exr::read_exr(path);
        std::vector<float>& id = img.channels["obj.X"];
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) id.push_back(f >= 6 && i >= w / 2 ? 2.0f : 1.0f);
        if (clean_color) img.channels["color.R"].assign(std::size_t(w) * h, 0.3f);
        rrc_exr::write_exr(path, img);
    }
}

}  // namespace

// Object ids through the library: a still camera, so every pixel reprojects
// onto its own texel (weight 1; its neighbours' weights are 0 up to fp32
// rounding).  Frame 6 gives the right half a new id: with --object-id those
// pixels miss (their previous texel is on another object), the left half
// hits, and frame 7 (same ids as 6) hits again away from the id boundary.
// Without --object-id every pixel hits, ids or not.
TEST(AccumulateTool, ObjectIdsEndToEnd) {
    TempDir dir;
    const int w = 16, h = 12;
    write_object_id_sequence(dir / "in/f_%d.exr", w, h, false);
    auto masks = [&](std::vector<std::string> extra, const std::string& out_dir) {
        std::vector<std::string> args = {"--input", dir / "in/f_%d.exr", "--output", dir / (out_dir + "/%d.exr"), "--frames", "5-7"};
        args.insert(args.end(), extra.begin(), extra.end());
        std::string out, err;
        EXPECT_EQ(run_tool(args, &out, &err), 0) << err;
        std::vector<std::vector<float>> m;
        for (int f = 5; f <= 7; ++f)
            m.push_back(rrc_exr::read_exr(rrc_cli::format_frame_path(dir / (out_dir + "/%d.exr"), f)).channels.at("rrc.mask"));
        return std::make_pair(m, out);
    };
    const auto [with_ids, ids_text] = masks({"--object-id", "obj.X"}, "ids");
    const auto [without, none_text] = masks({}, "none");
    EXPECT_NE(ids_text.find("object ids from 'obj.X'"), std::string::npos) << ids_text;
    EXPECT_EQ(none_text.find("object ids"), std::string::npos) << "no ids asked, nothing to report: " << none_text;
    const std::vector<std::string> names = rrc_exr::channel_names(rrc_exr::read_exr(dir / "ids/6.exr"));
    EXPECT_EQ(std::count(names.begin(), names.end(), "obj.X"), 0) << "the id channel is not accumulated as a signal";
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const std::size_t k = std::size_t(j) * w + i;
            const bool right = i >= w / 2, boundary = i == w / 2 - 1 || i == w / 2;
            for (int t = 1; t <= 2; ++t) EXPECT_TRUE(int(without[t][k]) & RRC_MASK_HIT) << "frame " << 5 + t << " pixel " << k;
            EXPECT_EQ(bool(int(with_ids[1][k]) & RRC_MASK_HIT), !right) << "frame 6 pixel (" << i << ", " << j << ")";
            if (!boundary) EXPECT_TRUE(int(with_ids[2][k]) & RRC_MASK_HIT) << "frame 7 pixel (" << i << ", " << j << ")";
        }
}

// ======================================================================
// --clean-report: the output against its own input, by region
// (clean_regions.h; docs/measurements/OFFLINE.md, "What rrc adds to a clean input")
// ======================================================================

TEST(AccumulateOptions, CleanReportAndFrom) {
    ParseResult r = parse_with({"--clean-report", "out/clean.md", "--from", "2"});
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.options.clean_report, "out/clean.md");
    EXPECT_EQ(r.options.clean_from, 2);
    // The error study's default first frame, or the range's first when the range ends before it.
    EXPECT_EQ(parse({"--input", "i/%d.exr", "--output", "o/%d.exr", "--frames", "0-20", "--clean-report", "c.csv"}).options.clean_from, 8);
    EXPECT_EQ(parse_with({"--clean-report", "c.csv"}).options.clean_from, 1);
    expect_error(parse_with({"--clean-report", "clean.txt"}), "--clean-report");
    expect_error(parse_with({"--from", "2"}), "--from needs --clean-report");
    expect_error(parse_with({"--clean-report", "c.md", "--from", "4"}), "after the last frame");
}

namespace {

// A CleanFrame over vectors the test owns.
struct HandFrame {
    uint32_t w, h;
    std::vector<uint8_t> mask;
    std::vector<uint16_t> age;
    std::vector<float> u;
    std::vector<uint32_t> id;
    rrc_host::CleanFrame frame(uint32_t fill_age, bool ids) const {
        rrc_host::CleanFrame f;
        f.width = w, f.height = h, f.mask = mask.data(), f.age = age.data(), f.inverse_depth = u.data();
        f.object_id = ids ? id.data() : nullptr;
        f.fill_age = fill_age;
        return f;
    }
};

}  // namespace

// An 8x4 frame: a plane whose u (1/depth) falls linearly from left to right (no seed: its second
// difference is 0) except column 6, a surface in front (a jump); pixel (0, 0) is background;
// column 2 misses; columns 0-1 are hits of age 2, columns 3-5 hits of age 9.
TEST(CleanRegions, HandMadeFrame) {
    HandFrame g{8, 4};
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            g.u.push_back(x == 6 ? 2.0f : 1.0f - 0.05f * x);
            g.mask.push_back(x == 2 ? 0 : RRC_MASK_HIT);
            g.age.push_back(x == 2 ? 1 : x < 2 ? 2 : 9);
            g.id.push_back(1);
        }
    g.mask[0] = RRC_MASK_BACKGROUND, g.age[0] = 0, g.u[0] = 0.0f;
    using namespace rrc_host;
    // Seeds: (0, 0) the background, and (1, 0) and (0, 1) whose second differences reach it; the
    // jump at column 6 seeds columns 5 and 6.  Dilated by 1 px: columns 0-2 of rows 0-1, columns
    // 0-1 of row 2, and columns 4-7.
    const std::vector<uint8_t> r = clean_regions(g.frame(0, false));
    auto at = [&](uint32_t x, uint32_t y) { return (int)r[y * 8 + x]; };
    EXPECT_EQ(at(0, 0), kCleanBackground);
    EXPECT_EQ(at(2, 1), kCleanEdge);
    EXPECT_EQ(at(1, 2), kCleanEdge);
    EXPECT_EQ(at(0, 3), kCleanYoung);  // age 2 < 4, a hit
    EXPECT_EQ(at(2, 2), kCleanMiss);
    EXPECT_EQ(at(2, 3), kCleanMiss);
    EXPECT_EQ(at(3, 2), kCleanHistory);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 4; x < 8; ++x) EXPECT_EQ(at(x, y), kCleanEdge) << x << "," << y;
    // With a fill of age 3 the young hit and the miss (age 1) are filled; age 9 is still history.
    const std::vector<uint8_t> filled = clean_regions(g.frame(3, false));
    EXPECT_EQ((int)filled[3 * 8 + 0], kCleanFilled);
    EXPECT_EQ((int)filled[3 * 8 + 2], kCleanFilled);
    EXPECT_EQ((int)filled[2 * 8 + 3], kCleanHistory);
    // An object-id boundary between columns 2 and 3 makes columns 1-4 edges.
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 3; x < 8; ++x) g.id[y * 8 + x] = 2;
    const std::vector<uint8_t> ids = clean_regions(g.frame(0, true));
    EXPECT_EQ((int)ids[3 * 8 + 1], kCleanEdge);
    EXPECT_EQ((int)ids[3 * 8 + 0], kCleanYoung);
    EXPECT_EQ((int)ids[3 * 8 + 2], kCleanEdge);
    EXPECT_EQ(clean_regions(g.frame(0, false))[3 * 8 + 2], (uint8_t)kCleanMiss) << "ids only count when given";

    // The errors: identity gives 0, a perturbed output more, and the regions add up to the total.
    std::vector<float> in(32), out(32);
    for (size_t p = 0; p < 32; ++p) in[p] = out[p] = 0.1f * (float)p;
    CleanSums same;
    add_clean_errors(same, r, in.data(), out.data(), 1, 1);
    EXPECT_EQ(same.total_sse(), 0.0);
    EXPECT_EQ(same.total_pixels(), 32u);
    out[3 * 8 + 2] += 0.5f;  // a miss
    out[2 * 8 + 3] -= 0.25f; // history
    out[1 * 8 + 1] = std::numeric_limits<float>::quiet_NaN();
    CleanSums s;
    add_clean_errors(s, r, in.data(), out.data(), 1, 1);
    EXPECT_NEAR(s.sse[kCleanMiss], 0.25, 1e-6);
    EXPECT_NEAR(s.sse[kCleanHistory], 0.0625, 1e-6);
    EXPECT_NEAR(s.total_sse(), 0.3125, 1e-6);
    EXPECT_EQ(s.skipped, 1u);
    EXPECT_EQ(s.total_pixels(), 31u);
    EXPECT_NEAR(s.rmse(kCleanRegionCount), std::sqrt(0.3125 / 31.0), 1e-7);
    EXPECT_NE(clean_table(s).find("| miss | 0.3536 | 80.0% | 6.5% |"), std::string::npos) << clean_table(s);
}

namespace {

// rrc-accumulate --clean-report FILE.csv's rows: (frame, layer, region) -> (pixels, sse).
std::map<std::string, std::pair<uint64_t, double>> clean_rows(const std::string& path) {
    std::map<std::string, std::pair<uint64_t, double>> rows;
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "frame,layer,region,pixels,values,sse,rmse");
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string item; std::getline(ss, item, ',');) f.push_back(item);
        if (f.size() != 7) {
            ADD_FAILURE() << line;
            continue;
        }
        rows[f[0] + "/" + f[1] + "/" + f[2]] = {std::stoull(f[3]), std::stod(f[5])};
    }
    return rows;
}

}  // namespace

// Three frames of a still camera; frame 6 gives the right half a new object id, so with ids its
// pixels miss (docs/measurements/OFFLINE.md, "Object ids"): at frame 6 columns 6-9 are edges (within 1 px of the
// boundary between 7 and 8), 10-15 misses, 0-5 young hits (age 2).  color.G and color.B are the same
// every frame (a clean input: rrc must return it), shadow.Y flips every frame (what rrc averages).
TEST(AccumulateTool, CleanReportByRegion) {
    TempDir dir;
    const int w = 16, h = 12;
    write_object_id_sequence(dir / "in/f_%d.exr", w, h, true);
    std::string out, err;
    ASSERT_EQ(run_tool({"--input", dir / "in/f_%d.exr", "--output", dir / "out/%d.exr", "--frames", "5-7", "--object-id", "obj.X",
                        "--signal", "shadow:history=fp32", "--signal", "color:history=fp32", "--clean-report", dir / "clean.csv",
                        "--quiet"},
                       &out, &err),
              0)
        << err;
    EXPECT_NE(out.find("shadow against its own input, frames 5-7"), std::string::npos) << out;
    const auto rows = clean_rows(dir / "clean.csv");
    auto pixels = [&](const std::string& key) { return rows.count(key) ? rows.at(key).first : 999u; };
    auto sse = [&](const std::string& key) { return rows.count(key) ? rows.at(key).second : -1.0; };
    // Frame 5 misses everywhere: out = s, no error.
    EXPECT_EQ(pixels("5/shadow/miss"), 192u);
    EXPECT_EQ(sse("5/shadow/all"), 0.0);
    EXPECT_EQ(pixels("6/shadow/edge"), 48u);
    EXPECT_EQ(pixels("6/shadow/miss"), 72u);
    EXPECT_EQ(pixels("6/shadow/young"), 72u);
    EXPECT_EQ(pixels("6/shadow/history"), 0u);
    EXPECT_EQ(sse("6/shadow/miss"), 0.0);
    // The flipping signal: a blend is never the frame's own sample (lambda 0.6: 0.6 away on each hit).
    EXPECT_NEAR(sse("6/shadow/young"), 72 * 0.36, 1e-3);
    // The clean one: what rrc adds is nothing but rounding.
    EXPECT_LT(sse("7/color/all"), 1e-8);
    for (int f = 5; f <= 7; ++f)
        for (const char* layer : {"shadow", "color"}) {
            const std::string pre = std::to_string(f) + "/" + layer + "/";
            uint64_t n = 0;
            double e = 0.0;
            for (int r = 0; r < rrc_host::kCleanRegionCount; ++r) {
                n += pixels(pre + rrc_host::clean_region_name(r));
                e += sse(pre + rrc_host::clean_region_name(r));
            }
            EXPECT_EQ(n, pixels(pre + "all")) << pre;
            EXPECT_EQ(n, 192u) << pre;
            EXPECT_NEAR(e, sse(pre + "all"), 1e-9 + 1e-6 * e) << pre;
        }
    // The markdown form: the summary's tables.
    ASSERT_EQ(run_tool({"--input", dir / "in/f_%d.exr", "--output", dir / "out2/%d.exr", "--frames", "5-7", "--signal", "shadow",
                        "--clean-report", dir / "clean.md", "--from", "6", "--quiet"},
                       &out, &err),
              0)
        << err;
    std::ifstream md(dir / "clean.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("frames 6-7 (2 frames)"), std::string::npos) << text;
    EXPECT_NE(text.find("| history |"), std::string::npos) << text;
}
