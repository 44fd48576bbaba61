// rrc-cache: the shading cache (docs/guide/integration.md, "The shading cache") on
// rrc-sample's temple scene with an 8-octave Perlin shader: frame time and
// error against shading every pixel every frame, for each refresh policy and
// period, with and without a maximum lifetime, and a stereo pair whose second
// eye reuses the first eye's shading; with --octaves, the speed-up of TILED
// n = 4 against the shader's cost.  host_sample/studies/cache/README.md.
#include "cache_report.h"
#include "cache_run.h"
#include "cache_targets.h"
#include "output.h"  // rrc_sample::coherence_map
#include "options_parser.h"
#include "png_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rrc_cache;

namespace {

const char* kUsage =
    "usage: rrc-cache [--size WxH] [--frames N] [--periods N,N,...] [--policies tiled,random] [--no-stereo]\n"
    "                 [--octaves N,N,...] [--validation] [--out DIR] [--no-plot] [--check-options]\n"
    "Runs the temple scene with an 8-octave Perlin shader: every pixel shaded each frame (the baseline), rrc's\n"
    "shading cache without refresh, with each policy at each period n, with and without a maximum lifetime of\n"
    "2n frames, a stereo pair (second eye reusing the first's shading) against shading both eyes, and motion blur\n"
    "(4 sub-frames a frame, each reusing the one before) against shading every sub-frame.\n"
    "--octaves: the shader's octave counts (its cost); all of the above at the first, and at each further one\n"
    "full and TILED n = 4 (runs named _oN), for the speed-up against shader cost and the break-even shader.\n"
    "Defaults: --size 320x180 --frames 24 --periods 1,2,4,8 --policies tiled,random --octaves 8 --out out/cache.\n"
    "Writes DIR/report.md, runs.csv, speedup_vs_cost.csv, speedup.png and speedup_vs_cost.png (matplotlib), and\n"
    "cached/full/coherence/anaglyph PNGs.\n"
    "--check-options: check the options as a run would, print \"rrc-cache: options ok\" and exit.\n";

struct Options {
    Settings settings;
    std::vector<uint32_t> periods{1, 2, 4, 8};
    std::vector<rrc_refresh_policy> policies{RRC_REFRESH_TILED, RRC_REFRESH_RANDOM};
    std::vector<uint32_t> octaves{kDefaultOctaves};  // the first: every run; the others: full and TILED n = 4
    bool stereo = true, plot = true;
    std::string out = "out/cache";
    bool help = false, check_options = false;
};

constexpr rrc_host::EnumName<rrc_refresh_policy> kPolicyNames[] = {{"tiled", RRC_REFRESH_TILED}, {"random", RRC_REFRESH_RANDOM}};

Options parse(int argc, char** argv) {
    Options o;
    rrc_host::ArgCursor c(argc, argv);
    while (c.next()) {
        if (c.option("--size")) {
            c.size(o.settings.width, o.settings.height, 1, 16384);
        } else if (c.option("--frames")) {
            // Two warm-up frames are not counted.
            o.settings.frames = (int)c.integer(4, 16384);
        } else if (c.option("--periods")) {
            o.periods.clear();
            for (long n : c.integers(1, 16384)) o.periods.push_back((uint32_t)n);
        } else if (c.option("--policies")) {
            o.policies = c.choices(kPolicyNames);
        } else if (c.option("--octaves")) {
            o.octaves.clear();
            for (long n : c.integers(1, kMaxOctaves))
                if (std::find(o.octaves.begin(), o.octaves.end(), (uint32_t)n) == o.octaves.end()) o.octaves.push_back((uint32_t)n);
        } else if (c.flag("--no-stereo")) {
            o.stereo = false;
        } else if (c.flag("--no-plot")) {
            o.plot = false;
        } else if (c.flag("--validation")) {
            o.settings.validation = true;
        } else if (c.option("--out")) {
            o.out = c.value();
        } else {
            c.unknown();
        }
    }
    o.check_options = c.check_only();
    o.help = c.help();
    return o;
}

// TILED n = 4 without a lifetime: the paper's setting, the speed-up against shader cost is measured with it.
CacheConfig tiled_4(uint32_t octaves, const std::string& suffix) {
    CacheConfig k;
    k.name = "tiled_" + std::to_string(kCostPeriod) + suffix;
    k.policy = RRC_REFRESH_TILED;
    k.period = kCostPeriod;
    k.octaves = octaves;
    return k;
}

std::vector<CacheConfig> configs(const Options& o) {
    std::vector<CacheConfig> c;
    c.push_back({"full", false});
    c.push_back({"cache_no_refresh", true});
    for (rrc_refresh_policy p : o.policies)
        for (uint32_t n : o.periods)
            for (bool lifetime : {false, true}) {
                CacheConfig k;
                k.name = std::string(p == RRC_REFRESH_TILED ? "tiled" : "random") + "_" + std::to_string(n) +
                         (lifetime ? "_L" + std::to_string(2 * n) : "");
                k.policy = p;
                k.period = n;
                k.lifetime = lifetime ? 2 * n : 0;
                c.push_back(k);
            }
    for (bool cache : {false, true}) {  // motion blur: 4 sub-frames a frame, each reusing the one before
        CacheConfig b{cache ? "blur4_cache" : "blur4_full", cache};
        b.subframes = 4;
        c.push_back(b);
    }
    if (o.stereo) {
        CacheConfig full{"stereo_full", false};
        full.stereo = true;
        CacheConfig cache{"stereo_cache", true};
        cache.stereo = true;
        c.push_back(full);
        c.push_back(cache);
    }
    const uint32_t first = o.octaves.front();
    for (CacheConfig& k : c) k.octaves = first;
    const bool has_tiled_4 = std::any_of(c.begin(), c.end(), [](const CacheConfig& k) {
        return k.cache && k.policy == RRC_REFRESH_TILED && k.period == kCostPeriod && !k.lifetime && !k.stereo && k.subframes == 1;
    });
    if (!has_tiled_4) c.push_back(tiled_4(first, ""));  // the cost curve's first point
    // Each further octave count: the shader's cost moves, the cache's does not.
    for (size_t i = 1; i < o.octaves.size(); ++i) {
        const std::string suffix = "_o" + std::to_string(o.octaves[i]);
        CacheConfig full{"full" + suffix, false};
        full.octaves = o.octaves[i];
        c.push_back(full);
        c.push_back(tiled_4(o.octaves[i], suffix));
    }
    return c;
}

uint8_t to8(float v) { return (uint8_t)std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f); }

