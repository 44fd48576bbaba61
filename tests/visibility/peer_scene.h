// The peers' guide buffers (rrc_ref::peers::GBuffer, Reprojection) made from
// an analytic scene's frames: exact normals from the objects' shapes, the
// depth derivatives SVGF's G-buffer writes computed on each pixel's own
// tangent plane (as a rasteriser's quad derivatives of one triangle), and the
// reprojection from the frame's fp32 prev_clip (the input rrc's PREV_CLIP
// test reads).  docs/measurements/COMPARISON.md, "How the peers were rebuilt".
#pragma once

#include "peer_tests.h"
#include "scenes/scene.h"

namespace rrc_peer {

// The guide buffers of a rendered frame (scene.render(frame.index)).
rrc_ref::peers::GBuffer make_gbuffer(const rrc_scene::Scene& scene, const rrc_scene::Frame& frame);

// Each pixel of `frame` reprojected into its previous frame (frame.prev_index).
rrc_ref::peers::Reprojection make_reprojection(const rrc_scene::Scene& scene, const rrc_scene::Frame& frame);

// The world-space unit normal of an object's surface at object-space point p.
glm::dvec3 object_normal(const rrc_scene::ObjectShape& shape, const glm::dvec3& p);

}  // namespace rrc_peer
