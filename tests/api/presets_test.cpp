// rrc_channel_preset and rrc_context_preset (include/rrc/rrc.h, "Presets"):
// every preset's description validates, the struct rules hold (only the
// caller's size is written, nothing on an error), tunings are kept, and
// each preset's values are its row in docs/reference/presets.md.
#include "support/source_file.h"

#include <rrc/rrc.h>

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Variant {
    rrc_preset preset;
    uint32_t flags;
    const char* name;     // as the docs' first column
    const char* variant;  // as the docs' second column
};
const Variant kVariants[] = {
    {RRC_PRESET_PCF_SHADOWS, RRC_PRESET_FLAG_BASE, "RRC_PRESET_PCF_SHADOWS", "base"},
    {RRC_PRESET_PCF_SHADOWS, 0, "RRC_PRESET_PCF_SHADOWS", "no base"},
    {RRC_PRESET_ENV_BUMP, RRC_PRESET_FLAG_BASE, "RRC_PRESET_ENV_BUMP", "base"},
    {RRC_PRESET_ENV_BUMP, 0, "RRC_PRESET_ENV_BUMP", "no base"},
    {RRC_PRESET_SOFT_SHADOWS, RRC_PRESET_FLAG_BASE, "RRC_PRESET_SOFT_SHADOWS", "base"},
    {RRC_PRESET_SOFT_SHADOWS, 0, "RRC_PRESET_SOFT_SHADOWS", "no base"},
    {RRC_PRESET_SHADING_CACHE, 0, "RRC_PRESET_SHADING_CACHE", "-"},
    {RRC_PRESET_OFFLINE, 0, "RRC_PRESET_OFFLINE", "-"},
};

rrc_channel_desc named_channel(const char* name, uint32_t components) {
    rrc_channel_desc c;
    std::memset(&c, 0, sizeof c);
    c.type = RRC_STRUCT_TYPE_CHANNEL_DESC;
    c.size = sizeof c;
    std::snprintf(c.name, sizeof c.name, "%s", name);
    c.components = components;
    return c;
}

rrc_context_desc context(uint32_t w, uint32_t h, const rrc_channel_desc* channel) {
    rrc_context_desc d;
    std::memset(&d, 0, sizeof d);
    d.type = RRC_STRUCT_TYPE_CONTEXT_DESC;
    d.size = sizeof d;
    d.api_version = RRC_API_VERSION;
    d.width = w, d.height = h;
    d.depth_mode = RRC_DEPTH_MODE_REVERSED;
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    d.channel_count = 1;
    d.channels = channel;
    return d;
}

TEST(Presets, EveryPresetsDescriptionValidates) {
    for (const Variant& v : kVariants) {
        SCOPED_TRACE(std::string(v.name) + ", " + v.variant);
        rrc_channel_desc ch = named_channel("signal", 4);
        ASSERT_EQ(rrc_channel_preset(v.preset, v.flags, RRC_API_VERSION, &ch), RRC_SUCCESS) << rrc_last_error();
        rrc_context_desc d = context(320, 180, &ch);
        ASSERT_EQ(rrc_context_preset(v.preset, v.flags, RRC_API_VERSION, &d), RRC_SUCCESS) << rrc_last_error();
        EXPECT_EQ(rrc_validate_context_desc(&d), RRC_SUCCESS) << rrc_last_error();
        EXPECT_STREQ(ch.name, "signal") << "the preset wrote the caller's name";
        EXPECT_EQ(ch.components, 4u) << "the preset wrote the caller's components";
    }
}

