// The oracle of true visibility (README.md, "Recall and false hits"): ray casts in double precision
// against the sample's own triangle meshes, at the model transforms the
// renderer used, decide for every pixel whether the surface point it shows
// was visible in the previous frame -- the ground truth rrc's hit test is
// judged against (recall and false hits, host_sample/testbed/README.md).
#pragma once

#include "frame_state.h"
#include "scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace rrc_sample {

/** One frame's geometry as the renderer drew it: camera and model matrices. */
struct OracleView {
    glm::dmat4 view_proj{1.0};
    std::vector<glm::dmat4> model;  // per scene object
};
/** This frame's view and the previous frame's (the renderer's prev_* matrices). */
void oracle_views(const FrameState& state, OracleView& current, OracleView& previous);

/** Per frame (or summed over a run).  Pixels are counted where the current
 *  frame's ray meets an object ("surface"); a pixel whose ray and G-buffer
 *  disagree on background (sub-pixel rasterisation at silhouettes) is
 *  "excluded" and nowhere else. */
struct VisibilityStats {
    uint64_t surface = 0;                // pixels whose ray meets an object (and the G-buffer is not background)
    uint64_t visible = 0;                // of them: the point was visible in the previous frame
    uint64_t straddling = 0;             // of them: a previous-depth tap (weight > 1e-3) lies on another object or the background
    uint64_t clean_visible = 0;          // visible and not straddling: recall's denominator
    uint64_t clean_hits = 0;             // rrc hits among clean_visible: recall's numerator
    uint64_t hits = 0;                   // rrc hits among surface pixels
    uint64_t false_hits = 0;             // hits whose point was not visible (straddling or not)
    uint64_t false_hits_straddling = 0;  // the false hits that straddle a silhouette
    uint64_t excluded = 0, excluded_hits = 0;
    // Recall's misses (clean_visible - clean_hits) by the Material of the pixel's object:
    // which surfaces the depth test rejects although they were visible.
    uint64_t missed_by_material[kMaterialCount] = {};
    double recall() const { return clean_visible ? (double)clean_hits / (double)clean_visible : 0.0; }
    VisibilityStats& operator+=(const VisibilityStats& o);
};

/** Per-pixel verdict bits (VisibilityOracle::judge's optional image). */
enum Verdict : uint8_t { kVerdictSurface = 1, kVerdictVisible = 2, kVerdictStraddling = 4, kVerdictHit = 8, kVerdictExcluded = 16 };

/** Bounding volume hierarchies of the scene's meshes (object space, built once). */
class VisibilityOracle {
public:
    explicit VisibilityOracle(const Scene& scene);
    ~VisibilityOracle();
    VisibilityOracle(const VisibilityOracle&) = delete;
    VisibilityOracle& operator=(const VisibilityOracle&) = delete;

    struct Hit {
        int object = -1;  // -1: nothing
        double t = 0.0;   // origin + t * direction
    };
    /** The first object the ray meets at t > 0 under `view`'s model matrices. */
    Hit cast(const OracleView& view, const glm::dvec3& origin, const glm::dvec3& direction) const;

    /** A G-buffer's object ids from ray casts through the pixel centres (0 background, object + 1). */
    std::vector<uint16_t> object_ids(const OracleView& view, uint32_t width, uint32_t height) const;

    /** Judges one frame.  mask: rrc's bits this frame; prev_object: the previous
     *  frame's G-buffer object ids (0 background, object + 1), empty when there
     *  is no previous frame (first frame, reset): then nothing was visible.
     *  verdict (optional): width*height Verdict bits, to see where the test errs.
     *  Threads: all cores (std::thread). */
    VisibilityStats judge(const OracleView& current, const OracleView& previous, uint32_t width, uint32_t height,
                          const std::vector<uint8_t>& mask, const std::vector<uint16_t>& prev_object,
                          std::vector<uint8_t>* verdict = nullptr) const;

private:
    struct MeshBvh;
    struct Prepared;
    Prepared prepare(const OracleView& view) const;
    Hit cast_prepared(const Prepared& prepared, const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const;
    std::vector<std::unique_ptr<MeshBvh>> meshes_;
    std::vector<uint32_t> object_mesh_, object_material_;
};

}  // namespace rrc_sample
