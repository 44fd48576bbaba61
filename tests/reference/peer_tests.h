// The reprojection validity tests of the peers our users already run, in
// double precision, for docs/measurements/COMPARISON.md only: none of them is an option of
// the library.  Each is rebuilt from its public source with its shipped
// defaults (peer_tests.cpp cites file and commit beside every formula and
// states each simplification).
//
// Every test receives the same exact reprojection (Reprojection: the previous
// texel coordinate q = uv_prev * size - prev_jitter of docs/CONVENTIONS.md,
// "Coordinates and jitter"), so the comparison isolates the validity test
// itself: the peers' own motion-vector and jitter conventions are not
// modelled.  Each returns, per pixel, whether it keeps history (a "hit") and
// the taps and normalised weights it fetches that history with, so a caller
// can tell whether a hit mixes another surface's history into the result.
#ifndef RRC_REFERENCE_PEER_TESTS_H
#define RRC_REFERENCE_PEER_TESTS_H

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace rrc_ref {
namespace peers {

enum class PeerTest {
    NRD_REBLUR,   // NRD ReBLUR TemporalAccumulation: plane-distance gate, disocclusionThreshold 0.01
    NRD_RELAX,    // NRD ReLAX TemporalAccumulation: the same gate, its own N.V ramp and tap rule
    SVGF,         // Falcor SVGFReproject: |dZ|/(fwidth Z + 0.01) <= 10, |dN|/(fwidth N + 0.01) <= 16, 3x3 fallback
    FSR2,         // FSR2 depth clip against the reconstructed (scattered) previous depth
    RELATIVE_1PC  // |d_prev_fetched - d_expected| <= 0.01 d_expected on linear depth (tutorials)
};
constexpr PeerTest kAllPeerTests[] = {PeerTest::NRD_REBLUR, PeerTest::NRD_RELAX, PeerTest::SVGF, PeerTest::FSR2, PeerTest::RELATIVE_1PC};

// Short name for tables and file names.
const char* peer_name(PeerTest t);

// One frame's guide buffers as the peers' APIs take them.  Row-major W*H,
// row 0 at the top; texel k's centre at k + 0.5.
struct GBuffer {
    int width = 0, height = 0;
    double tan_half_fovy = 0.0;  // the projection's tan(fovy / 2) (square pixels)
    // Planar view depth d as the renderer writes its linear-depth guide
    // (NRD IN_VIEWZ, Falcor's linear Z); +inf on the background.
    std::vector<double> view_z;
    // The depth buffer as stored (format and mode of the case), linearised
    // exactly (FSR2's ConvertFromDeviceDepthToViewSpace; the 1 % test);
    // whatever the stored background value linearises to on the background.
    std::vector<double> device_z;
    std::vector<glm::dvec3> normal;  // world-space unit normal; 0 on the background
    std::vector<double> z_fwidth;    // SVGF: max(|ddx d|, |ddy d|) of the pixel's own surface
    std::vector<double> n_fwidth;    // SVGF: length(fwidth(N)) of the pixel's own surface
    std::vector<uint8_t> background;  // 1 where the pixel shows no surface

    size_t size() const { return static_cast<size_t>(width) * height; }
};

// Each current pixel's reprojection into the previous frame.
struct Reprojection {
    std::vector<double> qx, qy;       // previous texel coordinate; NaN where w_prev <= 0
    std::vector<uint8_t> on_screen;   // w_prev > 0 and uv_prev in [0, 1]^2
    std::vector<double> prev_view_z;  // the point's planar depth in the previous frame (Xvprev.z)
    std::vector<glm::dvec3> view_dir;  // unit vector from the point to the current camera, world space
    std::vector<double> parallax_px;   // NRD's ComputeParallaxInPixels for the point
};

// The history a test fetches for one pixel: texel indices and normalised weights.
struct Tap {
    size_t texel;
    double weight;
};
struct Decision {
    bool hit = false;  // the test keeps (some) history
    int taps = 0;
    Tap tap[9] = {};  // up to 9: SVGF's 3x3 fallback
};

struct Options {
    // depth_mode REVERSED: FSR2 built with FFX_FSR2_OPTION_INVERTED_DEPTH (its Ksep depends on it).
    bool inverted_depth = false;
};

// Runs one test over a frame.  `cur` and `prev` have the same extent; `r` is cur's.
std::vector<Decision> run_peer_test(PeerTest test, const GBuffer& cur, const Reprojection& r, const GBuffer& prev,
                                    const Options& options = {});

// The per-pixel thresholds, exposed for the self-test.
// NRD's frustum size at view depth z: min(W, H) * unproject * z, unproject = 2 tan(fovy/2) / H.
double nrd_frustum_size(int width, int height, double tan_half_fovy, double view_z);
// ReBLUR's plane-distance threshold: 0.01 frustum / lerp(0.05 + 0.95 N.V, 1, saturate(parallax / 30)).
double reblur_threshold(double frustum_size, double n_dot_v, double parallax_px);
// ReLAX's: 0.01 frustum / lerp(N.V, 1, saturate(parallax / 30)).
double relax_threshold(double frustum_size, double n_dot_v, double parallax_px);
// FSR2's per-tap depth clip term (before the bilinear weight), in [0, 4].
double fsr2_sample_depth_clip(double current_view_z, double prev_view_z, double tan_half_fovy, int width, bool inverted_depth);

}  // namespace peers
}  // namespace rrc_ref

#endif
