// rrc-accumulate on offline renderers' sequences (docs/measurements/OFFLINE.md):
//   - a synthetic sequence in Blender 3.x's multilayer conventions
//     (ViewLayer.Combined/Depth/Vector, linear depth with the sky at 1e10,
//     vectors previous-minus-current in pixels with y up, half and float
//     channels, single- and multi-part files) accumulated with
//     --preset blender and checked pixel by pixel against the
//     double-precision reference fed the SPEC-convention data of the same
//     analytic scene, so the mapping itself is checked;
//   - the bad-input errors (missing channel, sizes, missing frame,
//     truncated file, corrupt header, corrupt pixel data, outputs over
//     inputs), each with a clear message, a non-zero exit and no partial file;
//   - the reference metrics (CSV, summary), the PNG coherence maps, the
//     progress output, camera cuts and channel mapping by name;
//   - the preset's depth tolerance: hit and false-hit rates measured against
//     exact visibility (the table in docs/measurements/OFFLINE.md);
//   - object ids (Blender's IndexOB) on the committed real render: with them
//     no hit takes a bilinear tap from another object, and without them the
//     tool behaves as before (the table in docs/measurements/OFFLINE.md).
#include "accumulate.h"
#include "enum_names.h"
#include "object_index_hits.h"
#include "options.h"
#include "sequence.h"

#include <exr_io.h>
#include <png_io.h>

#include "reference/rrc_reference.h"
#include "scenes/false_hits.h"
#include "scenes/scene.h"
#include "support/rrc_test_context.h"
#include "support/tolerance.h"

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace rrc_cli_test;

const std::string kLayer = "ViewLayer.";

// The signal --preset blender accumulates without --signal, spelt out as a
// --signal (options.h: blender_preset_channel(), the library's RRC_PRESET_OFFLINE:
// lambda, blend, filter, fill age, rectify).
std::string preset_signal() {
    char lambda[32];
    std::snprintf(lambda, sizeof lambda, "%g", static_cast<double>(rrc_cli::blender_preset_channel().lambda));
    return kLayer + "Combined:lambda=" + lambda + ",blend=" + rrc_host::enum_name(rrc_host::kBlendNames, rrc_cli::blender_preset_channel().blend) +
           ",filter=" + rrc_host::enum_name(rrc_host::kHistoryFilterNames, rrc_cli::blender_preset_channel().filter) +
           ",fill=" + std::to_string(rrc_cli::blender_preset_channel().fill_age) + ",rectify=" + (rrc_cli::blender_preset_channel().rectify ? "on" : "off");
}

std::string frame_path(const std::string& pattern, int f) { return rrc_cli::format_frame_path(pattern, f); }

void expect_contains(const std::string& text, const std::string& fragment) {
    EXPECT_NE(text.find(fragment), std::string::npos) << "'" << text << "' lacks '" << fragment << "'";
}

// ---- a synthetic sequence in Blender 3.x's conventions ------------------

rrc_scene::SceneConfig blender_scene_config(int w, int h) {
    rrc_scene::SceneConfig sc;
    sc.width = w;
    sc.height = h;
    sc.depth_mode = RRC_DEPTH_MODE_LINEAR;
    sc.linear_background = 1e10f;  // Blender's sky
    sc.jitter = false;             // Blender's Depth is the pixel-centre sample (docs/measurements/OFFLINE.md)
    return sc;
}

struct BlenderWrite {
    bool half_combined_odd = true;  // Combined as HALF in odd frames, FLOAT in even ones
    bool multipart_even = true;     // even frames: one part per layer
    std::string drop;               // a channel left out of frame drop_frame
    int drop_frame = -1;
    bool truth = false;  // the noise-free signals (a converged reference)
};

// Frame t of `scene` as Blender 3.x writes it: Combined.R/G/B/A (signal4),
// Shadow.X (signal1, a one-channel pass), Depth.Z (planar depth, sky 1e10),
// Vector.X/Y (previous minus current, pixels, y up; zero on the sky),
// Vector.Z/W (current minus next, same units), IndexOB.X.
rrc_exr::ExrImage blender_frame(const rrc_scene::Scene& scene, const rrc_scene::Frame& fr, const BlenderWrite& opt) {
    const int W = fr.width, H = fr.height;
    const std::size_t n = std::size_t(W) * H;
    rrc_exr::ExrImage img;
    img.width = W;
    img.height = H;
    auto ch = [&](const std::string& name) -> std::vector<float>& { return img.channels[kLayer + name] = std::vector<float>(n, 0.0f); };
    auto &cr = ch("Combined.R"), &cg = ch("Combined.G"), &cb = ch("Combined.B"), &ca = ch("Combined.A");
    auto& shadow = ch("Shadow.X");
    auto& depth = ch("Depth.Z");
    auto &vx = ch("Vector.X"), &vy = ch("Vector.Y"), &vz = ch("Vector.Z"), &vw = ch("Vector.W");
    auto& index = ch("IndexOB.X");
    const glm::dmat4 vp_next = scene.view_proj(fr.index + 1);
    for (std::size_t i = 0; i < n; ++i) {
        const std::vector<float>& s4 = opt.truth ? fr.truth4 : fr.signal4;
        const std::vector<float>& s1 = opt.truth ? fr.truth1 : fr.signal1;
        cr[i] = s4[4 * i];
        cg[i] = s4[4 * i + 1];
        cb[i] = s4[4 * i + 2];
        ca[i] = s4[4 * i + 3];
        shadow[i] = s1[i];
        depth[i] = fr.depth[i];
        const int32_t id = fr.object_id[i];
        index[i] = float(id + 1);
        if (id < 0) continue;  // Blender: zero vectors on the sky
        vx[i] = float(double(fr.motion[3 * i]) * W);
        vy[i] = float(-double(fr.motion[3 * i + 1]) * H);
        const glm::dvec3 p_next = scene.model(id, fr.index + 1).to_world(fr.object_pos[i]);
        const glm::dvec4 c = vp_next * glm::dvec4(p_next, 1.0);
        const double ux = ((i % W) + 0.5) / W, uy = ((i / W) + 0.5) / H;
        vz[i] = float((ux - (c.x / c.w + 1.0) / 2.0) * W);
        vw[i] = float(-(uy - (c.y / c.w + 1.0) / 2.0) * H);
    }
    if (opt.drop_frame == fr.index) img.channels.erase(opt.drop);
    return img;
}

void write_blender_sequence(const rrc_scene::Scene& scene, const std::string& pattern, int first, int last, const BlenderWrite& opt = {}) {
    for (int t = first; t <= last; ++t) {
        const rrc_scene::Frame fr = scene.render(t);
        rrc_exr::WriteOptions wo;
        if (opt.half_combined_odd && (t & 1))
            for (const char* c : {"Combined.R", "Combined.G", "Combined.B", "Combined.A"}) wo.half_channels.push_back(kLayer + c);
        wo.multipart_by_layer = opt.multipart_even && !(t & 1);
        const std::string path = frame_path(pattern, t);
        fs::create_directories(fs::path(path).parent_path());
        rrc_exr::write_exr(path, blender_frame(scene, fr, opt), wo);
    }
}

std::vector<float> interleave(const rrc_exr::ExrImage& img, const std::vector<std::string>& names) {
    const std::size_t n = img.pixel_count(), k = names.size();
    std::vector<float> out(n * k);
    for (std::size_t c = 0; c < k; ++c) {
        const std::vector<float>& v = img.channels.at(names[c]);
        for (std::size_t i = 0; i < n; ++i) out[i * k + c] = v[i];
    }
    return out;
}

