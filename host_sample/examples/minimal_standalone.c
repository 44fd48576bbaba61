/* The minimal C host on the standalone path (docs/guide/integration.md, "A minimal
 * C host (standalone path)"): a static camera over a flat surface; the
 * signal alternates 0, 1, 0, 1, ... and rrc's lambda filter with
 * lambda = 0.5 averages it.  Plain C99 on <rrc/rrc.h> alone; it exits
 * non-zero when a result is wrong or, with RRC_VALIDATION=1 in the
 * environment (include/rrc/rrc.h, enable_validation), when the validation
 * layer reported anything. */
#include <rrc/rrc.h>

#include <stdio.h>

enum { W = 16, H = 8 };

int main(void) {
    static float depth[W * H], samples[W * H], values[W * H];
    static uint8_t mask[W * H];
    rrc_context* ctx = NULL;
    rrc_result r;
    uint64_t messages = 0;
    int i, t, ok;

    /* Every descriptor starts with its type tag and size; a member left out is zero, its default.  The paper's plain
     * filter at lambda 1/2, whose values this program checks; an application takes its settings from
     * rrc_channel_preset (docs/guide/). */
    rrc_channel_desc shadow = {.type = RRC_STRUCT_TYPE_CHANNEL_DESC, .size = sizeof shadow, .name = "shadow",
                               .components = 1, .precision = RRC_HISTORY_FP32, .lambda = 0.5f};
    rrc_context_desc desc = {.type = RRC_STRUCT_TYPE_CONTEXT_DESC, .size = sizeof desc, .api_version = RRC_API_VERSION,
                             .width = W, .height = H, .depth_mode = RRC_DEPTH_MODE_REVERSED,
                             .reprojection = RRC_REPROJECTION_CAMERA, /* static scene: matrices only */
                             .channel_count = 1, .channels = &shadow};
    rrc_channel_input input = {.type = RRC_STRUCT_TYPE_CHANNEL_INPUT, .size = sizeof input, .samples = samples};
    rrc_frame_desc frame = {.type = RRC_STRUCT_TYPE_FRAME_DESC, .size = sizeof frame, .depth = depth,
                            .channel_count = 1, .channels = &input};
    rrc_channel_output channel_out = {.type = RRC_STRUCT_TYPE_CHANNEL_OUTPUT, .size = sizeof channel_out, .values = values};
    rrc_frame_output out = {.type = RRC_STRUCT_TYPE_FRAME_OUTPUT, .size = sizeof out, .mask = mask,
                            .channel_count = 1, .channels = &channel_out};
    for (i = 0; i < 16; i += 5) frame.view_proj[i] = frame.prev_view_proj[i] = 1.0; /* identity camera */

    r = rrc_context_create(&desc, &ctx);
    if (r != RRC_SUCCESS) {
        fprintf(stderr, "rrc_context_create: %s: %s\n", rrc_result_to_string(r), rrc_last_error());
        return 1;
    }
    for (i = 0; i < W * H; ++i) depth[i] = 0.5f;
    for (t = 0; t < 9; ++t) {
        for (i = 0; i < W * H; ++i) samples[i] = (float)(t % 2);
        frame.frame_index = (uint64_t)t;
        r = rrc_frame_run(ctx, &frame, &out);
        if (r != RRC_SUCCESS) {
            fprintf(stderr, "rrc_frame_run: %s: %s\n", rrc_result_to_string(r), rrc_last_error());
            return 1;
        }
        printf("frame %d: %lu hits, value %.4f\n", t, (unsigned long)out.stats.hits, values[0]);
    }
    rrc_context_validation_messages(ctx, &messages); /* 0 when validation is off */
    rrc_context_destroy(ctx);
    /* 0, 1/2, 1/4, 5/8, ...: after 9 frames (the last sample 0) the value is
     * (1 - 2^-8) / 3 at every pixel, and every pixel hit. */
    ok = out.stats.hits == W * H && messages == 0;
    for (i = 0; i < W * H; ++i) ok = ok && values[i] > 0.33f && values[i] < 0.34f && mask[i] == RRC_MASK_HIT;
    if (!ok) fprintf(stderr, "unexpected: %lu hits, value %g, %lu validation messages\n", (unsigned long)out.stats.hits,
                     (double)values[0], (unsigned long)messages);
    return ok ? 0 : 1;
}
