// rrc-sample-peers: rrc-sample (the same options, the same run) with the
// peers' validity tests (tests/reference/peer_tests.h) run on the CPU on each
// frame's read-back G-buffer and scored by the sample's ray-cast oracle
// beside rrc's own mask.  It appends a "Peer validity tests" table to
// OUT/summary.md.  It lives with the tests, not in host_sample/: rrc-sample
// and every host program use only the public headers of include/, and the
// peer tests are the test suite's double-precision reference
// (host_sample/testbed/README.md, "The peers' validity tests").
#include "options.h"
#include "oracle.h"
#include "sample_peer_frames.h"
#include "sample_run.h"
#include "scene.h"
#include "summary.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

using namespace rrc_sample;

namespace {

constexpr int kRows = 1 + 5;  // rrc's own mask, then the peers in kAllPeerTests' order

const char* row_label(int r) {
    static const char* const kLabels[kRows] = {"rrc (this run's depth test)", "NRD ReBLUR", "NRD ReLAX", "SVGF", "FSR2", "relative 1 %"};
    return kLabels[r];
}

std::string table(const Options& o, const PeerScore* s, int frames) {
    std::string t = "\n## Peer validity tests (rrc-sample-peers)\n\n";
    char line[512];
    std::snprintf(line, sizeof line,
                  "Frames 1 .. %d at %ux%u (frame 0 has no previous frame), depth test %s. Recall = hits among visible pixels whose\n"
                  "bilinear taps lie on their object; false hits = hits on pixels whose point was not visible; mixing = those false\n"
                  "hits whose fetched history takes weight > 1e-3 from a texel that held another object or the sky.\n\n",
                  frames - 1, o.width, o.height, depth_test_description(o).c_str());
    t += line;
    t += "| test | recall | hits / visible | false hits (of not visible) | mixing |\n|---|---|---|---|---|\n";
    for (int r = 0; r < kRows; ++r) {
        std::snprintf(line, sizeof line, "| %s | %.2f%% | %llu / %llu | %llu (of %llu) | %llu |\n", row_label(r), 100.0 * s[r].recall(),
                      (unsigned long long)s[r].clean_hits, (unsigned long long)s[r].clean_visible, (unsigned long long)s[r].false_hits,
                      (unsigned long long)s[r].not_visible, (unsigned long long)s[r].mixing);
        t += line;
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    const int code = rrc_host::parse_command_line("rrc-sample-peers", [&] { return parse_options(argc, argv); }, usage(), o, true);
    if (code >= 0) return code;
    try {
        // The same scene and frame states run_sample draws (sample_run.cpp).
        Scene scene = Scene::make(o.scene);
        if (o.static_camera) scene.camera_speed = 0.0f;
        scene.light_speed = o.light_speed;
        RenderSettings rs;
        rs.width = o.width, rs.height = o.height, rs.taps = o.taps, rs.fps = o.fps;
        rs.sun_map = o.sun_map, rs.lamp_map = o.lamp_map, rs.pcf_radius = o.pcf_radius, rs.seed = o.seed, rs.pcf_pattern = o.pcf_pattern;
        const VisibilityOracle oracle(scene);
        PeerScore scores[kRows];
        rrc_ref::peers::GBuffer prev_g;
        std::vector<uint16_t> prev_object;
        glm::dvec3 prev_eye(0.0);
        int frames = 0;
        rrc_ref::peers::Options peer_options;
        peer_options.inverted_depth = true;  // rrc-sample's depth is reversed-z
        auto on_frame = [&](const FrameOutput& out, const FrameRecord&) {
            const FrameState fs = make_frame_state(scene, rs, out.index);
            const double tan_half = std::tan(0.5 * scene.camera(out.index / (double)rs.fps).fov_y);
            rrc_ref::peers::GBuffer g = peer_gbuffer(out, fs.view_proj, tan_half, scene.near_plane, scene.far_plane);
            if (out.index > 0 && !prev_object.empty()) {
                OracleView cur, prev;
                oracle_views(fs, cur, prev);
                std::vector<uint8_t> verdict;
                oracle.judge(cur, prev, o.width, o.height, out.mask, prev_object, &verdict);
                const rrc_ref::peers::Reprojection r = peer_reprojection(out, fs.view_proj, fs.prev_view_proj, prev_eye);
                score_peer(scores[0], rrc_decisions(out.mask, r, out.width, out.height), verdict, out.object, prev_object);
                for (int k = 0; k < 5; ++k)
                    score_peer(scores[1 + k], rrc_ref::peers::run_peer_test(rrc_ref::peers::kAllPeerTests[k], g, r, prev_g, peer_options),
                               verdict, out.object, prev_object);
            }
            prev_g = std::move(g);
            prev_object = out.object;
            prev_eye = glm::dvec3(out.eye);
            ++frames;
        };
        RunResult run = run_sample(o, &std::cout, on_frame);
        print_summary(run, std::cout);
        const std::string t = table(o, scores, frames);
        std::cout << t;
        std::ofstream((std::filesystem::path(o.out) / "summary.md").string(), std::ios::app) << t;
        if (o.validation && run.validation_messages) {
            std::cerr << "rrc-sample-peers: " << run.validation_messages << " validation message(s)\n";
            return 1;
        }
    } catch (const std::exception& e) {
        std::cerr << "rrc-sample-peers: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