const std::vector<std::string> kCombined = {kLayer + "Combined.R", kLayer + "Combined.G", kLayer + "Combined.B", kLayer + "Combined.A"};

// Frames 2-3 of a 3-frame Blender render (`in`) against the tool's masks
// (`out`), counted as rrc-blender-check --hits counts them
// (object_index_hits.h).  `per_pixel` gets frame 2's pixels, then frame 3's.
rrc_cli::ObjectIndexHits count_real_render_hits(const std::string& in, const std::string& out,
                                                std::vector<rrc_cli::TapObjects>* per_pixel = nullptr) {
    rrc_cli::ObjectIndexHits total;
    if (per_pixel) per_pixel->clear();
    for (int f = 2; f <= 3; ++f) {
        const std::string cur_path = frame_path(in, f), prev_path = frame_path(in, f - 1);
        const rrc_exr::ExrImage cur = rrc_exr::read_exr(cur_path), prev = rrc_exr::read_exr(prev_path);
        const std::vector<float> mask = rrc_exr::read_exr(frame_path(out, f)).channels.at("rrc.mask");
        std::vector<rrc_cli::TapObjects> taps;
        // The tool's own conversion, so the ids counted are the ids rrc got.
        total += rrc_cli::count_object_index_hits(cur.width, cur.height, mask, rrc_cli::object_ids_of(cur, kLayer + "IndexOB.X", cur_path),
                                                  rrc_cli::object_ids_of(prev, kLayer + "IndexOB.X", prev_path),
                                                  cur.channels.at(kLayer + "Vector.X"), cur.channels.at(kLayer + "Vector.Y"), &taps);
        if (per_pixel) per_pixel->insert(per_pixel->end(), taps.begin(), taps.end());
    }
    return total;
}

}  // namespace

// ======================================================================
// Options
// ======================================================================

TEST(OfflineOptions, BlenderPresetSetsWhatBlenderWrites) {
    const char* argv[] = {"rrc-accumulate", "--preset", "blender", "--input", "f_%04d.exr", "--frames", "1-3", "--output", "o/%04d.exr"};
    const rrc_cli::ParseResult r = rrc_cli::parse_arguments(9, argv);
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.options.preset, "blender");
    EXPECT_EQ(r.options.depth_mode, RRC_DEPTH_MODE_LINEAR);
    EXPECT_EQ(r.options.reproject, rrc_cli::Reproject::Motion);
    EXPECT_EQ(r.options.motion_units, rrc_cli::MotionUnits::Pixels);
    EXPECT_TRUE(r.options.motion_y_up);
    EXPECT_EQ(r.options.tau, rrc_cli::blender_preset_tau());
    EXPECT_EQ(r.options.background_threshold, 0.0f);  // the library's 1e10: Blender's sky

    // Explicit options win over the preset.
    const char* argv2[] = {"rrc-accumulate", "--tau",          "0.05", "--preset", "blender",    "--input",
                           "f_%04d.exr",     "--frames",       "1-3",  "--output", "o/%04d.exr", "--motion-y",
                           "down",           "--motion-units", "uv"};
    const rrc_cli::ParseResult r2 = rrc_cli::parse_arguments(15, argv2);
    ASSERT_TRUE(r2.ok()) << r2.error;
    EXPECT_FLOAT_EQ(r2.options.tau, 0.05f);
    EXPECT_FALSE(r2.options.motion_y_up);
    EXPECT_EQ(r2.options.motion_units, rrc_cli::MotionUnits::Uv);
}

TEST(OfflineOptions, NewOptionsParseAndRefuseBadValues) {
    auto parse = [](std::vector<std::string> extra) {
        std::vector<std::string> args = {"rrc-accumulate", "--input", "in/f_%04d.exr", "--output", "out/o_%04d.exr", "--frames", "1-9"};
        args.insert(args.end(), extra.begin(), extra.end());
        std::vector<const char*> argv;
        for (const std::string& s : args) argv.push_back(s.c_str());
        return rrc_cli::parse_arguments(int(argv.size()), argv.data());
    };
    rrc_cli::ParseResult r = parse({"--depth-channel",
                                    "L.Depth.Z",
                                    "--motion-channels",
                                    "L.V.X,L.V.Y",
                                    "--prevclip-channels",
                                    "a,b,c,d",
                                    "--nocache-channel",
                                    "m.Y",
                                    "--cut",
                                    "3,5",
                                    "--cut",
                                    "7",
                                    "--coherence",
                                    "c/%d.png",
                                    "--reference",
                                    "ref/%04d.exr",
                                    "--metrics",
                                    "m.csv",
                                    "--psnr-peak",
                                    "2",
                                    "--progress",
                                    "bar"});
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.options.depth_channel, "L.Depth.Z");
    EXPECT_EQ(r.options.motion_channels, (std::vector<std::string>{"L.V.X", "L.V.Y"}));
    EXPECT_EQ(r.options.prevclip_channels, (std::vector<std::string>{"a", "b", "c", "d"}));
    EXPECT_EQ(r.options.nocache_channel, "m.Y");
    EXPECT_EQ(r.options.cuts, (std::vector<int64_t>{3, 5, 7}));
    EXPECT_EQ(r.options.coherence_pattern, "c/%d.png");
    EXPECT_EQ(r.options.reference_pattern, "ref/%04d.exr");
    EXPECT_EQ(rrc_cli::metrics_path(r.options), "m.csv");
    EXPECT_FLOAT_EQ(r.options.psnr_peak, 2.0f);
    EXPECT_EQ(r.options.progress, rrc_cli::Progress::Bar);
    rrc_cli::Options o;
    o.output_pattern = "out/dir/acc_%04d.exr";
    EXPECT_EQ(rrc_cli::metrics_path(o), "out/dir/metrics.csv");

    struct Bad {
        std::vector<std::string> args;
        const char* fragment;
    };
    for (const Bad& b : std::vector<Bad>{{{"--preset", "maya"}, "--preset"},
                                         {{"--view-layer", "X"}, "--preset blender"},
                                         {{"--motion-channels", "a"}, "--motion-channels"},
                                         {{"--motion-channels", "a,b,c,d"}, "--motion-channels"},
                                         {{"--motion-channels", "a,,b"}, "--motion-channels"},
                                         {{"--motion-channels", "a,a"}, "twice"},
                                         {{"--prevclip-channels", "a,b,c"}, "--prevclip-channels"},
                                         {{"--depth-channel", ""}, "--depth-channel"},
                                         {{"--motion-units", "mm"}, "--motion-units"},
                                         {{"--motion-y", "left"}, "--motion-y"},
                                         {{"--cut", "x"}, "--cut"},
                                         {{"--cut", "3,"}, "--cut"},
                                         {{"--coherence", "c.png"}, "--coherence"},
                                         {{"--coherence", "out/o_%04d.exr"}, "--coherence"},
                                         {{"--reference", "in/f_%04d.exr"}, "--reference"},
                                         {{"--metrics", "m.csv"}, "--reference"},
                                         {{"--psnr-peak", "0"}, "--psnr-peak"},
                                         {{"--progress", "fancy"}, "--progress"}}) {
        const rrc_cli::ParseResult bad = parse(b.args);
        EXPECT_FALSE(bad.ok()) << b.args[0];
        expect_contains(bad.error, b.fragment);
    }
    const std::string usage = rrc_cli::usage_text();
    for (const char* opt :
         {"--preset", "--view-layer", "--depth-channel", "--motion-channels", "--prevclip-channels", "--nocache-channel", "--motion-units",
          "--motion-y", "--cut", "--coherence", "--reference", "--metrics", "--psnr-peak", "--progress", "Vector.X", "Depth.Z", "1e10"})
        expect_contains(usage, opt);
    EXPECT_EQ(usage.find("@TAU@"), std::string::npos);
}

