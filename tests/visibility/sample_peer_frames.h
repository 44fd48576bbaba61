// rrc-sample-peers (sample_peers_main.cpp): the peers' validity tests
// (tests/reference/peer_tests.h) on rrc-sample's read-back G-buffers, scored
// by its ray-cast oracle (oracle.h).  docs/measurements/COMPARISON.md, "rrc-sample".
#pragma once

#include "oracle.h"
#include "peer_tests.h"
#include "renderer.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rrc_sample {

/** A frame's guide buffers from its read-back images: view depth = clip w of the G-buffer
 *  position under `view_proj`; the device depth its fp32 reversed-z value linearised with the
 *  scene's planes; the G-buffer's world normals; SVGF's derivatives as forward (else backward)
 *  differences of depth and normal to a neighbour on the same object (0 where none). */
rrc_ref::peers::GBuffer peer_gbuffer(const FrameOutput& out, const glm::dmat4& view_proj, double tan_half_fovy, double near_plane,
                                     double far_plane);

/** The frame's reprojection from its G-buffer prev_clip (no jitter in rrc-sample); NRD's
 *  parallax from the previous world position against the previous eye. */
rrc_ref::peers::Reprojection peer_reprojection(const FrameOutput& out, const glm::dmat4& view_proj, const glm::dmat4& prev_view_proj,
                                               const glm::dvec3& prev_eye);

/** One test's counts over a run, in the oracle's terms (VisibilityStats). */
struct PeerScore {
    uint64_t clean_visible = 0, clean_hits = 0, surface = 0, not_visible = 0, false_hits = 0, mixing = 0;
    double recall() const { return clean_visible ? (double)clean_hits / (double)clean_visible : 0.0; }
};

/** Adds one frame: `verdict` is the oracle's (VisibilityOracle::judge) for the frame; `prev_object`
 *  the previous frame's G-buffer ids; `object` this frame's. */
void score_peer(PeerScore& s, const std::vector<rrc_ref::peers::Decision>& decisions, const std::vector<uint8_t>& verdict,
                const std::vector<uint16_t>& object, const std::vector<uint16_t>& prev_object);

/** rrc's own mask as Decisions: hits with the bilinear taps at the reprojected position. */
std::vector<rrc_ref::peers::Decision> rrc_decisions(const std::vector<uint8_t>& mask, const rrc_ref::peers::Reprojection& r, int width,
                                                    int height);

}  // namespace rrc_sample
