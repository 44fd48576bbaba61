#include "stability_report.h"

#include <gtest/gtest.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#ifndef RRC_STABILITY_SECTION
#    error "RRC_STABILITY_SECTION must name the test executable"
#endif

namespace rrc_stab {
namespace {

struct Row {
    std::string area, name, bound, measured;
};

std::mutex g_mutex;
std::vector<Row>& rows() {
    static std::vector<Row> r;
    return r;
}

// A markdown table cell: '|' escaped, newlines flattened.
std::string cell(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '|') out += '\\';
        out += c == '\n' ? ' ' : c;
    }
    return out;
}

class ReportWriter : public ::testing::Environment {
public:
    void TearDown() override {
        const char* path = std::getenv("RRC_STABILITY_REPORT");
        if (!path || rows().empty()) return;
        const std::string section = RRC_STABILITY_SECTION;
        const std::string begin = "<!-- stability table " + section + ": begin -->";
        const std::string end = "<!-- stability table " + section + ": end -->";
        std::stringstream doc;
        doc << std::ifstream(path).rdbuf();
        std::string text = doc.str();
        size_t b = text.find(begin), e = text.find(end);
        if (b == std::string::npos || e == std::string::npos || e < b) {
            ADD_FAILURE() << path << " lacks the markers " << begin << " / " << end;
            return;
        }
        std::ostringstream table;
        table << begin << "\n| area | case | bound (asserted) | measured |\n|---|---|---|---|\n";
        for (const Row& r : rows())
            table << "| " << cell(r.area) << " | " << cell(r.name) << " | " << cell(r.bound) << " | " << cell(r.measured) << " |\n";
        text.replace(b, e - b, table.str());
        std::ofstream(path) << text;
    }
};
const ::testing::Environment* const kWriter = ::testing::AddGlobalTestEnvironment(new ReportWriter);

}  // namespace

void report(const std::string& area, const std::string& name, const std::string& bound, const std::string& measured) {
    std::lock_guard<std::mutex> lock(g_mutex);
    for (Row& r : rows())
        if (r.area == area && r.name == name) {  // a running summary: the latest value wins
            r.bound = bound;
            r.measured = measured;
            return;
        }
    rows().push_back({area, name, bound, measured});
    std::printf("[stability] %s / %s: bound %s, measured %s\n", area.c_str(), name.c_str(), bound.c_str(), measured.c_str());
}

std::string format(const char* fmt, ...) {
    char buffer[1024];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(buffer, sizeof buffer, fmt, args);
    va_end(args);
    return buffer;
}

}  // namespace rrc_stab
