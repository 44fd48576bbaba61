// The run's outputs: the table on stdout, bench.csv and bench.json (one row
// per configuration, the same columns), and report.md, the tables
// docs/measurements/PERFORMANCE.md quotes.
#pragma once

#include "analysis.h"
#include "result.h"

#include <string>
#include <vector>

namespace rrc_bench {

/** Published figures (not measured here) the memory column is set beside. */
constexpr double kNrdSigmaMb1080p = 31.9;  // NRD's SIGMA shadow denoiser at 1080p, NRD's README
constexpr double kFsr2Mb1080pQuality = 115.0;  // FSR 2 at 1080p, quality mode, AMD's FSR 2 documentation

void print_table(const std::vector<Row>& rows);
void write_csv(const std::string& path, const std::vector<Row>& rows);
void write_json(const std::string& path, const RunInfo& info, const std::vector<Row>& rows, const Linearity& lin,
                const std::vector<Target>& targets);
void write_markdown(const std::string& path, const RunInfo& info, const std::vector<Row>& rows, const Linearity& lin,
                    const std::vector<Target>& targets);

}  // namespace rrc_bench
