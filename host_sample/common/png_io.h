// rrc_png_io: 8-bit RGB PNG files through OpenImageIO, for the host_sample
// tools' pictures (rrc-accumulate's coherence maps) and the tests that read
// them back.  Only standard C++ types appear here.
#ifndef RRC_HOST_SAMPLE_PNG_IO_H
#define RRC_HOST_SAMPLE_PNG_IO_H

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrc_png {

/** Thrown by every function here; what() starts with the file name. */
class PngError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** An 8-bit RGB image, row-major, row 0 at the top, 3 bytes a pixel. */
struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb;
};

/** Writes a PNG under a temporary name in the same directory and renames it
 *  over `path` only once complete: a failure never leaves a partial file. */
void write_png(const std::string& path, const RgbImage& image);

/** Reads any image OpenImageIO reads as 8-bit RGB (tests). */
RgbImage read_png(const std::string& path);

}  // namespace rrc_png

#endif