// ======================================================================
// The Blender convention, end to end, against the reference
// ======================================================================

// The tool reads the Blender-convention files; the reference gets the
// analytic scene's SPEC-convention data (LINEAR depth, uv_prev - uv in uv
// units, y down) and the kernel's own previous output, one frame at a time.
TEST(BlenderConvention, PresetMatchesTheReference) {
    TempDir dir;
    const int W = 64, H = 40, first = 1, last = 6;
    const rrc_scene::Scene scene(blender_scene_config(W, H));
    write_blender_sequence(scene, dir / "in/frame_%04d.exr", first, last);
    ASSERT_EQ(rrc_exr::read_exr_info(dir / "in/frame_0002.exr").parts, 5);  // multi-part frames are read too
    EXPECT_EQ(rrc_exr::read_exr_info(dir / "in/frame_0001.exr").channels[0].type, rrc_exr::PixelType::Half);

    std::string out, err;
    // --no-object-id: the double-precision reference implements the paper's
    // test alone (the id rule is checked on the real render, BlenderRender.*).
    ASSERT_EQ(run_tool({"--preset", "blender", "--no-object-id", "--input", dir / "in/frame_%04d.exr", "--frames", "1-6", "--output",
                        dir / "out/acc_%04d.exr", "--signal", "ViewLayer.Combined:lambda=0.8,blend=age_aware,history=fp32", "--signal",
                        "ViewLayer.Shadow:lambda=0.6", "--quiet"},
                       &out, &err),
              rrc_cli::kExitOk)
        << err;

    std::vector<rrc_channel_desc> channels = {rrc_test::channel("ViewLayer.Combined", 4, 0.8f, RRC_HISTORY_FP32, RRC_BLEND_AGE_AWARE),
                                              rrc_test::channel("ViewLayer.Shadow", 1, 0.6f, RRC_HISTORY_FP16, RRC_BLEND_FIXED)};
    rrc_context_desc ctx = rrc_test::context_desc(W, H, channels);
    ctx.depth_mode = RRC_DEPTH_MODE_LINEAR;
    ctx.reprojection = RRC_REPROJECTION_MOTION;
    ctx.tau = rrc_cli::blender_preset_tau();

    rrc_ref::PreviousFrame prev;
    int64_t compared = 0, pixels = 0, near = 0, hits = 0, tested = 0;
    for (int t = first; t <= last; ++t) {
        const rrc_scene::Frame fr = scene.render(t);
        const rrc_exr::ExrImage in = rrc_exr::read_exr(frame_path(dir / "in/frame_%04d.exr", t));
        const rrc_exr::ExrImage res = rrc_exr::read_exr(frame_path(dir / "out/acc_%04d.exr", t));
        ASSERT_EQ(rrc_exr::channel_names(res),
                  (std::vector<std::string>{"ViewLayer.Combined.A", "ViewLayer.Combined.B", "ViewLayer.Combined.G", "ViewLayer.Combined.R",
                                            "ViewLayer.Combined.age", "ViewLayer.Shadow.X", "ViewLayer.Shadow.age", "rrc.mask"}));
        // SPEC-convention inputs: the scene's own depth and motion, the file's samples (half-rounded in odd frames).
        const std::size_t n = std::size_t(W) * H;
        std::vector<float> motion(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            motion[2 * i] = fr.motion[3 * i];
            motion[2 * i + 1] = fr.motion[3 * i + 1];
        }
        const std::vector<float> combined = interleave(in, kCombined);
        const std::vector<float>& shadow = in.channels.at(kLayer + "Shadow.X");
        std::vector<rrc_channel_input> inputs = {rrc_test::channel_input(combined.data()), rrc_test::channel_input(shadow.data())};
        rrc_frame_desc fd = rrc_test::frame_desc();
        fd.frame_index = uint64_t(t);
        fd.depth = fr.depth.data();
        fd.reprojection = motion.data();
        fd.channel_count = 2;
        fd.channels = inputs.data();
        const rrc_ref::FrameResult r = rrc_ref::run_frame(ctx, prev, fd);

        const std::vector<float> k_comb = interleave(res, kCombined);
        const std::vector<float>& k_shadow = res.channels.at(kLayer + "Shadow.X");
        const std::vector<float>& k_mask = res.channels.at("rrc.mask");
        const std::vector<float>* k_age[2] = {&res.channels.at(kLayer + "Combined.age"), &res.channels.at(kLayer + "Shadow.age")};
        const std::vector<float>* k_vals[2] = {&k_comb, &k_shadow};
        for (std::size_t i = 0; i < n; ++i) {
            ++pixels;
            const int km = int(k_mask[i]);
            if (r.near_threshold[i]) {
                ++near;
                if (km != r.mask[i]) continue;  // a legitimate flip at the tolerance
            }
            ASSERT_EQ(km, int(r.mask[i])) << "frame " << t << " pixel (" << i % W << "," << i / W << ") diff " << r.diff[i] << " eps "
                                          << r.eps[i];
            if (r.near_nearest_edge[i]) continue;
            ++compared;
            for (int c = 0; c < 2; ++c) {
                const unsigned m = channels[c].components;
                EXPECT_EQ((*k_age[c])[i], float(r.channels[c].age[i])) << "frame " << t << " pixel " << i;
                for (unsigned q = 0; q < m; ++q) {
                    const double kv = (*k_vals[c])[m * i + q], rv = r.channels[c].out[m * i + q];
                    const double spread = prev.valid ? rrc_test::history_spread(prev.channels[c].history, m, q, W, H, r.uv_prev_x[i],
                                                                                r.uv_prev_y[i], fd.prev_jitter)
                                                     : 0.0;
                    const double tol =
                        rrc_test::arithmetic_tolerance(rv, r.channels[c].exact[m * i + q], channels[c].precision == RRC_HISTORY_FP16) +
                        rrc_test::position_tolerance(spread, W, H);
                    ASSERT_LE(std::fabs(kv - rv), tol) << "frame " << t << " pixel " << i << " channel " << c;
                }
            }
        }
        if (t > first) {
            hits += int64_t(r.stats.hits);
            tested += int64_t(r.stats.hits + r.stats.misses);
        }
        // The next frame's reference starts from the tool's output.
        prev.valid = true;
        prev.depth = fr.depth;
        prev.channels.resize(2);
        prev.channels[0].history = k_comb;
        prev.channels[1].history = k_shadow;
        for (int c = 0; c < 2; ++c) prev.channels[c].age.assign(k_age[c]->begin(), k_age[c]->end());
    }
    std::printf("Blender convention: compared %lld of %lld pixel-frames, %lld near the tolerance, hit ratio %.1f%%\n", (long long)compared,
                (long long)pixels, (long long)near, 100.0 * double(hits) / double(tested));
    EXPECT_GT(compared, pixels * 9 / 10);
    EXPECT_GT(hits, tested * 7 / 10) << "the mapping should make most pixels hit";
}

