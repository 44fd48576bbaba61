// Non-finite samples, the 10,000 frames (label `long`).
#include "nonfinite_run.h"

TEST(NonFiniteSamples, TenThousandFrames) { rrc_stab::run_nonfinite_samples(10000); }
