#include "hit_test_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <vector>

namespace rrc_hit_report {
namespace {

const char kBegin[] = "<!-- hit-test-recall:begin -->";
const char kEnd[] = "<!-- hit-test-recall:end -->";

// Appended once, with the markers, to a file that lacks them.
const char kSection[] =
    "\n## Hit test against true visibility: FIXED and ADAPTIVE side by side\n\n"
    "Recall (hits / pixels whose surface point was visible in the previous frame and whose\n"
    "bilinear depth taps all lie on it) and false hits (hits on points that were not visible),\n"
    "scored by the analytic scenes' oracle (`tests/scenes/visibility.h`), for the library's\n"
    "default depth test (`depth_test` 0: ADAPTIVE for 0.2 callers) and for `FIXED`; the default\n"
    "run asserts recall >= 99.5% and, for PREV_CLIP and MOTION_DEPTH, 0 false hits\n"
    "(`tests/visibility/`). Thin-card rows: wall pixels the card covered in the previous frame\n"
    "(its gap 1e-3 d along the central ray), each of which must miss. Regenerate:\n\n"
    "```sh\n"
    "cmake --build build/release --target rrc_visibility_test &&\n"
    "  RRC_HIT_TEST_REPORT=$PWD/docs/measurements/ACCURACY.md XDG_RUNTIME_DIR=/tmp RRC_VALIDATION=1 \\\n"
    "  VK_ICD_FILENAMES=$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json) \\\n"
    "  build/release/tests/visibility/rrc_visibility_test\n"
    "```\n\n";

// The rows so far, in the order the cases ran (gtest runs them on one thread).
std::vector<Row> g_rows;

class Writer : public ::testing::Environment {
public:
    void TearDown() override {
        const char* path = std::getenv("RRC_HIT_TEST_REPORT");
        if (!path || g_rows.empty()) return;
        std::stringstream doc;
        doc << std::ifstream(path).rdbuf();
        std::string text = doc.str();
        if (text.find(kBegin) == std::string::npos || text.find(kEnd) == std::string::npos) {
            if (!text.empty() && text.back() != '\n') text += '\n';
            text += kSection + std::string(kBegin) + "\n" + kEnd + "\n";
        }
        const size_t b = text.find(kBegin), e = text.find(kEnd);
        if (e < b) {
            ADD_FAILURE() << path << ": " << kEnd << " before " << kBegin;
            return;
        }
        std::ostringstream table;
        table << kBegin
              << "\n| case | pixels scored | excluded (by reason) | recall FIXED | recall ADAPTIVE (default) | false hits FIXED | "
              << "false hits ADAPTIVE (default) |\n|---|---|---|---|---|---|---|\n";
        // The cells are this executable's own text: no '|' to escape.
        for (const Row& r : g_rows)
            for (const std::string* cell :
                 {&r.name, &r.scored, &r.excluded, &r.recall_fixed, &r.recall_default, &r.false_fixed, &r.false_default})
                table << "| " << *cell << (cell == &r.false_default ? " |\n" : " ");
        // The date and the identical-mask count say which library the default
        // column measured (ADAPTIVE became the default in 0.2: CHANGELOG.md, "Changes since 0.1").
        char date[32];
        const std::time_t now = std::time(nullptr);
        std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
        const size_t same = static_cast<size_t>(std::count_if(g_rows.begin(), g_rows.end(), [](const Row& r) { return r.same_masks; }));
        table << "\nMeasured " << date << ", " << g_rows.size() << " cases; in " << same
              << " of them the default test's masks equal FIXED's bit for bit"
              << (same == g_rows.size() ? " (the library measured does not distinguish them: ADAPTIVE is not in it).\n" : ".\n");
        text.replace(b, e - b, table.str());
        std::ofstream(path) << text;
    }
};
const ::testing::Environment* const kWriter = ::testing::AddGlobalTestEnvironment(new Writer);

}  // namespace

void add(const Row& row) { g_rows.push_back(row); }

std::string format(const char* fmt, ...) {
    va_list args, again;
    va_start(args, fmt);
    va_copy(again, args);
    std::string out(static_cast<size_t>(std::max(std::vsnprintf(nullptr, 0, fmt, args), 0)), '\0');
    va_end(args);
    std::vsnprintf(&out[0], out.size() + 1, fmt, again);
    va_end(again);
    return out;
}

}  // namespace rrc_hit_report