// The same files read through the channel options alone give the same bits:
// any channel can be mapped by name (the object ids too: the preset reads
// the IndexOB pass the synthetic frames carry).
TEST(BlenderConvention, ChannelOptionsReproduceThePreset) {
    TempDir dir;
    rrc_scene::SceneConfig sc = blender_scene_config(48, 32);
    sc.camera_speed = 3.0;  // enough vertical motion for the y sign to matter
    const rrc_scene::Scene scene(sc);
    write_blender_sequence(scene, dir / "in/f_%d.exr", 1, 3);
    const std::string tau = std::to_string(rrc_cli::blender_preset_tau());
    std::string err;
    ASSERT_EQ(run_tool({"--preset", "blender", "--input", dir / "in/f_%d.exr", "--frames", "1-3", "--output", dir / "a/%d.exr", "--quiet"},
                       nullptr, &err),
              0)
        << err;
    ASSERT_EQ(run_tool({"--input",
                        dir / "in/f_%d.exr",
                        "--frames",
                        "1-3",
                        "--output",
                        dir / "b/%d.exr",
                        "--depth-mode",
                        "linear",
                        "--reproject",
                        "motion",
                        "--depth-channel",
                        "ViewLayer.Depth.Z",
                        "--motion-channels",
                        "ViewLayer.Vector.X,ViewLayer.Vector.Y",
                        "--motion-units",
                        "pixels",
                        "--motion-y",
                        "up",
                        "--tau",
                        tau,
                        "--object-id",
                        "ViewLayer.IndexOB.X",
                        "--signal",
                        preset_signal(),
                        "--quiet"},
                       nullptr, &err),
              0)
        << err;
    for (int f = 1; f <= 3; ++f) {
        const rrc_exr::ExrImage a = rrc_exr::read_exr(frame_path(dir / "a/%d.exr", f));
        const rrc_exr::ExrImage b = rrc_exr::read_exr(frame_path(dir / "b/%d.exr", f));
        EXPECT_EQ(a.channels, b.channels) << "frame " << f;
        EXPECT_EQ(rrc_exr::channel_names(a).size(), 6u);  // the preset accumulates Combined alone
    }
    // The vectors read the wrong way round (current minus previous) lose hits,
    // and the y sign reaches the result (PresetMatchesTheReference checks the
    // mapping pixel by pixel; at this size most wrong positions still pass
    // the relative depth test, so hit counts alone discriminate little).
    ASSERT_EQ(run_tool({"--preset", "blender", "--input", dir / "in/f_%d.exr", "--frames", "1-3", "--output", dir / "c/%d.exr",
                        "--motion-scale", "-1,-1", "--quiet"},
                       nullptr, &err),
              0);
    ASSERT_EQ(run_tool({"--preset", "blender", "--input", dir / "in/f_%d.exr", "--frames", "1-3", "--output", dir / "d/%d.exr",
                        "--motion-y", "down", "--quiet"},
                       nullptr, &err),
              0);
    auto hits = [&](const std::string& pattern) {
        const std::vector<float> m = rrc_exr::read_exr(frame_path(pattern, 3)).channels.at("rrc.mask");
        return std::count_if(m.begin(), m.end(), [](float v) { return int(v) & RRC_MASK_HIT; });
    };
    EXPECT_GT(hits(dir / "a/%d.exr"), hits(dir / "c/%d.exr"));
    EXPECT_NE(rrc_exr::read_exr(dir / "a/3.exr").channels, rrc_exr::read_exr(dir / "c/3.exr").channels);
    EXPECT_NE(rrc_exr::read_exr(dir / "a/3.exr").channels, rrc_exr::read_exr(dir / "d/3.exr").channels);
}

TEST(BlenderConvention, ViewLayerDiscovery) {
    TempDir dir;
    const rrc_scene::Scene scene(blender_scene_config(24, 16));
    const rrc_scene::Frame fr = scene.render(1);
    rrc_exr::ExrImage img = blender_frame(scene, fr, {});
    // A second view layer with its own passes.
    std::map<std::string, std::vector<float>> second;
    for (const auto& kv : img.channels) second["Background." + kv.first.substr(kLayer.size())] = kv.second;
    img.channels.insert(second.begin(), second.end());
    rrc_exr::write_exr(dir / "two_1.exr", img);
    std::string err;
    EXPECT_EQ(
        run_tool({"--preset", "blender", "--input", dir / "two_%d.exr", "--frames", "1", "--output", dir / "o/%d.exr"}, nullptr, &err),
        rrc_cli::kExitError);
    expect_contains(err, "several view layers");
    expect_contains(err, "'Background'");
    expect_contains(err, "--view-layer");
    EXPECT_EQ(run_tool({"--preset", "blender", "--view-layer", "Background", "--input", dir / "two_%d.exr", "--frames", "1", "--output",
                        dir / "o/%d.exr", "--quiet"},
                       nullptr, &err),
              rrc_cli::kExitOk)
        << err;
    EXPECT_TRUE(rrc_exr::read_exr(dir / "o/1.exr").has("Background.Combined.R"));
    EXPECT_EQ(run_tool({"--preset", "blender", "--view-layer", "Nope", "--input", dir / "two_%d.exr", "--frames", "1", "--output",
                        dir / "p/%d.exr"},
                       nullptr, &err),
              rrc_cli::kExitError);
    expect_contains(err, "'Nope.Depth.Z'");

    // No depth pass at all: say how to get one.
    rrc_exr::ExrImage nodepth = blender_frame(scene, fr, {});
    nodepth.channels.erase(kLayer + "Depth.Z");
    rrc_exr::write_exr(dir / "nz_1.exr", nodepth);
    EXPECT_EQ(run_tool({"--preset", "blender", "--input", dir / "nz_%d.exr", "--frames", "1", "--output", dir / "q/%d.exr"}, nullptr, &err),
              rrc_cli::kExitError);
    expect_contains(err, "Depth.Z");
    expect_contains(err, "the file has: ViewLayer.Combined.A");
    EXPECT_FALSE(fs::exists(dir / "q"));
}

// ======================================================================
// Bad input: a clear message, exit status 1, no partial output
// ======================================================================

