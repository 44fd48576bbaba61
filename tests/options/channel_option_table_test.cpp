// Every row of compute/rrc_channel_options.def is validated, uploaded,
// declared and documented (docs/design/adding-an-option.md): the rows are
// read here through the same X-macro, so a new row is checked without a new
// line in this file.  Device-free: the validation is compiled in, the
// kernels' SPIR-V is read from the embedded modules.
#include "support/source_file.h"

#include "channel_options.h"
#include "error.h"
#include "validation.h"

#include <rrc_module_fill_4_spv.h>
#include <rrc_module_frame_4_spv.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {

struct Row {
    const char* member;
    const char* check;    // NONE, BOOL, UINT, FLOAT, BELOW
    bool has_needs;       // `needs` is not `true`
    bool reuse_refused;
    bool param;
    unsigned bit, width;
    const char* anchor;
};

std::vector<Row> rows() {
    return {
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, version, anchor) \
    {#member, #check, std::string(#needs) != "true", std::string(#reuse) == "REFUSED", std::string(#param) == "PARAM", bit, width, anchor},
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    };
}

// A valid one-channel accumulating description; `edit` changes its channel.
struct Desc {
    rrc_channel_desc channel{};
    rrc_context_desc context{};
    Desc() {
        channel.type = RRC_STRUCT_TYPE_CHANNEL_DESC;
        channel.size = sizeof channel;
        std::snprintf(channel.name, sizeof channel.name, "s");
        channel.components = 1;
        channel.lambda = 0.6f;
        context.type = RRC_STRUCT_TYPE_CONTEXT_DESC;
        context.size = sizeof context;
        context.api_version = RRC_API_VERSION;
        context.width = 8;
        context.height = 8;
        context.reprojection = RRC_REPROJECTION_CAMERA;
        context.channel_count = 1;
        context.channels = &channel;
    }
    // The library's message for this description, or "" if it is valid.
    std::string error() {
        context.channels = &channel;
        try {
            rrc::resolve_context_desc(&context);
        } catch (const rrc::Error& e) {
            return e.what();
        }
        return "";
    }
};

// Sets member `name` of a channel to `value` (converted to the member's type).
void set_member(rrc_channel_desc& c, const std::string& name, double value) {
#define RRC_CHANNEL_OPTION(member, ...) \
    if (name == #member) c.member = (decltype(c.member))value;
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
}

TEST(ChannelOptionTable, EveryRangeIsValidatedAndNamedInTheMessage) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    int checked = 0;
    for (const Row& r : rows()) {
        const std::string check = r.check, what = std::string("channels[0].") + r.member;
        std::vector<double> bad;
        if (check == "UINT") bad = {4294967295.0};
        if (check == "FLOAT" || check == "BELOW") bad = {-1.0, 1e30, nan};
        for (double v : bad) {
            Desc d;
            // Its prerequisites on, so that only the range can refuse it.
            d.channel.rectify = 1, d.channel.antilag = 1, d.channel.fill_age = 4, d.channel.filter = RRC_HISTORY_FILTER_GAUSSIAN;
            ASSERT_EQ(d.error(), "") << "the base description of " << r.member;
            set_member(d.channel, r.member, v);
            const std::string message = d.error();
            EXPECT_NE(message.find(what), std::string::npos) << r.member << " = " << v << ": " << message;
            ++checked;
        }
    }
    EXPECT_GE(checked, 30) << "the table's ranges were not found";
}

