// Every place where the documentation, the header's comments or a tool's
// --help text repeats a constant of include/rrc/ is checked against the
// macro itself, so a changed value cannot leave a stale copy behind.  Each
// check finds a specific phrase (an anchor) and reads the value right after
// it; whitespace runs (line breaks included) count as one space.
#include "support/source_file.h"

#include <rrc/rrc.h>

#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

// The file with every whitespace run made one space.
std::string read_squashed(const std::string& relative) {
    return std::regex_replace(rrc_test::read_source(relative), std::regex("\\s+"), " ");
}

// The text right after `anchor` (which must occur exactly once), up to n characters.
std::string after(const std::string& text, const std::string& file, const std::string& anchor, size_t n = 160) {
    const size_t at = text.find(anchor);
    if (at == std::string::npos) {
        ADD_FAILURE() << file << ": phrase \"" << anchor << "\" not found (reworded? update this test with the document)";
        return "";
    }
    EXPECT_EQ(text.find(anchor, at + 1), std::string::npos) << file << ": phrase \"" << anchor << "\" occurs more than once";
    return text.substr(at + anchor.size(), n);
}

// The number at the start of s (after spaces), as written.
std::string leading_number(const std::string& s) {
    std::smatch m;
    if (!std::regex_search(s, m, std::regex("^ ?([0-9]+(\\.[0-9]+)?([eE][-+]?[0-9]+)?)"))) return "(no number)";
    return m[1];
}

struct Place {
    const char* file;
    const char* anchor;  // the value follows it directly
};

// Checks that each place states `value`: parsed as the macro's type.
template <typename T>
void expect_value(const char* macro, T value, const std::vector<Place>& places) {
    for (const Place& p : places) {
        const std::string text = read_squashed(p.file);
        const std::string written = leading_number(after(text, p.file, p.anchor));
        T parsed{};
        std::istringstream(written) >> parsed;
        EXPECT_EQ(parsed, value) << p.file << ": \"" << p.anchor << written << "\" repeats " << macro << " = " << value;
    }
}

// The mask bits, from the public list: {value, name without RRC_MASK_}.
std::vector<std::pair<unsigned, std::string>> mask_bits() {
    std::vector<std::pair<unsigned, std::string>> bits;
#define RRC_TEST_BIT(name, value) bits.emplace_back(static_cast<unsigned>(value), std::string(#name).substr(sizeof "RRC_MASK_" - 1));
    RRC_MASK_VALUES(RRC_TEST_BIT)
#undef RRC_TEST_BIT
    return bits;
}

// A list "1 HIT, 2 REFRESHED, ..." after the anchor names every bit with its value.
void expect_mask_list(const char* file, const char* anchor) {
    const std::string text = read_squashed(file);
    const std::string list = after(text, file, anchor, 200);
    for (const auto& [value, name] : mask_bits()) {
        std::smatch m;
        const bool found = std::regex_search(list, m, std::regex("([0-9]+) " + name + "\\b"));
        EXPECT_TRUE(found) << file << ": the mask list after \"" << anchor << "\" lacks " << name << ": " << list;
        if (found) EXPECT_EQ(std::stoul(m[1]), value) << file << ": bit " << name << " is RRC_MASK_" << name << " = " << value;
    }
}

const char* const kAccumulateHelp = "host_sample/tools/accumulate/options.cpp";  // usage_text()
const char* const kSampleHelp = "host_sample/testbed/options.cpp";          // usage()

}  // namespace

TEST(ConstantsInDocs, MaskBits) {
    expect_mask_list("docs/CONVENTIONS.md", "The mask bits:");
    expect_mask_list("docs/reference/api.md", "| mask | storage R8_UINT / `uint8_t[W*H]` | bits:");
    expect_mask_list("docs/measurements/OFFLINE.md", "`rrc.mask` (bits");
    expect_mask_list(kAccumulateHelp, "the integer value of the per-pixel bitfield");
}

TEST(ConstantsInDocs, Limits) {
    expect_value<unsigned>("RRC_MAX_CHANNELS", RRC_MAX_CHANNELS,
                           {{"README.md", "Limits: up to "},
                            {"docs/measurements/OFFLINE.md", "can be accumulated alongside, up to "},
                            {kAccumulateHelp, "accumulate EXR layer NAME (repeatable, at most "}});
    expect_value<unsigned>("RRC_MAX_AGE_CAP", RRC_MAX_AGE_CAP,
                           {{"README.md", "ages up to "},
                            {"docs/CONVENTIONS.md", "Age cap: default 255, at most "},
                            {kAccumulateHelp, "max_age=1.."}});
    expect_value<unsigned>("RRC_MAX_EXTENT", RRC_MAX_EXTENT, {{"README.md", "history), "}});
    const std::string readme = read_squashed("README.md");
    const std::string extent = std::to_string(RRC_MAX_EXTENT);
    EXPECT_NE(readme.find(extent + "×" + extent + " pixels"), std::string::npos) << "README.md: the largest extent";
}

