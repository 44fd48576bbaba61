/* The signal passes' modes, written once for the sample's C++ (options.cpp, signals.cpp,
 * channel_presets.h) and its shaders (signal_env.comp, signal_pcf.comp): plain #defines with
 * unsigned literals, which C++ and GLSL read alike. */
#ifndef RRC_SAMPLE_SIGNAL_MODES_H
#define RRC_SAMPLE_SIGNAL_MODES_H

/* signal_env.comp's push constant `base`: the base the per-frame env pass also writes for
 * the env residual (README.md, "The env residual"; rrc-sample's --env-residual names). */
#define SAMPLE_ENV_BASE_OFF 0u       /* none: rrc accumulates the sample */
#define SAMPLE_ENV_BASE_CENTRE 1u    /* the bumped mirror along the ray through the pixel's centre */
#define SAMPLE_ENV_BASE_UNBUMPED 2u  /* that ray reflected by the smooth sphere */
#define SAMPLE_ENV_BASE_SMOOTH 3u    /* that reflection into env_smooth (env.glsl) */
#define SAMPLE_ENV_BASE_FILTERED 4u  /* four quarter-pixel reflections into env_filtered (the preset) */

/* signal_pcf.comp's push constant `reference` for the pcf residual's base pass (README.md,
 * "The pcf residual"): 0 is the per-frame signal, 1 the reference, 2 brute force. */
#define SAMPLE_PCF_BASE_PASS 3u

#endif
