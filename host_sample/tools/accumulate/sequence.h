// rrc-accumulate: from EXR frames and the camera file to rrc descriptors.
#ifndef RRC_ACCUMULATE_SEQUENCE_H
#define RRC_ACCUMULATE_SEQUENCE_H

#include "options.h"

#include <exr_io.h>
#include <rrc/rrc.h>

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrc_cli {

/** Every failure of the tool that is not a bad command line. */
class CliError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** One accumulated layer as found in the first frame. */
struct SignalLayout {
    SignalOptions options;               /* options.layer is the layer name */
    std::vector<std::string> components; /* channel suffixes in the file: {"Y"}, {"R","G","B"}, ... */
    uint32_t rrc_components = 1;         /* 1 or 4 (RGB is padded with A = 1) */
    bool confidence = false;             /* <layer>.conf present */
};

/** The channels the geometry is read from (defaults, preset or options). */
struct ChannelMap {
    std::string depth = "Z";
    std::vector<std::string> motion;   /* 2 (MOTION) or 3 (MOTION_DEPTH) names; empty otherwise */
    std::vector<std::string> prevclip; /* 4 names for PREV_CLIP; empty otherwise */
    std::string nocache = "nocache.Y";
    std::string view_layer; /* --preset blender: the view layer read ("ViewLayer") */
    std::string object_id;  /* the object id channel; empty: the run has no object ids */
};

/** What the first frame and the options make of the sequence. */
struct SequenceLayout {
    int width = 0, height = 0;
    rrc_reprojection reprojection = RRC_REPROJECTION_PREV_CLIP;
    bool nocache = false; /* the nocache channel is present */
    ChannelMap channels;
    std::vector<SignalLayout> signals;
    /* Whether and why the run has object ids, for the progress output:
     * "object ids from 'ViewLayer.IndexOB.X'", "no object ids (...)";
     * empty when neither --object-id nor the preset asked for them. */
    std::string object_id_report;
};

/** "a, b, c" (at most 40 names, then "... (N in all)"); "none" if empty. */
std::string list_channels(const rrc_exr::ExrInfo& info);

/** A channel every frame must have, and why (for the error message). */
struct RequiredChannel {
    std::string name;
    std::string reason;
};

/** Decides the layout from the first frame's header: the channel names
 *  (defaults, --preset blender's with its view layer, or the channel
 *  options), the reprojection (motion becomes MOTION_DEPTH when mv.Z exists
 *  or three motion channels are named), the signals (from --signal, the
 *  preset's Combined, or every layer not used by the geometry), their
 *  components and confidence, the nocache mask and the object ids
 *  (--object-id, or the preset's <view layer>.IndexOB.X if the first frame
 *  has it; never with --no-object-id).  Throws CliError naming
 *  the file and channel and listing the channels the file has. */
SequenceLayout discover_layout(const rrc_exr::ExrInfo& first, const std::string& first_path, const Options& options);

/** The channels the layout reads from every frame. */
std::vector<RequiredChannel> required_channels(const SequenceLayout& layout);

/** Throws CliError if the frame's size differs from the layout's or a
 *  required channel is missing (the message lists the file's channels). */
void check_frame_header(const rrc_exr::ExrInfo& info, const std::string& path, const SequenceLayout& layout);

/** One frame's entry in the camera file. */
struct CameraFrame {
    bool has_view_proj = false;
    std::array<double, 16> view_proj{}; /* column-major (GLM), Vulkan clip */
    std::array<float, 2> jitter{};      /* pixels, x right, y down; 0 if absent */
};

/** Reads the camera JSON: an object mapping frame numbers ("12") to
 *  {"view_proj": [16 numbers], "jitter": [x, y]}.  With need_view_proj
 *  every frame in [first, last] must have a view_proj.  Throws CliError. */
std::map<int64_t, CameraFrame> load_camera_file(const std::string& path, int64_t first, int64_t last, bool need_view_proj);

/** The arrays of one frame in rrc's layout (interleaved components). */
struct FrameData {
    std::vector<float> depth;
    std::vector<float> reprojection;            /* 4, 3 or 2 floats a pixel; empty for CAMERA */
    std::vector<std::vector<float>> samples;    /* per signal */
    std::vector<std::vector<float>> confidence; /* per signal; empty without */
    std::vector<uint8_t> nocache;               /* empty without */
    std::vector<uint32_t> object_id;            /* empty without */
};

/** A channel of object ids as rrc takes them.  A UINT channel is taken
 *  exactly; a float one (Blender writes IndexOB as float) is rounded to the
 *  nearest integer, and a negative, non-finite or larger than UINT32_MAX
 *  value throws CliError naming the file, the channel and the pixel. */
std::vector<uint32_t> object_ids_of(const rrc_exr::ExrImage& image, const std::string& channel, const std::string& path);

/** Converts a decoded frame (already checked by check_frame_header). */
FrameData load_frame(const rrc_exr::ExrImage& image, const std::string& path, const SequenceLayout& layout);

/** rrc's context descriptor; `channels` receives the channel descriptors the
 *  result points to (keep it alive).  Throws CliError for combinations the
 *  tool can explain better than the library. */
rrc_context_desc make_context_desc(const Options& options, const SequenceLayout& layout, std::vector<rrc_channel_desc>& channels);

/** The output image of one frame from rrc's outputs. */
struct FrameResult {
    std::vector<std::vector<float>> values; /* per signal, w*h*rrc_components */
    std::vector<std::vector<uint16_t>> age; /* per signal */
    std::vector<std::vector<float>> weight; /* per signal; filled for confidence layers */
    std::vector<uint8_t> mask;
};
rrc_exr::ExrImage make_output_image(const SequenceLayout& layout, const FrameResult& result);

/** The coherence map of a mask: green hit, red miss, blue refreshed, dark
 *  grey (64) background, magenta invalid geometry; 8-bit RGB, row 0 on top. */
std::vector<uint8_t> coherence_rgb(const std::vector<uint8_t>& mask);

/** The channels of a signal that metrics compare (its components but A). */
std::vector<std::string> metric_channels(const SignalLayout& signal);

}  // namespace rrc_cli

#endif
