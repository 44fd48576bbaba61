// A whole run of rrc-sample: device, scene, renderer, the frame loop with
// references on checkpoint frames, the files, the summary.  main() and the
// validation test call it.
#pragma once

#include "finish.h"
#include "metrics.h"
#include "options.h"
#include "oracle.h"
#include "renderer.h"

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace rrc_sample {

struct FrameRecord {
    int index = 0;
    bool checkpoint = false;
    HitStats hits;
    VisibilityStats visibility;  // recall and false hits against the oracle of true visibility (oracle.h)
    FrameTimings timings;
    std::vector<SignalErrors> errors;  // checkpoints only
    FinishErrors finish;               // checkpoints: pcf's remapped display, confidence's targets (finish.h)
};

struct RunResult {
    Options options;
    uint32_t signals = 0;  // what ran: the scene's signals, narrowed by --signals
    std::string device;
    uint64_t rrc_memory_bytes = 0;
    std::vector<std::string> channels;  // one line per rrc channel
    std::vector<FrameRecord> frames;
    double wall_seconds = 0.0;          // the frame loop, files included
    double oracle_seconds = 0.0;        // the visibility oracle's ray casts (overlapping the files)
    uint64_t validation_messages = 0;   // counted through device and instance destruction
    std::vector<std::string> messages;  // the first few
    std::string finish_table;           // the young soft pixels' errors (finish.h), empty without them
};

/** Runs the sample.  progress: per-frame lines (nullptr or --quiet: none).
 *  on_frame: called with every frame's images (tests).  Throws std::runtime_error. */
RunResult run_sample(const Options& options, std::ostream* progress,
                     const std::function<void(const FrameOutput&, const FrameRecord&)>& on_frame = {});

/** Checkpoint frames: t % K == K - 1, and the last frame (K = reference_every > 0). */
bool is_checkpoint(const Options& options, int frame);

}  // namespace rrc_sample
