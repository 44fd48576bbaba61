// Determinism (docs/measurements/STABILITY.md, "Fast cases", rows "determinism"): bit-identical outputs
//  - across repeated runs in one process;
//  - with lavapipe on 1 and on 2 threads: LP_NUM_THREADS is read when the
//    driver starts, so this test runs itself as a child process per thread
//    count (RRC_DETERMINISM_DIGEST_OUT tells the child where to write its
//    digest) and compares the digests with its own;
//  - with two contexts driven from two threads at once, against the same two
//    runs one after the other.
// The digest is FNV-1a over every output of every frame: values' bits, ages,
// weights and masks, of a moving jittered scene through three channels.
#include "stability_report.h"
#include "stability_util.h"
#include "support/scene_frames.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

extern char** environ;

using namespace rrc_stab;
using rrc_test::channel;

namespace {

struct Digest {
    uint64_t h = 1469598103934665603ull;
    void add(const void* data, size_t bytes) {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    template <typename T>
    void add(const std::vector<T>& v) {
        add(v.data(), v.size() * sizeof(T));
    }
};

// 12 frames of a moving, jittered scene (seed varies the noise) through an
// fp32 bilinear, an fp16 Catmull-Rom and an fp32 confidence channel.
uint64_t scenario_digest(uint64_t seed) {
    rrc_scene::SceneConfig sc = rrc_test::scene_config(48, 32, RRC_DEPTH_MODE_REVERSED);
    sc.jitter = true;
    sc.seed = seed;
    sc.invalid_fraction = 0.01;
    rrc_scene::Scene scene(sc);
    std::vector<rrc_channel_desc> channels = {
        channel("pcf", 1, 0.6f),
        channel("env", 4, 0.8f, RRC_HISTORY_FP16, RRC_BLEND_AGE_AWARE, RRC_HISTORY_FILTER_CATMULL_ROM),
        channel("soft", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_RUNNING_MEAN, RRC_HISTORY_FILTER_BILINEAR, 32, 1),
    };
    rrc_test::Context ctx(rrc_test::scene_context_desc(sc, RRC_REPROJECTION_PREV_CLIP, channels));
    if (!ctx) return 0;
    Digest digest;
    for (int t = 0; t < 12; ++t) {
        rrc_test::SceneFrameInputs in;
        in.frame = scene.render(t);
        rrc_test::make_frame_inputs(in, RRC_REPROJECTION_PREV_CLIP, channels);
        rrc_test::FrameResult r = ctx.run(in.desc);
        digest.add(r.mask);
        for (size_t c = 0; c < channels.size(); ++c) {
            digest.add(r.values[c]);
            digest.add(r.age[c]);
            digest.add(r.weight[c]);
        }
    }
    return digest.h;
}

// Runs this test program again, filtered to `test`, with extra environment;
// returns the digest the child wrote, or 0.
uint64_t child_digest(const std::string& test, const std::vector<std::string>& extra_env) {
    char path[] = "/tmp/rrc_determinism_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return 0;
    close(fd);
    std::vector<std::string> env_strings = extra_env;
    env_strings.push_back(std::string("RRC_DETERMINISM_DIGEST_OUT=") + path);
    for (char** e = environ; *e; ++e) {
        std::string s = *e;
        bool overridden = false;
        for (const std::string& x : extra_env) overridden |= s.compare(0, s.find('=') + 1, x.substr(0, x.find('=') + 1)) == 0;
        if (!overridden) env_strings.push_back(s);
    }
    std::vector<char*> envp;
    for (std::string& s : env_strings) envp.push_back(&s[0]);
    envp.push_back(nullptr);
    std::string filter = "--gtest_filter=" + test;
    char exe[] = "/proc/self/exe";
    char* argv[] = {exe, &filter[0], nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);  // the child's gtest chatter
    pid_t pid = 0;
    int rc = posix_spawn(&pid, exe, &actions, nullptr, argv, envp.data());
    posix_spawn_file_actions_destroy(&actions);
    uint64_t digest = 0;
    if (rc == 0) {
        int status = 0;
        waitpid(pid, &status, 0);
        std::ifstream in(path);
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0) in >> digest;
    }
    std::remove(path);
    return digest;
}

TEST(Determinism, RepeatedRunsAreBitIdentical) {
    const uint64_t a = scenario_digest(1), b = scenario_digest(1), other = scenario_digest(2);
    EXPECT_NE(a, 0u);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, other) << "the digest should depend on the inputs";
}

TEST(Determinism, LavapipeOnOneAndTwoThreadsIsBitIdentical) {
    if (const char* out = std::getenv("RRC_DETERMINISM_DIGEST_OUT")) {  // the child: write and stop
        std::ofstream(out) << scenario_digest(1);
        return;
    }
    const std::string self = "Determinism.LavapipeOnOneAndTwoThreadsIsBitIdentical";
    const uint64_t here = scenario_digest(1);
    const uint64_t one = child_digest(self, {"LP_NUM_THREADS=1"}), two = child_digest(self, {"LP_NUM_THREADS=2"});
    EXPECT_NE(one, 0u) << "the child with LP_NUM_THREADS=1 failed";
    EXPECT_NE(two, 0u) << "the child with LP_NUM_THREADS=2 failed";
    EXPECT_EQ(one, two);
    EXPECT_EQ(one, here);
    report("determinism", "LP_NUM_THREADS=1 vs 2 (child processes) vs this process; repeated runs", "bit-identical digests",
           format("%016llx / %016llx / %016llx", (unsigned long long)one, (unsigned long long)two, (unsigned long long)here));
}

TEST(Determinism, TwoContextsOnTwoThreadsMatchSequentialRuns) {
    const uint64_t a = scenario_digest(1), b = scenario_digest(2);
    for (int round = 0; round < 2; ++round) {
        uint64_t ta = 0, tb = 0;
        std::thread first([&] { ta = scenario_digest(1); });
        std::thread second([&] { tb = scenario_digest(2); });
        first.join();
        second.join();
        EXPECT_EQ(ta, a) << "round " << round;
        EXPECT_EQ(tb, b) << "round " << round;
    }
    report("determinism", "two contexts on two threads at once (twice) vs one after the other", "bit-identical digests",
           format("%016llx, %016llx", (unsigned long long)a, (unsigned long long)b));
}

}  // namespace