TEST(Presets, OnlyTheCallersSizeIsWrittenAndNothingOnAnError) {
    // A 0.1 caller's channel ends before rectify: the bytes past it stay as they were.
    unsigned char bytes[sizeof(rrc_channel_desc) + 16];
    std::memset(bytes, 0xCD, sizeof bytes);
    rrc_channel_desc ch = named_channel("old", 1);
    const size_t old_size = offsetof(rrc_channel_desc, rectify);
    ch.size = (uint32_t)old_size;
    std::memcpy(bytes, &ch, old_size);
    ASSERT_EQ(rrc_channel_preset(RRC_PRESET_SOFT_SHADOWS, RRC_PRESET_FLAG_BASE, RRC_API_VERSION, (rrc_channel_desc*)bytes), RRC_SUCCESS)
        << rrc_last_error();
    rrc_channel_desc written;
    std::memcpy(&written, bytes, old_size);
    EXPECT_FLOAT_EQ(written.lambda, 0.95f);
    EXPECT_EQ(written.filter, (uint32_t)RRC_HISTORY_FILTER_CATMULL_ROM);
    for (size_t i = old_size; i < sizeof bytes; ++i) ASSERT_EQ(bytes[i], 0xCD) << "byte " << i << " past the caller's size was written";

    // Errors: a bad preset, a flag it does not take, an unknown flag, a newer tuning, a wrong tag.
    rrc_channel_desc before = named_channel("x", 1);
    before.lambda = 0.123f;
    struct Case {
        rrc_preset preset;
        uint32_t flags, tuning;
        rrc_result code;
    };
    const Case cases[] = {{0, 0, RRC_API_VERSION, RRC_ERROR_INVALID_ARGUMENT},
                          {99, 0, RRC_API_VERSION, RRC_ERROR_INVALID_ARGUMENT},
                          {RRC_PRESET_OFFLINE, RRC_PRESET_FLAG_BASE, RRC_API_VERSION, RRC_ERROR_INVALID_ARGUMENT},
                          {RRC_PRESET_PCF_SHADOWS, 0x2, RRC_API_VERSION, RRC_ERROR_INVALID_ARGUMENT},
                          {RRC_PRESET_PCF_SHADOWS, 0,
                           RRC_MAKE_VERSION(RRC_VERSION_MAJOR(RRC_API_VERSION), RRC_VERSION_MINOR(RRC_API_VERSION) + 1, 0),
                           RRC_ERROR_UNSUPPORTED},
                          {RRC_PRESET_PCF_SHADOWS, 0, RRC_MAKE_VERSION(1, 0, 0), RRC_ERROR_UNSUPPORTED}};
    for (const Case& c : cases) {
        rrc_channel_desc ch2 = before;
        EXPECT_EQ(rrc_channel_preset(c.preset, c.flags, c.tuning, &ch2), c.code) << "preset " << c.preset << " flags " << c.flags;
        EXPECT_EQ(std::memcmp(&ch2, &before, sizeof ch2), 0) << "written on an error";
    }
    rrc_channel_desc wrong = before;
    wrong.type = RRC_STRUCT_TYPE_CONTEXT_DESC;
    EXPECT_EQ(rrc_channel_preset(RRC_PRESET_PCF_SHADOWS, 0, 0, &wrong), RRC_ERROR_INVALID_STRUCT);
    EXPECT_EQ(rrc_channel_preset(RRC_PRESET_PCF_SHADOWS, 0, 0, nullptr), RRC_ERROR_INVALID_ARGUMENT);
    // OFFLINE's motion scale needs the size: refused, nothing written.
    rrc_context_desc d = context(0, 0, &before), d0 = d;
    EXPECT_EQ(rrc_context_preset(RRC_PRESET_OFFLINE, 0, 0, &d), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::memcmp(&d, &d0, sizeof d), 0);
}

TEST(Presets, TuningsAreKeptAndTheLatestIsTheDefault) {
    for (const Variant& v : kVariants) {
        rrc_channel_desc latest = named_channel("a", 1), pinned = latest, old = latest;
        ASSERT_EQ(rrc_channel_preset(v.preset, v.flags, 0, &latest), RRC_SUCCESS);
        ASSERT_EQ(rrc_channel_preset(v.preset, v.flags, RRC_API_VERSION, &pinned), RRC_SUCCESS);
        // A caller built before presets existed gets the first tuning, which this version's is.
        ASSERT_EQ(rrc_channel_preset(v.preset, v.flags, RRC_MAKE_VERSION(0, 9, 0), &old), RRC_SUCCESS);
        EXPECT_EQ(std::memcmp(&latest, &pinned, sizeof latest), 0) << v.name;
        EXPECT_EQ(std::memcmp(&old, &pinned, sizeof old), 0) << v.name;
    }
}

