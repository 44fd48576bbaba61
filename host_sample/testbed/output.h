// Files of a run: composed frames, coherence maps and age heat maps as PNG,
// each signal's images as EXR.
#pragma once

#include "oracle.h"
#include "renderer.h"

#include <string>

namespace rrc_sample {

class OutputWriter {
public:
    /** Creates out_dir/{frames,coherence,age,exr}. */
    OutputWriter(const std::string& out_dir, uint32_t width, uint32_t height);
    void write(const FrameOutput& frame) const;
    /** oracle/oracle_NNNN.png from VisibilityOracle::judge's verdicts (oracle_map's colours). */
    void write_oracle(int index, const std::vector<uint8_t>& verdict) const;
    const std::string& dir() const { return dir_; }

private:
    std::string dir_;
    uint32_t width_, height_;
};

/** The paper's Figure 1 colours: green hit, red miss, blue refreshed, black background; RGB8. */
std::vector<uint8_t> coherence_map(const std::vector<uint8_t>& mask);
/** The oracle's verdicts: black background; visible and clean: green hit, yellow miss (recall's loss);
 *  not visible: red hit (a false hit), blue miss; straddling: light grey hit, dark grey miss; magenta excluded. */
std::vector<uint8_t> oracle_map(const std::vector<uint8_t>& verdict);
/** Age 0 black, then dark red -> yellow -> white at `full` and above; RGB8. */
std::vector<uint8_t> age_heat_map(const std::vector<uint16_t>& age, uint32_t full);

}  // namespace rrc_sample
