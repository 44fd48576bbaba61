// Non-finite samples, 300 frames (the sanitizer build runs this one; the
// 10,000-frame run is nonfinite_long_test.cpp).
#include "nonfinite_run.h"

TEST(NonFiniteSamples, ThreeHundredFrames) { rrc_stab::run_nonfinite_samples(300); }