class BadInput : public ::testing::Test {
protected:
    void SetUp() override {
        scene_ = std::make_unique<rrc_scene::Scene>(blender_scene_config(32, 20));
        in_ = dir_ / "in/frame_%04d.exr";
        out_ = dir_ / "out/acc_%04d.exr";
    }
    int run(std::vector<std::string> extra = {}, const std::string& frames = "1-5") {
        std::vector<std::string> args = {"--preset", "blender", "--input", in_, "--frames", frames, "--output", out_, "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_tool(args, &out_text_, &err_);
    }
    TempDir dir_;
    std::unique_ptr<rrc_scene::Scene> scene_;
    std::string in_, out_, out_text_, err_;
};

TEST_F(BadInput, MissingChannelListsTheChannelsTheFileHas) {
    BlenderWrite w;
    w.drop = kLayer + "Vector.Y";
    w.drop_frame = 3;
    write_blender_sequence(*scene_, in_, 1, 5, w);
    EXPECT_EQ(run(), rrc_cli::kExitError);
    expect_contains(err_, "frame_0003.exr: missing channel 'ViewLayer.Vector.Y'");
    expect_contains(err_, "the file has: ViewLayer.Combined.A, ViewLayer.Combined.B");
    expect_contains(err_, "ViewLayer.Vector.X, ViewLayer.Vector.Z");
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "an output was written before the check";

    // A missing signal layer names it too.
    EXPECT_EQ(run({"--signal", "ViewLayer.DiffCol"}, "1-2"), rrc_cli::kExitError);
    expect_contains(err_, "'ViewLayer.DiffCol'");
    expect_contains(err_, "the file has: ");
}

TEST_F(BadInput, FramesOfDifferentSizes) {
    write_blender_sequence(*scene_, in_, 1, 5);
    const rrc_scene::Scene small(blender_scene_config(32, 19));
    write_blender_sequence(small, in_, 4, 4);
    EXPECT_EQ(run(), rrc_cli::kExitError);
    expect_contains(err_, "frame_0004.exr: 32x19 differs from the first frame's 32x20");
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(BadInput, MissingFrameInTheRange) {
    write_blender_sequence(*scene_, in_, 1, 5);
    fs::remove(frame_path(in_, 3));
    EXPECT_EQ(run(), rrc_cli::kExitError);
    expect_contains(err_, "frame_0003.exr: cannot open: no such file");
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(BadInput, TruncatedFileIsFoundBeforeAnyOutput) {
    write_blender_sequence(*scene_, in_, 1, 5);
    for (double keep : {0.9, 0.5}) {
        write_blender_sequence(*scene_, in_, 4, 4);
        const std::vector<char> bytes = file_bytes(frame_path(in_, 4));
        write_bytes(frame_path(in_, 4), std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep * bytes.size())));
        EXPECT_EQ(run(), rrc_cli::kExitError) << keep;
        expect_contains(err_, "frame_0004.exr");
        expect_contains(err_, "truncated");
        EXPECT_FALSE(fs::exists(dir_ / "out")) << "frames were written before the truncated file was found";
    }
}

TEST_F(BadInput, CorruptHeader) {
    write_blender_sequence(*scene_, in_, 1, 5);
    std::vector<char> bytes = file_bytes(frame_path(in_, 2));
    for (std::size_t i = 8; i < 60; ++i)  // the channel list, just after the magic number and version
        bytes[i] = char(0xA5 ^ i);
    write_bytes(frame_path(in_, 2), bytes);
    EXPECT_EQ(run(), rrc_cli::kExitError);
    expect_contains(err_, "frame_0002.exr: not a readable OpenEXR file");
    EXPECT_FALSE(fs::exists(dir_ / "out"));
    // Not an EXR at all.
    std::ofstream(frame_path(in_, 2), std::ios::trunc) << "P6\n4 4\n255\n";
    EXPECT_EQ(run(), rrc_cli::kExitError);
    expect_contains(err_, "frame_0002.exr: not a readable OpenEXR file");
}

// Corrupt compressed pixels pass every structural check and are found only
// when the frame is decoded: the frames before it stay, complete, and no
// partial or temporary file is left.
TEST_F(BadInput, CorruptPixelDataStopsCleanly) {
    BlenderWrite w;
    w.multipart_even = false;
    write_blender_sequence(*scene_, in_, 1, 5, w);
    const std::string bad = frame_path(in_, 3);
    std::vector<char> bytes = file_bytes(bad);
    for (std::size_t i = bytes.size() * 6 / 10; i < bytes.size() * 6 / 10 + 48; ++i) bytes[i] = char(~bytes[i]);
    write_bytes(bad, bytes);
    ASSERT_NO_THROW(rrc_exr::verify_exr_chunks(bad)) << "the corruption should sit inside a block's data";
    ASSERT_THROW(rrc_exr::read_exr(bad), rrc_exr::ExrError);
    EXPECT_EQ(run({"--coherence", dir_ / "out/coh_%04d.png"}), rrc_cli::kExitError);
    expect_contains(err_, "frame_0003.exr");
    expect_contains(err_, "frames 1-2 were written completely before the error; no partial file was left");
    EXPECT_EQ(dir_entries(dir_.path() / "out"), (std::vector<std::string>{"acc_0001.exr", "acc_0002.exr", "coh_0001.png", "coh_0002.png"}));
}

// An object id is only known once its frame is decoded: a bad one stops
// the run there, naming the file, the channel and the pixel, and
// --no-object-id reads past it.
TEST_F(BadInput, BadObjectIdNamesThePixel) {
    write_blender_sequence(*scene_, in_, 1, 5);
    rrc_exr::ExrImage img = rrc_exr::read_exr(frame_path(in_, 3));
    img.channels.at(kLayer + "IndexOB.X")[std::size_t(7) * 32 + 5] = -2.0f;  // pixel (5, 7)
    rrc_exr::write_exr(frame_path(in_, 3), img);
    EXPECT_EQ(run(), rrc_cli::kExitError);
    expect_contains(err_, "frame_0003.exr: channel 'ViewLayer.IndexOB.X' (the object ids): pixel (5, 7) holds -2");
    expect_contains(err_, "frames 1-2 were written completely before the error; no partial file was left");
    EXPECT_EQ(dir_entries(dir_.path() / "out"), (std::vector<std::string>{"acc_0001.exr", "acc_0002.exr"}));
    EXPECT_EQ(run({"--no-object-id"}), rrc_cli::kExitOk) << err_;
}

TEST_F(BadInput, OutputsNeverOverwriteInputs) {
    write_blender_sequence(*scene_, in_, 1, 5);
    write_blender_sequence(*scene_, dir_ / "ref/r_%d.exr", 1, 5, BlenderWrite{false, false, "", -1, true});
    const std::vector<char> before = file_bytes(frame_path(in_, 2));
    struct Case {
        std::vector<std::string> args;
        const char* fragment;
    };
    const std::string same_input = (dir_.path() / "in" / "." / "frame_%04d.exr").string();
    for (const Case& c : std::vector<Case>{{{"--output", same_input}, "never overwritten"},
                                           {{"--coherence", dir_ / "in/frame_%04d.exr"}, "never overwritten"},
                                           {{"--reference", dir_ / "ref/r_%d.exr", "--output", dir_ / "ref/r_%d.exr"}, "never overwritten"},
                                           {{"--reference", dir_ / "ref/r_%d.exr", "--metrics", frame_path(in_, 5)}, "never overwritten"},
                                           {{"--coherence", dir_ / "out/./acc_%04d.exr"}, "choose distinct output names"}}) {
        std::vector<std::string> args = {"--preset", "blender", "--input", in_, "--frames", "1-5", "--quiet"};
        if (std::find(c.args.begin(), c.args.end(), "--output") == c.args.end()) {
            args.push_back("--output");
            args.push_back(out_);
        }
        args.insert(args.end(), c.args.begin(), c.args.end());
        EXPECT_EQ(run_tool(args, nullptr, &err_), rrc_cli::kExitError) << c.args[0] << " " << c.args[1];
        expect_contains(err_, c.fragment);
        EXPECT_FALSE(fs::exists(dir_ / "out"));
    }
    EXPECT_EQ(file_bytes(frame_path(in_, 2)), before);
}

TEST_F(BadInput, ReferenceFramesAreCheckedUpFront) {
    write_blender_sequence(*scene_, in_, 1, 5);
    write_blender_sequence(*scene_, dir_ / "ref/r_%d.exr", 1, 4, BlenderWrite{false, false, "", -1, true});
    EXPECT_EQ(run({"--reference", dir_ / "ref/r_%d.exr"}), rrc_cli::kExitError);
    expect_contains(err_, "r_5.exr: cannot open: no such file");
    write_blender_sequence(*scene_, dir_ / "ref/r_%d.exr", 5, 5, BlenderWrite{false, false, kLayer + "Combined.G", 5, true});
    EXPECT_EQ(run({"--reference", dir_ / "ref/r_%d.exr"}), rrc_cli::kExitError);
    expect_contains(err_, "r_5.exr: missing channel 'ViewLayer.Combined.G'");
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// ======================================================================
// Metrics, coherence maps, progress, cuts
// ======================================================================

TEST(OfflineOutputs, ReferenceMetricsAndCoherenceMaps) {
    TempDir dir;
    const int W = 48, H = 32;
    // A still camera and scene: the gain is the noise averaging alone (under
    // motion the bilinear history fetch also blurs, docs/measurements/OFFLINE.md).
    rrc_scene::SceneConfig sc = blender_scene_config(W, H);
    sc.camera_motion = false;
    sc.object_motion = false;
    const rrc_scene::Scene scene(sc);
    write_blender_sequence(scene, dir / "in/f_%d.exr", 1, 6);
    write_blender_sequence(scene, dir / "ref/r_%d.exr", 1, 6, BlenderWrite{false, false, "", -1, true});
    std::string out, err;
    ASSERT_EQ(run_tool({"--preset", "blender", "--input", dir / "in/f_%d.exr", "--frames", "1-6", "--output", dir / "out/acc_%d.exr",
                        "--signal", "ViewLayer.Combined:lambda=0.8,blend=age_aware,history=fp32", "--reference", dir / "ref/r_%d.exr",
                        "--coherence", dir / "png/coh_%d.png", "--quiet"},
                       &out, &err),
              0)
        << err;
    expect_contains(out, "rrc-accumulate: ViewLayer.Combined against the reference over 6 frames: input RMSE ");
    expect_contains(out, "accumulated RMSE ");
    expect_contains(out, "metrics.csv");
    EXPECT_EQ(out.find("frame 3:"), std::string::npos) << "--quiet prints no per-frame line";

    // The CSV: a header and one line per frame, recomputed here from the files.
    std::ifstream csv(dir / "out/metrics.csv");
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "frame,layer,hit_ratio,values,input_rmse,input_psnr_db,output_rmse,output_psnr_db");
    const std::size_t n = std::size_t(W) * H;
    for (int f = 1; f <= 6; ++f) {
        ASSERT_TRUE(std::getline(csv, line)) << "frame " << f;
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
        ASSERT_EQ(cells.size(), 8u) << line;
        EXPECT_EQ(cells[0], std::to_string(f));
        EXPECT_EQ(cells[1], "ViewLayer.Combined");
        const rrc_exr::ExrImage in = rrc_exr::read_exr(frame_path(dir / "in/f_%d.exr", f));
        const rrc_exr::ExrImage acc = rrc_exr::read_exr(frame_path(dir / "out/acc_%d.exr", f));
        const rrc_exr::ExrImage ref = rrc_exr::read_exr(frame_path(dir / "ref/r_%d.exr", f));
        double in_sse = 0, out_sse = 0;
        for (const char* c : {"Combined.R", "Combined.G", "Combined.B"})  // A is left out
            for (std::size_t i = 0; i < n; ++i) {
                const double r = ref.channels.at(kLayer + c)[i];
                in_sse += std::pow(in.channels.at(kLayer + c)[i] - r, 2);
                out_sse += std::pow(acc.channels.at(kLayer + c)[i] - r, 2);
            }
        EXPECT_EQ(std::stoul(cells[3]), 3 * n);
        const double in_rmse = std::sqrt(in_sse / double(3 * n)), out_rmse = std::sqrt(out_sse / double(3 * n));
        EXPECT_NEAR(std::stod(cells[4]), in_rmse, 1e-5 * in_rmse);
        EXPECT_NEAR(std::stod(cells[5]), 10 * std::log10(1.0 / (in_rmse * in_rmse)), 1e-4);
        EXPECT_NEAR(std::stod(cells[6]), out_rmse, 1e-5 * out_rmse);
        if (f == 1)
            EXPECT_EQ(cells[4], cells[6]) << "the first frame is the input";
        else  // the mean of f samples: the error falls as 1/sqrt(f)
            EXPECT_LT(out_rmse, 1.1 * in_rmse / std::sqrt(double(f))) << "frame " << f;

        // The coherence map shows the mask.
        const rrc_png::RgbImage png = rrc_png::read_png(frame_path(dir / "png/coh_%d.png", f));
        ASSERT_EQ(png.width, W);
        ASSERT_EQ(png.height, H);
        const std::vector<float>& mask = acc.channels.at("rrc.mask");
        int greens = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const int m = int(mask[i]);
            const uint8_t* p = &png.rgb[3 * i];
            if (m & RRC_MASK_BACKGROUND)
                EXPECT_TRUE(p[0] == 64 && p[1] == 64 && p[2] == 64) << i;
            else if (m & RRC_MASK_HIT)
                EXPECT_TRUE(p[0] == 0 && p[1] == 255 && p[2] == 0) << i;
            else
                EXPECT_TRUE(p[0] == 255 && p[1] == 0 && p[2] == 0) << i;
            greens += p[1] == 255;
        }
        if (f > 1) EXPECT_GT(greens, int(n / 2));
    }
    EXPECT_FALSE(std::getline(csv, line));
    EXPECT_EQ(dir_entries(dir.path() / "out").size(), 7u);  // 6 frames + the CSV, no temporary file
}

