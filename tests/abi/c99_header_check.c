/* Compiled with -std=c99 -pedantic-errors -Werror: the public header is plain
 * C99.  Also run: a C host drives one static frame end to end. */
#include <rrc/rrc.h>

#include <stdio.h>
#include <string.h>

/* What every C host does before filling a descriptor: zero it, then its type
 * tag and size (rrc.h Versioning). */
#define INIT_STRUCT(s, tag) (memset(&(s), 0, sizeof(s)), (s).type = (tag), (s).size = (uint32_t)sizeof(s))

int main(void) {
    enum { W = 8, H = 4 };
    static float depth[W * H], samples[W * H], values[W * H];
    static uint8_t mask[W * H];
    rrc_channel_desc ch;
    rrc_context_desc desc;
    rrc_context* ctx = NULL;
    rrc_channel_input in;
    rrc_frame_desc frame;
    rrc_channel_output co;
    rrc_frame_output out;
    rrc_result r;
    int i, t;

    INIT_STRUCT(ch, RRC_STRUCT_TYPE_CHANNEL_DESC);
    strcpy(ch.name, "shadow");
    ch.components = 1;
    ch.precision = RRC_HISTORY_FP32;
    ch.lambda = 0.5f;
    INIT_STRUCT(desc, RRC_STRUCT_TYPE_CONTEXT_DESC);
    desc.api_version = RRC_API_VERSION;
    desc.width = W;
    desc.height = H;
    desc.reprojection = RRC_REPROJECTION_CAMERA;
    desc.channel_count = 1;
    desc.channels = &ch;
    desc.enable_validation = 1;
    r = rrc_context_create(&desc, &ctx);
    if (r != RRC_SUCCESS) {
        fprintf(stderr, "create: %s: %s\n", rrc_result_to_string(r), rrc_last_error());
        return 1;
    }
    INIT_STRUCT(in, RRC_STRUCT_TYPE_CHANNEL_INPUT);
    in.samples = samples;
    INIT_STRUCT(frame, RRC_STRUCT_TYPE_FRAME_DESC);
    frame.depth = depth;
    for (i = 0; i < 16; i += 5) frame.view_proj[i] = frame.prev_view_proj[i] = 1.0;
    frame.channel_count = 1;
    frame.channels = &in;
    INIT_STRUCT(co, RRC_STRUCT_TYPE_CHANNEL_OUTPUT);
    co.values = values;
    INIT_STRUCT(out, RRC_STRUCT_TYPE_FRAME_OUTPUT);
    out.mask = mask;
    out.channel_count = 1;
    out.channels = &co;
    for (i = 0; i < W * H; ++i) depth[i] = 0.25f;
    for (t = 0; t < 2; ++t) {
        for (i = 0; i < W * H; ++i) samples[i] = (float)(t + 1); /* 1 then 2: out = 0.5*1 + 0.5*2 */
        r = rrc_frame_run(ctx, &frame, &out);
        if (r != RRC_SUCCESS) {
            fprintf(stderr, "frame: %s: %s\n", rrc_result_to_string(r), rrc_last_error());
            return 1;
        }
    }
    {
        uint64_t messages = 1;
        rrc_context_validation_messages(ctx, &messages);
        rrc_context_destroy(ctx);
        if (out.stats.hits != W * H || values[5] != 1.5f || mask[5] != RRC_MASK_HIT || messages != 0) {
            fprintf(stderr, "unexpected: hits %lu value %g mask %u validation messages %lu\n", (unsigned long)out.stats.hits,
                    (double)values[5], (unsigned)mask[5], (unsigned long)messages);
            return 1;
        }
    }
    printf("c99 host: %d hits, value %g\n", (int)(W * H), (double)values[5]);
    return 0;
}
