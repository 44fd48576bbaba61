#include "clean_report.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace rrc_cli {

CleanReport::CleanReport(const Options& o, const SequenceLayout& layout, std::vector<uint32_t> fill_ages)
    : options_(o), layout_(layout), fill_ages_(std::move(fill_ages)), summary_(layout.signals.size()) {
    csv_ = std::string("frame,layer,") + rrc_host::kCleanCsvColumns + "\n";
}

void CleanReport::add_frame(int64_t f, const FrameData& data, const FrameResult& result) {
    const size_t n = result.mask.size();
    std::vector<float> u(n);
    for (size_t p = 0; p < n; ++p) u[p] = rrc_host::clean_inverse_depth((uint32_t)options_.depth_mode, data.depth[p]);
    for (size_t s = 0; s < layout_.signals.size(); ++s) {
        rrc_host::CleanFrame cf;
        cf.width = (uint32_t)layout_.width;
        cf.height = (uint32_t)layout_.height;
        cf.mask = result.mask.data();
        cf.age = result.age[s].data();
        cf.inverse_depth = u.data();
        cf.object_id = data.object_id.empty() ? nullptr : data.object_id.data();
        cf.fill_age = fill_ages_[s];
        rrc_host::CleanSums sums;
        const SignalLayout& sig = layout_.signals[s];
        rrc_host::add_clean_errors(sums, rrc_host::clean_regions(cf), data.samples[s].data(), result.values[s].data(),
                                   (int)sig.rrc_components, (int)metric_channels(sig).size());
        csv_ += rrc_host::clean_csv_rows(std::to_string(f) + "," + sig.options.layer, sums);
        if (f >= options_.clean_from) summary_[s].add(sums);
    }
    if (f >= options_.clean_from) ++frames_;
}

void CleanReport::finish(std::ostream& out) const {
    const std::string range = "frames " + std::to_string(options_.clean_from) + "-" + std::to_string(options_.last_frame);
    std::string md = "# What rrc adds to a clean input\n\nThe accumulated output against each frame's own input, " + range +
                     " (" + std::to_string(frames_) +
                     " frames), by region (docs/measurements/OFFLINE.md, \"What rrc adds to a clean input\").\n";
    for (size_t s = 0; s < layout_.signals.size(); ++s) {
        const rrc_host::CleanSums& c = summary_[s];
        md += "\n## " + layout_.signals[s].options.layer + " (fill_age " + std::to_string(fill_ages_[s]) + ")\n\n" +
              rrc_host::clean_table(c);
        if (c.skipped) md += "\n" + std::to_string(c.skipped) + " pixels with a non-finite value left out.\n";
        char line[256];
        std::snprintf(line, sizeof line, "RMSE %.4g (history %.4g, young %.4g, filled %.4g, edge %.4g, miss %.4g)", c.rmse(rrc_host::kCleanRegionCount),
                      c.rmse(rrc_host::kCleanHistory), c.rmse(rrc_host::kCleanYoung), c.rmse(rrc_host::kCleanFilled),
                      c.rmse(rrc_host::kCleanEdge), c.rmse(rrc_host::kCleanMiss));
        out << "rrc-accumulate: " << layout_.signals[s].options.layer << " against its own input, " << range << ": " << line << "; "
            << options_.clean_report << "\n";
    }
    const std::string& path = options_.clean_report;
    const bool csv = path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << (csv ? csv_ : md);
    if (!f.flush()) throw CliError("cannot write '" + path + "'");
}

}  // namespace rrc_cli