TEST(ChannelOptionTable, NeedsAndReuseRefusalsAreValidated) {
    for (const Row& r : rows()) {
        if (std::string(r.check) == "NONE") continue;
        if (r.has_needs) {
            Desc d;  // no prerequisite is on in the base description
            set_member(d.channel, r.member, 1.0);
            if (std::string(r.member) == "blur_sigma") set_member(d.channel, r.member, 0.5);
            // The gate needs confidence off: its refusal is the base description with confidence on.
            if (std::string(r.member) == "gate_kappa") d.channel.confidence = 1;
            EXPECT_NE(d.error().find(std::string("channels[0].") + r.member), std::string::npos) << r.member << " without its prerequisite";
        }
        Desc d;
        d.channel.blend = RRC_BLEND_REUSE;
        d.channel.lambda = 0.0f;
        set_member(d.channel, r.member, std::string(r.member) == "age_cap" ? 8.0 : 0.5);
        if (std::string(r.check) == "UINT" || std::string(r.check) == "BOOL") set_member(d.channel, r.member, 1.0);
        const std::string message = d.error();
        if (r.reuse_refused)
            EXPECT_NE(message.find("REUSE"), std::string::npos) << r.member << " on a REUSE channel: " << message;
        else if (!r.has_needs)
            EXPECT_EQ(message, "") << r.member << " on a REUSE channel";
    }
}

// The SPIR-V words of a module, and its names: OpName and OpMemberName.
struct Spirv {
    std::vector<uint32_t> words;
    Spirv(const uint32_t* code, size_t bytes) : words(code, code + bytes / 4) {}
    static std::string literal(const uint32_t* w) { return std::string(reinterpret_cast<const char*>(w)); }
    // The ids OpName gives `name` (a struct's laid-out copy shares its name).
    std::vector<uint32_t> ids_named(const std::string& name) const {
        std::vector<uint32_t> out;
        for (size_t i = 5; i < words.size(); i += words[i] >> 16)
            if ((words[i] & 0xFFFF) == 5 /* OpName */ && literal(&words[i + 2]) == name) out.push_back(words[i + 1]);
        return out;
    }
    // Member index -> name, and member index -> Offset, of struct `id`.
    std::map<uint32_t, std::string> member_names(uint32_t id) const {
        std::map<uint32_t, std::string> out;
        for (size_t i = 5; i < words.size(); i += words[i] >> 16)
            if ((words[i] & 0xFFFF) == 6 /* OpMemberName */ && words[i + 1] == id) out[words[i + 2]] = literal(&words[i + 3]);
        return out;
    }
    std::map<uint32_t, uint32_t> member_offsets(uint32_t id) const {
        std::map<uint32_t, uint32_t> out;
        for (size_t i = 5; i < words.size(); i += words[i] >> 16)
            if ((words[i] & 0xFFFF) == 72 /* OpMemberDecorate */ && words[i + 1] == id && words[i + 3] == 35 /* Offset */)
                out[words[i + 2]] = words[i + 4];
        return out;
    }
};

// The kernel's parameter block is the library's, member for member.
void expect_block_matches(const Spirv& module, const char* which) {
    // The block's struct: the RrcChannelParams with offsets (std140).
    uint32_t id = 0;
    for (uint32_t candidate : module.ids_named("RrcChannelParams"))
        if (!module.member_offsets(candidate).empty()) id = candidate;
    ASSERT_NE(id, 0u) << which << ": no laid-out RrcChannelParams";
    const auto names = module.member_names(id);
    const auto offsets = module.member_offsets(id);
    std::map<std::string, size_t> library;
#define RRC_PARAM_NONE(member)
#define RRC_PARAM_PARAM(member) library[#member] = offsetof(rrc::KernelChannelParams, member);
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, ...) RRC_PARAM_##param(member)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_PARAM_PARAM
#undef RRC_PARAM_NONE
    EXPECT_EQ(names.size(), library.size()) << which;
    for (const auto& [index, name] : names) {
        ASSERT_TRUE(library.count(name)) << which << ": the kernel declares " << name << ", not a PARAM row";
        ASSERT_TRUE(offsets.count(index)) << which << ": " << name << " has no Offset";
        EXPECT_EQ(offsets.at(index), library[name]) << which << ": " << name << "'s offset";
    }
}

