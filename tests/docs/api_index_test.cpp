// The concept index of docs/reference/api.md ("The API by concept") must list
// every public struct, struct member and function of include/rrc/rrc.h and
// include/rrc/rrc_vulkan.h, one table row each:
//     | `rrc_struct.member` (or `rrc_struct`, `rrc_function`) | meaning | 0.N |
// with 0.N the API version that added it.  The headers are parsed here, so a
// member appended without a row fails, as does a row naming nothing or a
// version the headers contradict.  A version comes from the headers:
//   - in the 0.1 headers kept in tests/abi/rrc_0_1/: 0.1;
//   - a member below a "---- 0.N" mark inside its struct: 0.N;
//   - otherwise its struct's: the "/* 0.N */" on the struct's RRC_STRUCT_TYPE_
//     tag when it has one, else only "after 0.1" is known.
// The members every tagged struct starts with (type, next, size) are listed
// once, as rrc_struct_header's.
#include "support/source_file.h"

#include <rrc/rrc.h>  // RRC_MAKE_VERSION, RRC_VERSION_MINOR (the option table's versions)

#include <gtest/gtest.h>

#include <cctype>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using rrc_test::read_source;

namespace {

// The text without comments; a comment holding a version mark "---- 0.N"
// becomes the statement "@0.N;".
std::string strip_comments(const std::string& text) {
    std::string out;
    for (size_t i = 0; i < text.size();) {
        if (text.compare(i, 2, "//") == 0) {
            i = text.find('\n', i);
            if (i == std::string::npos) break;
        } else if (text.compare(i, 2, "/*") == 0) {
            const size_t end = text.find("*/", i + 2);
            const std::string comment = text.substr(i, end == std::string::npos ? std::string::npos : end - i);
            std::smatch mark;
            out += std::regex_search(comment, mark, std::regex("---- (0\\.[0-9]+)")) ? " @" + mark[1].str() + "; " : " ";
            if (end == std::string::npos) break;
            i = end + 2;
        } else {
            out += text[i++];
        }
    }
    return out;
}

// The public API of a pair of headers: name -> the version that added it,
// "" where the headers do not say.  Names: "rrc_struct", "rrc_struct.member",
// "rrc_function".
struct Api {
    std::map<std::string, std::string> since;
    std::set<std::string> structs;
};

Api parse(const std::string& dir) {
    Api api;
    const std::string raw = read_source(dir + "/rrc.h") + "\n" + read_source(dir + "/rrc_vulkan.h");
    const std::string text = strip_comments(raw);
    const std::regex open("typedef struct (\\w+) \\{");
    for (std::sregex_iterator it(text.begin(), text.end(), open), end; it != end; ++it) {
        const std::string name = (*it)[1];
        const size_t begin = it->position() + it->length();
        const size_t close = text.find("} " + name + ";", begin);
        if (close == std::string::npos) {
            ADD_FAILURE() << dir << ": no end of struct " << name;
            continue;
        }
        // The struct's own version: "/* 0.N */" on its type tag's line.
        std::string tag = "RRC_STRUCT_TYPE_" + name.substr(4);
        for (char& c : tag) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        std::smatch m;
        const std::string struct_since =
            std::regex_search(raw, m, std::regex(tag + " +0x[0-9a-fA-Fu]+ +/\\* (0\\.[0-9]+) \\*/")) ? m[1].str() : "";
        api.structs.insert(name);
        api.since[name] = struct_since;
        std::vector<std::string> members;
        std::string mark = struct_since;
        std::stringstream body(text.substr(begin, close - begin));
        for (std::string statement; std::getline(body, statement, ';');) {
            statement = std::regex_replace(statement, std::regex("\\[[^\\]]*\\]"), "");  // arrays
            if (std::regex_search(statement, m, std::regex("^\\s*@(0\\.[0-9]+)\\s*$"))) {
                mark = m[1];
                continue;
            }
            std::stringstream declarators(statement);  // `uint32_t width, height`
            for (std::string d; std::getline(declarators, d, ',');)
                if (std::regex_search(d, m, std::regex("(\\w+)\\s*$"))) {
                    members.push_back(m[1]);
                    api.since[name + "." + m[1].str()] = mark;
                }
        }
        EXPECT_FALSE(members.empty()) << dir << ": struct " << name << " has no members";
        if (name != "rrc_struct_header" && members.size() >= 3 && members[0] == "type" && members[1] == "next" && members[2] == "size")
            for (const char* header : {".type", ".next", ".size"}) api.since.erase(name + header);
    }
    const std::regex function("\\bRRC_API\\b[^;(]*?\\b(rrc_\\w+)\\s*\\(");
    for (std::sregex_iterator it(text.begin(), text.end(), function), end; it != end; ++it) api.since[(*it)[1]] = "";
    return api;
}

// The version each name of the current headers must carry in the index; "later than 0.1" where only that is known.
const char* const kAfter01 = "later than 0.1";

std::map<std::string, std::string> expected_versions() {
    const Api now = parse("include/rrc");
    const Api v01 = parse("tests/abi/rrc_0_1/rrc");
    std::map<std::string, std::string> expected;
    for (const auto& [name, since] : now.since) {
        const std::string owner = name.substr(0, name.find('.'));
        if (v01.since.count(name))
            expected[name] = "0.1";
        else if (!since.empty())
            expected[name] = since;
        else if (name != owner && v01.structs.count(owner))
            ADD_FAILURE() << "include/rrc: " << name << " is not in the 0.1 struct and has no \"---- 0.N\" mark above it";
        else
            expected[name] = kAfter01;
    }
    EXPECT_GT(expected.size(), 150u) << "the header parse found too little";
    return expected;
}

// The rows of the index: name -> the versions its rows give.
std::multimap<std::string, std::string> index_rows() {
    const std::string doc = read_source("docs/reference/api.md");
    const size_t begin = doc.find("\n## The API by concept\n");
    EXPECT_NE(begin, std::string::npos) << "docs/reference/api.md: no section \"The API by concept\"";
    if (begin == std::string::npos) return {};
    const size_t end = doc.find("\n## ", begin + 1);
    std::stringstream section(doc.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    std::multimap<std::string, std::string> rows;
    const std::regex row("^\\| `(rrc_\\w+(\\.\\w+)?)` \\|.*\\| (0\\.[0-9]+) \\|$");
    for (std::string line; std::getline(section, line);) {
        std::smatch m;
        if (std::regex_match(line, m, row))
            rows.emplace(m[1], m[3]);
        else
            EXPECT_NE(line.rfind("| `rrc_", 0), 0u) << "docs/reference/api.md: a row not of the form | `name` | meaning | 0.N |: " << line;
    }
    // rrc_channel_desc's options: each row of compute/rrc_channel_options.def is
    // its index row (its version; its meaning in docs/CONVENTIONS.md, its range in the table).
#define RRC_CHANNEL_OPTION(member, ctype, check, dflt, high, needs, needs_text, reuse, param, bit, width, feature, version, anchor) \
    rows.emplace("rrc_channel_desc." #member, "0." + std::to_string(RRC_VERSION_MINOR(version)));
#include <rrc_channel_options.def>
#undef RRC_CHANNEL_OPTION
    return rows;
}

}  // namespace

TEST(ApiIndexInDocs, EveryStructMemberAndFunctionIsListed) {
    const auto rows = index_rows();
    for (const auto& [name, version] : expected_versions())
        EXPECT_TRUE(rows.count(name)) << "docs/reference/api.md, \"The API by concept\": no row for " << name << " (since " << version << ")";
}

TEST(ApiIndexInDocs, EveryRowNamesTheApiWithItsVersion) {
    const auto expected = expected_versions();
    for (const auto& [name, version] : index_rows()) {
        const auto it = expected.find(name);
        if (it == expected.end()) {
            ADD_FAILURE() << "docs/reference/api.md, \"The API by concept\": " << name << " is no public struct, member or function";
        } else if (it->second == kAfter01) {
            EXPECT_NE(version, "0.1") << "docs/reference/api.md, \"The API by concept\": " << name << " is not in the 0.1 headers";
        } else {
            EXPECT_EQ(version, it->second) << "docs/reference/api.md, \"The API by concept\": the version of " << name;
        }
    }
}