TEST(Presets, ContextPresetsFixWhatTheApplicationFixes) {
    rrc_channel_desc ch = named_channel("c", 1);
    rrc_context_desc d = context(320, 180, &ch);
    ASSERT_EQ(rrc_context_preset(RRC_PRESET_OFFLINE, 0, 0, &d), RRC_SUCCESS);
    EXPECT_EQ(d.depth_mode, (uint32_t)RRC_DEPTH_MODE_LINEAR);
    EXPECT_EQ(d.reprojection, (uint32_t)RRC_REPROJECTION_MOTION);
    EXPECT_EQ(d.motion_scale[0], (float)(1.0 / 320));  // pixels, y up (Cycles' vectors)
    EXPECT_EQ(d.motion_scale[1], (float)(-1.0 / 180));
    EXPECT_EQ(d.depth_test, (uint32_t)RRC_DEPTH_TEST_FIXED);
    rrc_context_desc c = context(320, 180, &ch), c0 = c;
    ASSERT_EQ(rrc_context_preset(RRC_PRESET_PCF_SHADOWS, RRC_PRESET_FLAG_BASE, 0, &c), RRC_SUCCESS);
    EXPECT_EQ(std::memcmp(&c, &c0, sizeof c), 0) << "pcf fixes no context member";
    ASSERT_EQ(rrc_context_preset(RRC_PRESET_SHADING_CACHE, 0, 0, &c), RRC_SUCCESS);
    EXPECT_EQ(c.refresh_policy, (uint32_t)RRC_REFRESH_TILED);
    EXPECT_EQ(c.refresh_period, 4u);
    EXPECT_EQ(c.refresh_tiles[0] + c.refresh_tiles[1], 0u) << "the default grid: vertical strips, as rrc-cache measured";
    EXPECT_GT(c.max_lifetime, 0u);
}

// docs/reference/presets.md's table: one row per preset and variant,
// "| `RRC_PRESET_X` | variant | λ | blend | filter | age cap | fill age |
// fill radius | fill prior | rectify | anti-lag γ_a / T | blur bound | view lobe | residual | gate κ |".
TEST(Presets, EachPresetIsItsRowInTheDocs) {
    const std::string text = rrc_test::read_source("docs/reference/presets.md");
    std::map<std::string, std::vector<std::string>> rows;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("| `RRC_PRESET_", 0) != 0) continue;
        std::vector<std::string> cells;
        std::istringstream cols(line.substr(1));
        for (std::string cell; std::getline(cols, cell, '|');) {
            cell = std::regex_replace(cell, std::regex("^\\s+|\\s+$|`"), "");
            cells.push_back(cell);
        }
        if (!cells.empty() && cells.back().empty()) cells.pop_back();
        if (cells.size() != 15) continue;  // the context members' table
        rows[cells[0] + "/" + cells[1]] = cells;
    }
    ASSERT_EQ(rows.size(), sizeof kVariants / sizeof kVariants[0]) << "one row per preset and variant";
    const char* blends[] = {"FIXED", "AGE_AWARE", "RUNNING_MEAN", "REUSE"};
    const char* filters[] = {"BILINEAR", "NEAREST", "CATMULL_ROM", "GAUSSIAN"};
    auto num = [](double x) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", x);
        return std::string(b);
    };
    for (const Variant& v : kVariants) {
        const std::string key = std::string(v.name) + "/" + v.variant;
        SCOPED_TRACE(key);
        ASSERT_TRUE(rows.count(key)) << "no row in docs/reference/presets.md";
        const std::vector<std::string>& r = rows[key];
        rrc_channel_desc c = named_channel("d", 1);
        ASSERT_EQ(rrc_channel_preset(v.preset, v.flags, RRC_API_VERSION, &c), RRC_SUCCESS);
        EXPECT_EQ(r[2], num(c.lambda));
        EXPECT_EQ(r[3], blends[c.blend]);
        EXPECT_EQ(r[4], filters[c.filter]);
        EXPECT_EQ(r[5], c.age_cap ? num(c.age_cap) : "255");
        EXPECT_EQ(r[6], c.fill_age ? num(c.fill_age) : "off");
        EXPECT_EQ(r[7], !c.fill_age ? "-" : c.fill_radius ? num(c.fill_radius) : "2");  // 0: RRC_DEFAULT_FILL_RADIUS
        EXPECT_EQ(r[8], c.fill_prior > 0 ? num(c.fill_prior) : "-");
        EXPECT_EQ(r[9], c.rectify ? "on" : "off");
        EXPECT_EQ(r[10], c.antilag ? num(c.antilag_gamma) + " / " + num(c.antilag_threshold) : "off");
        EXPECT_EQ(r[11], c.blur_bound > 0 ? num(c.blur_bound) : "off");
        EXPECT_EQ(r[12], c.view_lobe > 0 ? num(c.view_lobe) : "off");
        EXPECT_EQ(r[13], c.residual ? "on" : "off");
        EXPECT_EQ(r[14], c.gate_kappa > 0 ? num(c.gate_kappa) : "off");
    }
}

}  // namespace