rrc_png::RgbImage picture(const std::vector<float>& rgba, const Settings& s) {
    rrc_png::RgbImage img{(int)s.width, (int)s.height, std::vector<uint8_t>(3 * (size_t)s.width * s.height)};
    for (size_t i = 0; i < img.rgb.size() / 3; ++i)
        for (int k = 0; k < 3; ++k) img.rgb[3 * i + k] = to8(rgba[4 * i + k]);
    return img;
}

// rrc-sample's coherence colours: green reused (HIT), blue refreshed, red shaded (miss), black background.
rrc_png::RgbImage coherence(const std::vector<uint8_t>& mask, const Settings& s) {
    return rrc_png::RgbImage{(int)s.width, (int)s.height, rrc_sample::coherence_map(mask)};
}

// Red from the second (left) eye, green and blue from the first (right) eye.
rrc_png::RgbImage anaglyph(const std::vector<float>& left, const std::vector<float>& right, const Settings& s) {
    rrc_png::RgbImage img{(int)s.width, (int)s.height, std::vector<uint8_t>(3 * (size_t)s.width * s.height)};
    for (size_t i = 0; i < img.rgb.size() / 3; ++i) {
        const float l = 0.3f * left[4 * i] + 0.59f * left[4 * i + 1] + 0.11f * left[4 * i + 2];
        img.rgb[3 * i] = to8(l);
        img.rgb[3 * i + 1] = to8(right[4 * i + 1]);
        img.rgb[3 * i + 2] = to8(right[4 * i + 2]);
    }
    return img;
}

