// rrc_exr_io: a small OpenEXR frame reader and writer for the host_sample
// tools and the tests (golden images).  Only standard C++ types appear here;
// OpenEXR stays an implementation detail.
//
// Images are row-major, row 0 at the top (OpenEXR's and rrc's order), one
// plain array of width*height values per channel.  Every function reports a
// failure by throwing rrc_exr::ExrError, a std::runtime_error whose message
// starts with the file name ("frames/f_0003.exr: missing channel 'Z'").
#ifndef RRC_HOST_SAMPLE_EXR_IO_H
#define RRC_HOST_SAMPLE_EXR_IO_H

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrc_exr {

/** Thrown by every function of this library; what() names the file. */
class ExrError : public std::runtime_error {
public:
    ExrError(const std::string& path, const std::string& message);
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

/** A flat (non-deep) image: channel name -> width*height values. */
struct ExrImage {
    int width = 0;
    int height = 0;
    /** HALF and FLOAT channels of the file, as float.  Written as FLOAT. */
    std::map<std::string, std::vector<float>> channels;
    /** UINT channels of the file, exactly.  Written as UINT. */
    std::map<std::string, std::vector<uint32_t>> uint_channels;
    /** String-valued header attributes (read from the first part; written
     *  as they are).  The structural ones "name" and "type" are not read. */
    std::map<std::string, std::string> attributes;

    /** True if a float or a UINT channel has this name. */
    bool has(const std::string& name) const;
    /** The float channel of that name, or nullptr. */
    const std::vector<float>* find(const std::string& name) const;
    /** A channel as float whatever its type (UINT converted); throws
     *  ExrError (path as given) naming the channel if it is missing. */
    std::vector<float> as_float(const std::string& name, const std::string& path = "") const;
    /** width*height; 0 for an empty image. */
    std::size_t pixel_count() const;
};

enum class PixelType { Uint, Half, Float };

struct ExrChannelInfo {
    std::string name;
    PixelType type = PixelType::Float;
    int part = 0; /* index of the part holding the channel */
};

/** What the header says, without decoding pixels. */
struct ExrInfo {
    int width = 0; /* of the data window */
    int height = 0;
    int parts = 0;
    std::vector<ExrChannelInfo> channels; /* sorted by name */
    bool has(const std::string& name) const;
};

/** Read every channel of a single-part or multi-part scanline or tiled file
 *  (all parts must share one data window; deep parts and subsampled
 *  channels are refused).  The file is read into memory once and checked
 *  with OpenEXR's Imf::checkOpenEXRFile before anything is decoded, so a
 *  truncated or corrupt file gives an ExrError, not a crash.  The image is
 *  the data window; its origin is dropped. */
ExrImage read_exr(const std::string& path);

/** The header only (data window, parts, channel names and types), read with
 *  the OpenEXR Core library, which validates headers and is safe on
 *  malformed input.  Cheap: used to check a whole sequence up front. */
ExrInfo read_exr_info(const std::string& path);

/** Checks, without decoding pixels, that every pixel block (chunk) the
 *  header promises is in the file: the offset table and each block's
 *  leader are read with the OpenEXR Core library and every block must end
 *  within the file.  Catches truncated files up front (a whole sequence
 *  can be checked before any output is written); corrupt compressed data
 *  inside a block is only found by read_exr().  Throws ExrError. */
void verify_exr_chunks(const std::string& path);

/** The sorted channel names of a file (header only) or of an image. */
std::vector<std::string> channel_names(const std::string& path);
std::vector<std::string> channel_names(const ExrImage& image);

enum class Compression { None, Zip, Zips, Piz, Rle };

struct WriteOptions {
    Compression compression = Compression::Zip; /* lossless */
    /** Float channels written as HALF (rounded to nearest); the others are
     *  FLOAT.  Names not in the image are ignored. */
    std::vector<std::string> half_channels;
    /** false: one part (as Blender writes multilayer files).  true: one part
     *  per layer (the channel name up to its last '.', "" for plain names),
     *  each part named after its layer, as compositors often write. */
    bool multipart_by_layer = false;
};

/** Write a scanline file (data window = display window = [0,w-1]x[0,h-1]),
 *  single-part unless options.multipart_by_layer.  Every channel must hold width*height values and no
 *  name may be both a float and a UINT channel.  The file is written under a
 *  temporary name in the same directory and renamed over `path` only once
 *  complete, so a failure never leaves a partial file (an existing `path`
 *  is kept on failure and replaced on success). */
void write_exr(const std::string& path, const ExrImage& image, const WriteOptions& options = {});

/** OpenEXR's global worker-thread count for (de)compression: 0 = none
 *  (OpenEXR's default), n > 0 = n threads.  A process-wide setting. */
void set_thread_count(int threads);

}  // namespace rrc_exr

#endif