TEST(OfflineOutputs, ProgressBarLinesAndQuiet) {
    TempDir dir;
    const rrc_scene::Scene scene(blender_scene_config(24, 16));
    write_blender_sequence(scene, dir / "in/f_%d.exr", 1, 3);
    auto run_with = [&](std::vector<std::string> extra, std::string& out) {
        std::vector<std::string> args = {"--preset", "blender", "--input",  dir / "in/f_%d.exr",
                                         "--frames", "1-3",     "--output", dir / "out/%d.exr"};
        args.insert(args.end(), extra.begin(), extra.end());
        std::string err;
        EXPECT_EQ(run_tool(args, &out, &err), 0) << err;
    };
    std::string bar, lines, quiet, automatic;
    run_with({"--progress", "bar"}, bar);
    expect_contains(bar, "\r[");
    expect_contains(bar, "] 3/3 frames, frame 3: hit ");
    expect_contains(bar, "ETA 0:00");
    expect_contains(bar, "\nrrc-accumulate: 3 frames");
    run_with({"--progress", "lines"}, lines);
    EXPECT_EQ(lines.find('\r'), std::string::npos);
    expect_contains(lines, "frame 2: hit ");
    expect_contains(lines, "[2/3, ETA ");
    run_with({}, automatic);  // not a terminal: lines
    EXPECT_EQ(automatic.find('\r'), std::string::npos);
    expect_contains(automatic, "[3/3, ETA 0:00]");
    run_with({"--progress", "bar", "--quiet"}, quiet);
    EXPECT_EQ(quiet.find("frame 2"), std::string::npos);
    EXPECT_EQ(quiet.find('\r'), std::string::npos);
    expect_contains(quiet, "rrc-accumulate: 3 frames");
}

TEST(OfflineOutputs, CutsResetTheHistory) {
    TempDir dir;
    const rrc_scene::Scene scene(blender_scene_config(32, 20));
    write_blender_sequence(scene, dir / "in/f_%d.exr", 1, 5);
    std::string out, err;
    ASSERT_EQ(
        run_tool({"--preset", "blender", "--input", dir / "in/f_%d.exr", "--frames", "1-5", "--output", dir / "out/%d.exr", "--cut", "4"},
                 &out, &err),
        0)
        << err;
    expect_contains(out, "frame 4: hit 0.0% (cut)");
    auto hits = [&](int f) {
        const rrc_exr::ExrImage img = rrc_exr::read_exr(frame_path(dir / "out/%d.exr", f));
        const std::vector<float>& m = img.channels.at("rrc.mask");
        const std::vector<float>& age = img.channels.at("ViewLayer.Combined.age");
        EXPECT_LE(*std::max_element(age.begin(), age.end()), float(f >= 4 ? f - 3 : f));
        return std::count_if(m.begin(), m.end(), [](float v) { return int(v) & RRC_MASK_HIT; });
    };
    EXPECT_GT(hits(3), 0);
    EXPECT_EQ(hits(4), 0);
    EXPECT_GT(hits(5), 0);
}

// ======================================================================
// The preset's depth tolerance: hit and false-hit rates (docs/measurements/OFFLINE.md)
// ======================================================================

