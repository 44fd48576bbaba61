// Non-finite samples over 10,000 frames (label `long`; docs/measurements/STABILITY.md, "Long cases").
#include "nonfinite_run.h"

TEST(NonFiniteSamples, TenThousandFrames) { rrc_stab::run_nonfinite_samples(10000); }