TEST(ConstantsInDocs, Fp16MaxLambda) {
    expect_value<double>("RRC_FP16_MAX_LAMBDA", RRC_FP16_MAX_LAMBDA,
                         {{"docs/CONVENTIONS.md", "`RRC_FP16_MAX_LAMBDA` = "}, {"docs/measurements/STABILITY.md", "`RRC_FP16_MAX_LAMBDA` = "}});
}

TEST(ConstantsInDocs, DefaultAgeCap) {
    expect_value<unsigned>("RRC_DEFAULT_AGE_CAP", RRC_DEFAULT_AGE_CAP,
                           {{"docs/CONVENTIONS.md", "Age cap: default "},
                            {"docs/measurements/STABILITY.md", "A running mean with the default cap "},
                            {"include/rrc/rrc.h", "saturation of the age count; 0 = default "},
                            {kAccumulateHelp, "max_age=1..65535 ("}});
}

TEST(ConstantsInDocs, DefaultTau) {
    expect_value<float>("RRC_DEFAULT_TAU", RRC_DEFAULT_TAU,
                        {{"docs/CONVENTIONS.md", "τ default "},
                         {"docs/measurements/OFFLINE.md", "The library's default τ = "},
                         {"include/rrc/rrc.h", "MOTION tests; 0 = default "},
                         {kAccumulateHelp, "relative tolerance for linear-depth tests ("}});
}

TEST(ConstantsInDocs, DefaultEpsilonScale) {
    expect_value<float>("RRC_DEFAULT_EPSILON_SCALE_FLOAT32", RRC_DEFAULT_EPSILON_SCALE_FLOAT32,
                        {{"docs/CONVENTIONS.md", "default scale 1 (UNORM) or "},
                         {"include/rrc/rrc.h", "0 = default (1 unorm, "},
                         {"include/rrc/rrc_values.h", "/* eps = scale * ulp(z), default scale "},
                         {kAccumulateHelp, "the format's smallest increment (default "},
                         {kSampleHelp, "0 = the library default, "}});
    expect_value<float>("RRC_DEFAULT_EPSILON_SCALE_UNORM", RRC_DEFAULT_EPSILON_SCALE_UNORM,
                        {{"docs/CONVENTIONS.md", "(2^−149 at e = 0, i.e. the ulp of the fp32 value e); default scale "},
                         {"include/rrc/rrc.h", "epsilon = scale * increment; 0 = default ("},
                         {"include/rrc/rrc_values.h", "/* eps = scale / 65535, default scale "},
                         {"include/rrc/rrc_values.h", "/* eps = scale / 16777215, default scale "},
                         {kAccumulateHelp, "(default 4 for float32, "}});
}

TEST(ConstantsInDocs, DefaultBackgroundThreshold) {
    expect_value<float>("RRC_DEFAULT_BACKGROUND_THRESHOLD", RRC_DEFAULT_BACKGROUND_THRESHOLD,
                        {{"docs/CONVENTIONS.md", "background iff d ≥ threshold (default "},
                         {"docs/reference/api.md", "sky = +inf or ≥ `background_threshold` ("},
                         {"docs/measurements/OFFLINE.md", "`background_threshold` "},
                         {"include/rrc/rrc.h", "LINEAR: d >= this is background; 0 = default "},
                         {kAccumulateHelp, "linear depth >= T is background ("}});
}

// 0.4: the finishing steps' defaults and limits, as docs/CONVENTIONS.md states them.
TEST(ConstantsInDocs, FinishingStepDefaults) {
    expect_value<float>("RRC_DEFAULT_RECTIFY_GAMMA", RRC_DEFAULT_RECTIFY_GAMMA, {{"docs/CONVENTIONS.md", "γ = `rectify_gamma`, default "}});
    expect_value<float>("RRC_MAX_RECTIFY_GAMMA", RRC_MAX_RECTIFY_GAMMA, {{"docs/CONVENTIONS.md", "`rectify_gamma`, default 1, at most "}});
    expect_value<float>("RRC_DEFAULT_BLUR_SIGMA", RRC_DEFAULT_BLUR_SIGMA, {{"docs/CONVENTIONS.md", "σ_b = `blur_sigma`, default "}});
    expect_value<unsigned>("RRC_DEFAULT_FILL_RADIUS", RRC_DEFAULT_FILL_RADIUS, {{"docs/CONVENTIONS.md", "r = `fill_radius` (default "}});
    expect_value<unsigned>("RRC_MAX_FILL_RADIUS", RRC_MAX_FILL_RADIUS, {{"docs/CONVENTIONS.md", "(default 2, at most "}});
    expect_value<float>("RRC_DEFAULT_FILL_DEPTH_TOLERANCE", RRC_DEFAULT_FILL_DEPTH_TOLERANCE,
                        {{"docs/CONVENTIONS.md", "τ = `fill_depth_tolerance` (default "}});
}