// Blender's Depth is the pixel-centre sample and its Vector carries no depth
// change, so the test is rrc's relative one on linear depth: a surface
// whose depth changes by more than tau between frames misses, and a
// different surface within tau of the expected depth hits falsely.  This
// sweeps tau over the analytic scene (camera orbit, moving sphere) at two
// camera speeds and checks the preset's value keeps nearly every hit while
// the false-hit rate stays at the level of the smallest tolerances.
TEST(BlenderPresetTau, HitAndFalseHitRates) {
    struct Rates {
        double tau, speed;
        int64_t tested = 0, hits = 0, checked = 0, false_hits = 0, strict = 0;
        double hit_ratio() const { return tested ? double(hits) / double(tested) : 0.0; }
        double false_ratio() const { return checked ? double(false_hits) / double(checked) : 0.0; }
        double strict_ratio() const { return checked ? double(strict) / double(checked) : 0.0; }
    };
    const int W = 96, H = 64, frames = 8;
    const std::vector<double> taus = {0.0025, 0.005, 0.01, 0.02, 0.03, double(rrc_cli::blender_preset_tau()), 0.05, 0.08};
    std::vector<Rates> table;
    for (double speed : {1.0, 3.0}) {
        rrc_scene::SceneConfig sc = blender_scene_config(W, H);
        sc.camera_speed = speed;
        sc.object_speed = speed;
        const rrc_scene::Scene scene(sc);
        std::vector<rrc_scene::Frame> rendered;
        for (int t = 0; t < frames; ++t) rendered.push_back(scene.render(t));
        for (double tau : taus) {
            if (std::any_of(table.begin(), table.end(), [&](const Rates& r) { return r.tau == tau && r.speed == speed; })) continue;
            std::vector<rrc_channel_desc> ch = {rrc_test::channel("c", 1, 0.6f, RRC_HISTORY_FP16)};
            rrc_context_desc d = rrc_test::context_desc(W, H, ch);
            d.depth_mode = RRC_DEPTH_MODE_LINEAR;
            d.reprojection = RRC_REPROJECTION_MOTION;
            d.tau = float(tau);
            rrc_test::Context ctx(d);
            ASSERT_TRUE(ctx);
            Rates r{tau, speed};
            for (int t = 0; t < frames; ++t) {
                const rrc_scene::Frame& fr = rendered[std::size_t(t)];
                const std::size_t n = std::size_t(W) * H;
                std::vector<float> motion(2 * n);
                for (std::size_t i = 0; i < n; ++i) {
                    motion[2 * i] = fr.motion[3 * i];
                    motion[2 * i + 1] = fr.motion[3 * i + 1];
                }
                rrc_channel_input in = rrc_test::channel_input(fr.signal1.data());
                rrc_frame_desc fd = rrc_test::frame_desc();
                fd.frame_index = uint64_t(t);
                fd.depth = fr.depth.data();
                fd.reprojection = motion.data();
                fd.channel_count = 1;
                fd.channels = &in;
                const rrc_test::FrameResult k = ctx.run(fd);
                if (t == 0) continue;
                r.tested += int64_t(k.stats.hits + k.stats.misses);
                r.hits += int64_t(k.stats.hits);
                const rrc_scene::FalseHitReport fh = rrc_scene::count_false_hits(scene, t, k.mask.data());
                r.checked += fh.hits_checked;
                r.false_hits += fh.false_hits;
                r.strict += fh.strict_false_hits;
            }
            table.push_back(r);
        }
    }
    std::printf("| camera speed | tau | hit ratio | false hits | strict false hits |\n|---|---|---|---|---|\n");
    for (const Rates& r : table)
        std::printf("| %.0fx | %g%s | %.2f%% | %.3f%% | %.3f%% |\n", r.speed, r.tau,
                    r.tau == double(rrc_cli::blender_preset_tau()) ? " (preset)" : "", 100.0 * r.hit_ratio(), 100.0 * r.false_ratio(),
                    100.0 * r.strict_ratio());
    for (double speed : {1.0, 3.0}) {
        auto at = [&](double tau) {
            return *std::find_if(table.begin(), table.end(), [&](const Rates& r) { return r.tau == tau && r.speed == speed; });
        };
        const Rates preset = at(rrc_cli::blender_preset_tau()), loosest = at(0.08), tightest = at(0.0025);
        // Nearly every hit the loosest tolerance finds...
        EXPECT_GT(preset.hits, loosest.hits * 97 / 100) << "speed " << speed;
        // ...with few false hits (the loosest admits several times more).
        EXPECT_LT(preset.false_ratio(), 0.01) << "speed " << speed;
        EXPECT_LT(preset.false_ratio(), loosest.false_ratio()) << "speed " << speed;
        // The tightest tolerance loses hits to the depth change between frames.
        EXPECT_LT(tightest.hits, preset.hits) << "speed " << speed;
    }
}

// ======================================================================
// A real Blender 3.4 render (tests/data/offline, made by
// blender/render_check_scene.py; Blender itself is not needed here)
// ======================================================================