TEST(ChannelOptionTable, EveryParameterIsDeclaredWhereTheLibraryUploadsIt) {
    expect_block_matches(Spirv(rrc_module_frame_4_spv, sizeof rrc_module_frame_4_spv), "rrc_module_frame");
    expect_block_matches(Spirv(rrc_module_fill_4_spv, sizeof rrc_module_fill_4_spv), "rrc_module_fill");
    // And the upload holds each resolved value.
    Desc d;
    d.channel.lambda = 0.25f, d.channel.age_cap = 77, d.channel.rectify = 1, d.channel.rectify_gamma = 3.5f, d.channel.fill_age = 5;
    d.channel.fill_depth_tolerance = 0.125f, d.channel.fill_prior = 2.0f, d.channel.antilag = 1, d.channel.antilag_gamma = 1.5f;
    d.channel.antilag_threshold = 0.75f, d.channel.blur_bound = 6.0f, d.channel.view_lobe = 0.3f, d.channel.filter = RRC_HISTORY_FILTER_GAUSSIAN;
    d.channel.blur_sigma = 0.25f;
    const rrc::ChannelConfig c = rrc::resolve_context_desc(&d.context).channels[0];
    const rrc::KernelChannelParams p = rrc::kernel_channel_params(c);
#define RRC_PARAM_NONE(member, dflt)
#define RRC_PARAM_PARAM(member, dflt)          \
    EXPECT_EQ(p.member, c.member) << #member; \
    EXPECT_EQ(p.member, d.channel.member != 0 ? (decltype(p.member))d.channel.member : (decltype(p.member))(dflt)) \
        << #member " is uploaded as the caller set it (0: the row's default)";
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, ...) RRC_PARAM_##param(member, dflt)
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
#undef RRC_PARAM_PARAM
#undef RRC_PARAM_NONE
}

TEST(ChannelOptionTable, FeatureWordOfTheDefaultsIsTheKernelsDefault) {
    EXPECT_EQ(rrc::channel_feature_word(rrc::ChannelConfig{}), RRC_DEFAULT_CHANNEL_FEATURES);
    Desc d;
    EXPECT_EQ(rrc::channel_feature_word(rrc::resolve_context_desc(&d.context).channels[0]) & ~(1u << 1), 0u)
        << "a default channel (lambda 0.6: fp16) has no feature but fp16";
    // Each feature field is read by the per-channel passes: its selector is declared there.
    const Spirv frame(rrc_module_frame_4_spv, sizeof rrc_module_frame_4_spv), fill(rrc_module_fill_4_spv, sizeof rrc_module_fill_4_spv);
    for (const Row& r : rows()) {
        const std::string selector = std::string("ch_") + r.member + "(i1;";
        if (r.width != 0) EXPECT_FALSE(frame.ids_named(selector).empty() && fill.ids_named(selector).empty()) << r.member << "'s field selector";
    }
}

TEST(ChannelOptionTable, EveryRowIsDocumentedInItsSection) {
    const std::string conventions = rrc_test::read_source("docs/CONVENTIONS.md");
    for (const Row& r : rows()) {
        const std::string heading = std::string(" ") + r.anchor;
        size_t at = std::string::npos;
        for (size_t p = conventions.find("\n#"); p != std::string::npos; p = conventions.find("\n#", p + 1)) {
            const size_t text = conventions.find_first_not_of('#', p + 1);
            if (conventions.compare(text, heading.size(), heading) == 0) {
                at = p;
                break;
            }
        }
        ASSERT_NE(at, std::string::npos) << r.member << ": docs/CONVENTIONS.md has no section \"" << r.anchor << "\"";
        const size_t end = conventions.find("\n## ", at + 1);
        const std::string section = conventions.substr(at, end == std::string::npos ? std::string::npos : end - at);
        EXPECT_NE(section.find(std::string("`") + r.member + "`"), std::string::npos)
            << r.member << " is not named in docs/CONVENTIONS.md, \"" << r.anchor << "\"";
    }
}

}  // namespace