void progress(int frame, int frames) {
    if (frame == frames || frame % 8 == 0) std::fprintf(stderr, "  frame %d/%d\n", frame, frames);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    const int code = rrc_host::parse_command_line("rrc-cache", [&] { return parse(argc, argv); }, kUsage, o);
    if (code >= 0) return code;
    try {
        fs::create_directories(o.out);
        std::string command = "rrc-cache";
        for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
        Bench bench(o.settings);
        const std::vector<CacheConfig> cs = configs(o);
        std::vector<RunResult> runs;
        uint64_t messages = 0;
        for (size_t i = 0; i < cs.size(); ++i) {
            std::fprintf(stderr, "rrc-cache: [%zu/%zu] %s\n", i + 1, cs.size(), cs[i].name.c_str());
            runs.push_back(bench.run(cs[i], progress));
            messages += runs.back().validation_messages;
            if (!runs.back().list_matched)
                std::fprintf(stderr, "rrc-cache: %s: the miss shader did not shade exactly the listed quads\n", cs[i].name.c_str());
        }
        const std::vector<Figures> f = figures(runs);
        write_csv((fs::path(o.out) / "runs.csv").string(), f);
        write_cost_csv((fs::path(o.out) / "speedup_vs_cost.csv").string(), f);
        write_report((fs::path(o.out) / "report.md").string(), f, command, bench.device_name(), o.settings);
        for (const RunResult& r : runs) {
            if (r.config.name == "full") rrc_png::write_png((fs::path(o.out) / "full.png").string(), picture(r.image, o.settings));
            if (r.config.name == "tiled_4" || (r.config.cache && r.config.policy == RRC_REFRESH_TILED && !r.config.lifetime &&
                                               r.config.octaves == o.octaves.front() && !fs::exists(fs::path(o.out) / "cached.png"))) {
                rrc_png::write_png((fs::path(o.out) / "cached.png").string(), picture(r.image, o.settings));
                rrc_png::write_png((fs::path(o.out) / "coherence.png").string(), coherence(r.mask, o.settings));
            }
            if (r.config.name == "stereo_cache") {
                rrc_png::write_png((fs::path(o.out) / "anaglyph.png").string(), anaglyph(r.image_left, r.image, o.settings));
                rrc_png::write_png((fs::path(o.out) / "coherence_second_eye.png").string(), coherence(r.mask_left, o.settings));
            }
        }
        if (o.plot) {
            const std::string py = std::string(RRC_CACHE_PYTHON) + " ";
            for (const std::string& cmd :
                 {py + RRC_CACHE_PLOT_PY + " " + (fs::path(o.out) / "runs.csv").string() + " " + (fs::path(o.out) / "speedup.png").string(),
                  py + RRC_CACHE_PLOT_COST_PY + " " + (fs::path(o.out) / "speedup_vs_cost.csv").string() + " " +
                      (fs::path(o.out) / "speedup_vs_cost.png").string()})
                if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "rrc-cache: the plot was not drawn (%s)\n", cmd.c_str());
        }
        std::FILE* rep = std::fopen((fs::path(o.out) / "report.md").string().c_str(), "r");
        if (rep) {
            char buf[4096];
            size_t k;
            while ((k = std::fread(buf, 1, sizeof buf, rep)) > 0) std::fwrite(buf, 1, k, stdout);
            std::fclose(rep);
        }
        bool matched = true;
        for (const RunResult& r : runs) matched = matched && r.list_matched;
        if (messages) {
            std::fprintf(stderr, "rrc-cache: %llu validation messages; the first:\n", (unsigned long long)messages);
            const std::vector<std::string> m = bench.validation_messages();
            for (size_t i = 0; i < m.size() && i < 3; ++i) std::fprintf(stderr, "  %s\n", m[i].c_str());
        }
        return matched && messages == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rrc-cache: %s\n", e.what());
        return 1;
    }
}
