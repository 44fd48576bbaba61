// rrc_peer_comparison: measures docs/measurements/COMPARISON.md (peer_comparison.h) and
// rewrites its tables between
//   <!-- peer-comparison:begin --> and <!-- peer-comparison:end -->
// and the pictures of where each test fails (docs/measurements/comparison/).
//   rrc_peer_comparison [--doc docs/measurements/COMPARISON.md] [--images docs/measurements/comparison] [--only SUBSTRING]
// Without --doc it prints the tables; --only keeps the cases whose name contains SUBSTRING.
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "peer_comparison.h"
#include "png_io.h"

using namespace rrc_peer;

namespace {

const char kBegin[] = "<!-- peer-comparison:begin -->";
const char kEnd[] = "<!-- peer-comparison:end -->";

// The cases pictured (docs/measurements/COMPARISON.md, "Where each test fails").
const char* const kPictured[] = {"objects_prev_clip_reversed_f32_inf_near_0_1", "grazing_prev_clip_standard_f32_1e4",
                                 "objects_prev_clip_standard_u24_1e4", "card_80deg_prev_clip_standard_f32"};
constexpr int kScale = 4;

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}
std::string percent(const rrc_scene::RecallScore& s) { return s.scored ? fmt("%.2f%%", 100.0 * s.recall()) : "-"; }

// Orange: a visible pixel missed; red: a false hit; light grey: a visible pixel hit; dark: not
// visible and missed; mid grey: excluded or straddling (scored neither way).
void picture(const std::string& path, const CaseResult& r, int test) {
    const rrc_scene::VisibilityMap& m = r.last_map;
    rrc_png::RgbImage img;
    img.width = m.width * kScale;
    img.height = m.height * kScale;
    img.rgb.assign(size_t(img.width) * img.height * 3, 0);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const size_t k = size_t(y / kScale) * m.width + x / kScale;
            const bool hit = r.last_hits[test][k] != 0;
            uint8_t c[3] = {110, 110, 110};
            auto set = [&](uint8_t a, uint8_t b, uint8_t d) { c[0] = a, c[1] = b, c[2] = d; };
            if (rrc_scene::VisibilityMap::scored(m.cls[k]))
                hit ? set(205, 205, 205) : set(255, 150, 0);
            else if (rrc_scene::VisibilityMap::not_visible(m.cls[k]))
                hit ? set(230, 0, 40) : set(35, 35, 55);
            std::memcpy(&img.rgb[(size_t(y) * img.width + x) * 3], c, 3);
        }
    rrc_png::write_png(path, img);
}

std::string tables(const std::vector<CaseResult>& results) {
    std::ostringstream t;
    t << "Recall (hits / VISIBLE pixels):\n\n| case | visible |";
    for (int k = 0; k < kTestCount; ++k) t << " " << test_label(k) << " |";
    t << "\n|---|---|";
    for (int k = 0; k < kTestCount; ++k) t << "---|";
    t << "\n";
    TestScore total[kTestCount];
    for (const CaseResult& r : results) {
        t << "| " << r.name << " | " << r.tests[0].score.scored << " |";
        for (int k = 0; k < kTestCount; ++k) {
            t << " " << percent(r.tests[k].score) << " |";
            total[k].score += r.tests[k].score;
            total[k].mixing += r.tests[k].mixing;
        }
        t << "\n";
    }
    t << "| **all cases** | " << total[0].score.scored << " |";
    for (int k = 0; k < kTestCount; ++k) t << " **" << percent(total[k].score) << "** |";
    t << "\n\nFalse hits (hits on pixels whose point was not visible), and in brackets those whose fetched history "
         "takes weight > "
      << kMixWeight << " from a texel that held another object or the sky:\n\n| case | not visible |";
    for (int k = 0; k < kTestCount; ++k) t << " " << test_label(k) << " |";
    t << "\n|---|---|";
    for (int k = 0; k < kTestCount; ++k) t << "---|";
    t << "\n";
    for (const CaseResult& r : results) {
        t << "| " << r.name << " | " << r.tests[0].score.not_visible << " |";
        for (int k = 0; k < kTestCount; ++k) t << " " << r.tests[k].score.false_hits << " (" << r.tests[k].mixing << ") |";
        t << "\n";
    }
    t << "| **all cases** | " << total[0].score.not_visible << " |";
    for (int k = 0; k < kTestCount; ++k) t << " **" << total[k].score.false_hits << " (" << total[k].mixing << ")** |";
    t << "\n\nWhere a peer's recall is higher than rrc ADAPTIVE's, and what it pays in false hits (mixing in brackets):\n\n"
         "| case | test | its recall | rrc ADAPTIVE recall | its false hits | rrc ADAPTIVE false hits |\n|---|---|---|---|---|---|\n";
    int rows = 0;
    for (const CaseResult& r : results)
        for (int k = 2; k < kTestCount; ++k)
            if (r.tests[k].score.recall() > r.tests[0].score.recall()) {
                ++rows;
                t << "| " << r.name << " | " << test_label(k) << " | " << percent(r.tests[k].score) << " | " << percent(r.tests[0].score)
                  << " | " << r.tests[k].score.false_hits << " (" << r.tests[k].mixing << ") | " << r.tests[0].score.false_hits << " ("
                  << r.tests[0].mixing << ") |\n";
            }
    if (rows == 0) t << "| (none) | | | | | |\n";
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    t << "\nMeasured " << date << ", " << results.size() << " cases.\n";
    return t.str();
}