// 0.5: the lag detector's defaults and limits, as docs/CONVENTIONS.md states them.
TEST(ConstantsInDocs, AntilagDefaults) {
    expect_value<float>("RRC_DEFAULT_ANTILAG_GAMMA", RRC_DEFAULT_ANTILAG_GAMMA, {{"docs/CONVENTIONS.md", "`RRC_DEFAULT_ANTILAG_GAMMA` = "}});
    expect_value<float>("RRC_MAX_ANTILAG_GAMMA", RRC_MAX_ANTILAG_GAMMA, {{"docs/CONVENTIONS.md", "`RRC_MAX_ANTILAG_GAMMA` = "}});
    expect_value<float>("RRC_DEFAULT_ANTILAG_THRESHOLD", RRC_DEFAULT_ANTILAG_THRESHOLD,
                        {{"docs/CONVENTIONS.md", "`RRC_DEFAULT_ANTILAG_THRESHOLD` = "}});
    expect_value<float>("RRC_MAX_ANTILAG_THRESHOLD", RRC_MAX_ANTILAG_THRESHOLD, {{"docs/CONVENTIONS.md", "`RRC_MAX_ANTILAG_THRESHOLD` = "}});
}

// 0.6: the blur bound's limit, as docs/CONVENTIONS.md states it.
TEST(ConstantsInDocs, BlurBoundLimit) {
    expect_value<float>("RRC_MAX_BLUR_BOUND", RRC_MAX_BLUR_BOUND, {{"docs/CONVENTIONS.md", "`RRC_MAX_BLUR_BOUND` = "}});
}

// 0.7: the view lobe's limit, as docs/CONVENTIONS.md states it.
TEST(ConstantsInDocs, ViewLobeLimit) {
    expect_value<float>("RRC_MAX_VIEW_LOBE", RRC_MAX_VIEW_LOBE, {{"docs/CONVENTIONS.md", "`RRC_MAX_VIEW_LOBE` = "}});
}

// docs/CONVENTIONS.md's table of channel options is the option table
// (compute/rrc_channel_options.def), row for row: each row's range, its
// default, what it needs, the REUSE refusal and its version, as the rows write
// them (the macros' values are checked above).
namespace {

// A C expression of the table as the docs write it: no `out.`, no casts, no `u`/`f` suffixes.
std::string as_written(std::string e) {
    e = std::regex_replace(e, std::regex("out\\."), "");
    e = std::regex_replace(e, std::regex("\\(float\\)"), "");
    e = std::regex_replace(e, std::regex("([0-9.])[uf]\\b"), "$1");
    return e;
}
std::string code(const std::string& e) { return "`" + as_written(e) + "`"; }

std::vector<std::string> option_rows() {
    std::vector<std::string> rows;
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, version, anchor)      \
    {                                                                                                                                  \
        const std::string c = #check, d = as_written(#dflt);                                                                           \
        const std::string range = c == "BOOL"    ? "0 or non-zero"                                                                     \
                                  : c == "UINT"  ? "0 to " + code(#high)                                                               \
                                  : c == "FLOAT" ? "[0, " + code(#high) + "]"                                                          \
                                  : c == "BELOW" ? "[0, " + code(#high) + ")"                                                          \
                                                 : std::string("a set or an enumeration, checked by hand");                           \
        const std::string zero = c == "NONE" ? "" : (d == "0" || d == "0.0") ? "0" : code(#dflt);                                      \
        const std::string n = std::string(needs_text).empty() ? "" : std::string("`") + needs_text + "`";                             \
        rows.push_back("| `" #member "` | " + range + " | " + zero + " | " + n + " | " + (std::string(#reuse) == "REFUSED" ? "refused" : "") + \
                       " | 0." + std::to_string(RRC_VERSION_MINOR(version)) + " |");                                                   \
    }
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    return rows;
}

}  // namespace

TEST(ConstantsInDocs, ChannelOptionTable) {
    const std::string doc = rrc_test::read_source("docs/CONVENTIONS.md");
    const std::string header = "| member | values | 0 means | needs | REUSE | since |";
    const size_t at = doc.find(header);
    ASSERT_NE(at, std::string::npos) << "docs/CONVENTIONS.md: no channel option table (header " << header << ")";
    std::vector<std::string> written;
    std::istringstream lines(doc.substr(at));
    for (std::string line; std::getline(lines, line) && line.rfind("|", 0) == 0;)
        if (line.rfind("| `", 0) == 0) written.push_back(line);
    const std::vector<std::string> expected = option_rows();
    std::string want;
    for (const std::string& r : expected) want += r + "\n";
    EXPECT_EQ(written, expected) << "docs/CONVENTIONS.md's channel option table must read, row for row:\n" << header << "\n|---|---|---|---|---|---|\n"
                                 << want;
}