TEST(BlenderRender, RealFramesFollowTheDocumentedConvention) {
    const char* data = std::getenv("RRC_TEST_DATA");
    ASSERT_NE(data, nullptr) << "RRC_TEST_DATA is set by tests/CMakeLists.txt";
    const std::string in = std::string(data) + "/offline/blender_cycles_%04d.exr";

    // What the files hold: Combined in half, the data passes in float, the
    // sky (object index 0) at exactly 1e10 and nowhere else.
    const rrc_exr::ExrInfo info = rrc_exr::read_exr_info(frame_path(in, 1));
    ASSERT_EQ(info.width, 64);
    ASSERT_EQ(info.height, 48);
    for (const rrc_exr::ExrChannelInfo& c : info.channels)
        EXPECT_EQ(c.type, c.name.find(".Combined.") != std::string::npos ? rrc_exr::PixelType::Half : rrc_exr::PixelType::Float) << c.name;
    for (int f = 1; f <= 3; ++f) {
        const rrc_exr::ExrImage img = rrc_exr::read_exr(frame_path(in, f));
        const std::vector<float>& z = img.channels.at(kLayer + "Depth.Z");
        const std::vector<float>& id = img.channels.at(kLayer + "IndexOB.X");
        int sky = 0;
        for (std::size_t i = 0; i < z.size(); ++i) {
            EXPECT_EQ(id[i] == 0.0f, z[i] == 1e10f) << "frame " << f << " pixel " << i;
            sky += id[i] == 0.0f;
        }
        EXPECT_GT(sky, 100);
    }

    // The preset's mapping makes most pixels hit; the vectors read with y
    // down, or as current minus previous, lose nearly half of them.
    TempDir dir;
    auto hit_ratio = [&](std::vector<std::string> extra, const std::string& out) {
        std::vector<std::string> args = {"--preset", "blender", "--input", in, "--frames", "1-3", "--output", out, "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        std::string err;
        EXPECT_EQ(run_tool(args, nullptr, &err), 0) << err;
        int64_t hits = 0, tested = 0;
        for (int f = 2; f <= 3; ++f) {
            const std::vector<float> mask = rrc_exr::read_exr(frame_path(out, f)).channels.at("rrc.mask");
            for (float m : mask) {
                tested += !(int(m) & RRC_MASK_BACKGROUND);
                hits += int(m) & RRC_MASK_HIT;
            }
        }
        return double(hits) / double(tested);
    };
    const double preset = hit_ratio({}, dir / "a/%d.exr");
    const double y_down = hit_ratio({"--motion-y", "down"}, dir / "b/%d.exr");
    const double reversed = hit_ratio({"--motion-scale", "-1,-1"}, dir / "c/%d.exr");
    std::printf("real Blender frames 2-3: hit ratio %.1f%% (preset), %.1f%% (y down), %.1f%% (reversed)\n", 100 * preset, 100 * y_down,
                100 * reversed);
    EXPECT_GT(preset, 0.9);
    EXPECT_LT(y_down, 0.7);
    EXPECT_LT(reversed, 0.7);

    // Hits take their history from the same object (Blender's object index
    // at the nearest previous texel), but for a few edge pixels.
    const rrc_cli::ObjectIndexHits counted = count_real_render_hits(in, dir / "a/%d.exr");
    EXPECT_GT(counted.hits, 4000);
    EXPECT_LT(counted.nearest_foreign, counted.hits / 200)
        << counted.nearest_foreign << " of " << counted.hits << " hits from another object";
}

// Object ids (docs/measurements/OFFLINE.md): the preset reads ViewLayer.IndexOB.X when the file
// has it.  A hit then needs every previous depth tap of non-zero bilinear
// weight on the pixel's object (rrc.h, use_object_id), so no hit is an
// object-index false hit; the id rule only removes hits, and only those
// with a tap on another object.  Without ids (--no-object-id, or a file
// without the pass) the tool gives what the plain channel mapping gave
// before object ids existed.  Prints the table of docs/measurements/OFFLINE.md.
TEST(BlenderRender, ObjectIdsRuleOutTapsOnOtherObjects) {
    const char* data = std::getenv("RRC_TEST_DATA");
    ASSERT_NE(data, nullptr) << "RRC_TEST_DATA is set by tests/CMakeLists.txt";
    const std::string in = std::string(data) + "/offline/blender_cycles_%04d.exr";
    TempDir dir;
    auto run = [&](const std::string& input, std::vector<std::string> extra, const std::string& out_pattern, std::string* out_text) {
        std::vector<std::string> args = {"--input", input, "--frames", "1-3", "--output", out_pattern};
        args.insert(args.end(), extra.begin(), extra.end());
        std::string err;
        EXPECT_EQ(run_tool(args, out_text, &err), rrc_cli::kExitOk) << err;
    };
    std::string ids_text, none_text, stripped_text;
    run(in, {"--preset", "blender"}, dir / "ids/%d.exr", &ids_text);
    run(in, {"--preset", "blender", "--no-object-id"}, dir / "none/%d.exr", &none_text);
    expect_contains(ids_text, "rrc-accumulate: object ids from 'ViewLayer.IndexOB.X'");
    expect_contains(none_text, "rrc-accumulate: no object ids (--no-object-id)");

    // The same frames without the IndexOB pass: the preset goes without ids and says so.
    fs::create_directories(dir.path() / "noindex");
    for (int f = 1; f <= 3; ++f) {
        rrc_exr::ExrImage img = rrc_exr::read_exr(frame_path(in, f));
        ASSERT_EQ(img.channels.erase(kLayer + "IndexOB.X"), 1u);
        rrc_exr::WriteOptions wo;
        for (const std::string& c : kCombined) wo.half_channels.push_back(c);  // as Blender wrote them
        rrc_exr::write_exr(frame_path(dir / "noindex/f_%d.exr", f), img, wo);
    }
    run(dir / "noindex/f_%d.exr", {"--preset", "blender"}, dir / "stripped/%d.exr", &stripped_text);
    expect_contains(stripped_text, "no object ids: ");
    expect_contains(stripped_text, "has no 'ViewLayer.IndexOB.X'");
    // The mapping the preset stands for, spelt out without ids: the old behaviour.
    run(in,
        {"--depth-mode", "linear", "--reproject", "motion", "--depth-channel", "ViewLayer.Depth.Z", "--motion-channels",
         "ViewLayer.Vector.X,ViewLayer.Vector.Y", "--motion-units", "pixels", "--motion-y", "up", "--tau",
         std::to_string(rrc_cli::blender_preset_tau()), "--signal", preset_signal(), "--quiet"},
        dir / "plain/%d.exr", nullptr);
    for (int f = 1; f <= 3; ++f) {
        const auto none = rrc_exr::read_exr(frame_path(dir / "none/%d.exr", f)).channels;
        EXPECT_EQ(none, rrc_exr::read_exr(frame_path(dir / "stripped/%d.exr", f)).channels) << "frame " << f;
        EXPECT_EQ(none, rrc_exr::read_exr(frame_path(dir / "plain/%d.exr", f)).channels) << "frame " << f;
    }

    std::vector<rrc_cli::TapObjects> ids_taps, none_taps;
    const rrc_cli::ObjectIndexHits with_ids = count_real_render_hits(in, dir / "ids/%d.exr", &ids_taps);
    const rrc_cli::ObjectIndexHits without = count_real_render_hits(in, dir / "none/%d.exr", &none_taps);
    auto pct = [](int64_t a, int64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; };
    std::printf(
        "| object ids | hit ratio | hits | object-index false hits | of them at taps of weight <= %g | nearest-texel false hits |\n"
        "|---|---|---|---|---|---|\n",
        double(rrc_cli::kBorderlineTapWeight));
    for (const auto& row : {std::make_pair("IndexOB (preset)", with_ids), std::make_pair("none (--no-object-id)", without)})
        std::printf("| %s | %.2f%% | %lld of %lld | %.3f%% (%lld) | %lld | %.3f%% (%lld) |\n", row.first,
                    pct(row.second.hits, row.second.tested), (long long)row.second.hits, (long long)row.second.tested,
                    pct(row.second.foreign + row.second.borderline, row.second.hits),
                    (long long)(row.second.foreign + row.second.borderline), (long long)row.second.borderline,
                    pct(row.second.nearest_foreign, row.second.hits), (long long)row.second.nearest_foreign);

    // Without ids the fixture has such hits (edges of the moving sphere and
    // the cube), so the rule has something to remove...
    EXPECT_GT(without.foreign, 0);
    EXPECT_GT(without.hits, without.tested * 9 / 10);
    // ...and with them none is left (a foreign tap whose weight is within
    // fp32 rounding of zero is the kernel's call either way).
    EXPECT_EQ(with_ids.foreign, 0) << "hits with a tap of non-zero weight on another object";
    // The rule only removes hits, and only hits with a tap on another object:
    // the hit ratio drops by no more than the pixels it legitimately rejects.
    EXPECT_EQ(with_ids.tested, without.tested);
    EXPECT_GE(with_ids.hits, without.hits - without.foreign - without.borderline);
    ASSERT_EQ(ids_taps.size(), none_taps.size());
    int64_t lost_legitimately = 0;
    for (int f = 2; f <= 3; ++f) {
        const std::vector<float> a = rrc_exr::read_exr(frame_path(dir / "ids/%d.exr", f)).channels.at("rrc.mask");
        const std::vector<float> b = rrc_exr::read_exr(frame_path(dir / "none/%d.exr", f)).channels.at("rrc.mask");
        for (std::size_t k = 0; k < a.size(); ++k) {
            const bool hit_ids = int(a[k]) & RRC_MASK_HIT, hit_none = int(b[k]) & RRC_MASK_HIT;
            const rrc_cli::TapObjects& t = none_taps[(std::size_t(f) - 2) * a.size() + k];
            EXPECT_TRUE(hit_none || !hit_ids) << "frame " << f << " pixel " << k << ": a hit only with ids";
            if (hit_none && !hit_ids) {
                EXPECT_TRUE(t.foreign || t.borderline)
                    << "frame " << f << " pixel " << k << ": lost a hit whose taps are all on its object";
                ++lost_legitimately;
            }
        }
    }
    EXPECT_EQ(without.hits - with_ids.hits, lost_legitimately);
}