std::string picture_table(const std::vector<CaseResult>& results, const std::string& images_rel) {
    std::ostringstream t;
    t << "\n### Where each test fails\n\n"
         "The last scored frame of four cases, one picture per test, " << kScale << "x magnified: **orange** = a visible pixel the test\n"
         "missed, **red** = a false hit, light grey = a visible pixel hit, dark = not visible and missed (sky included),\n"
         "mid grey = excluded or straddling (scored neither way).\n";
    t << "\n| case |";
    for (int k = 0; k < kTestCount; ++k) t << " " << test_label(k) << " |";
    t << "\n|---|";
    for (int k = 0; k < kTestCount; ++k) t << "---|";
    t << "\n";
    for (const CaseResult& r : results)
        for (const char* p : kPictured)
            if (r.name == p) {
                t << "| " << r.name << " (last frame) |";
                for (int k = 0; k < kTestCount; ++k) t << " ![](" << images_rel << "/" << r.name << "__" << test_slug(k) << ".png) |";
                t << "\n";
            }
    return t.str();
}

}  // namespace

int main(int argc, char** argv) {
    std::string doc, images, only;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--doc")) doc = argv[i + 1];
        else if (!std::strcmp(argv[i], "--images")) images = argv[i + 1];
        else if (!std::strcmp(argv[i], "--only")) only = argv[i + 1];
        else {
            std::fprintf(stderr, "usage: %s [--doc FILE] [--images DIR] [--only SUBSTRING]\n", argv[0]);
            return 2;
        }
    }
    if (argc % 2 == 0) {
        std::fprintf(stderr, "usage: %s [--doc FILE] [--images DIR] [--only SUBSTRING]\n", argv[0]);
        return 2;
    }
    std::vector<CaseResult> results;
    for (const CaseSpec& spec : comparison_cases()) {
        if (!only.empty() && spec.name.find(only) == std::string::npos) continue;
        results.push_back(evaluate(spec));
        const CaseResult& r = results.back();
        std::printf("%s:", r.name.c_str());
        for (int k = 0; k < kTestCount; ++k)
            std::printf(" %s %s/%lld(%lld)", test_slug(k), percent(r.tests[k].score).c_str(), (long long)r.tests[k].score.false_hits,
                        (long long)r.tests[k].mixing);
        std::printf("\n");
        std::fflush(stdout);
        if (!images.empty())
            for (const char* p : kPictured)
                if (r.name == p)
                    for (int k = 0; k < kTestCount; ++k) picture(images + "/" + r.name + "__" + test_slug(k) + ".png", r, k);
    }
    const std::string text = tables(results) + picture_table(results, "comparison");
    if (doc.empty()) {
        std::printf("%s", text.c_str());
        return 0;
    }
    std::stringstream in;
    in << std::ifstream(doc).rdbuf();
    std::string s = in.str();
    const size_t b = s.find(kBegin), e = s.find(kEnd);
    if (b == std::string::npos || e == std::string::npos || e < b) {
        std::fprintf(stderr, "%s: no %s ... %s markers\n", doc.c_str(), kBegin, kEnd);
        return 1;
    }
    s.replace(b, e - b, std::string(kBegin) + "\n" + text);
    std::ofstream(doc) << s;
    return 0;
}
