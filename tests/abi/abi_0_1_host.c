/* A 0.1 caller: compiled against ONLY the verbatim 0.1 headers
 * (tests/abi/rrc_0_1; include/ is not on its include path) and linked to the
 * current library by file.  It runs a standalone context over a static scene
 * whose results are known in closed form and checks values, mask, age,
 * weight and stats; any difference is a break of the 0.x ABI (rule 6: a
 * caller passing api_version 0.1.0 keeps working identically).
 *
 * Scene, 8x4 pixels, STANDARD depth, PREV_CLIP reprojection equal to each
 * pixel's own clip position (x = 2(i+0.5)/8 - 1, y = 2(j+0.5)/4 - 1, z =
 * depth, w = 1: every value exact in fp32, so the previous-frame coordinate
 * is exactly a texel centre and the bilinear taps' weights are 1, 0, 0, 0).
 * Column 0 is background (depth 1) in every frame; the others have depth 0.5.
 * Seven frames; frame 5 is a reset (camera cut); frames 3 and 4 go through
 * rrc_frame_run_batch, the others through rrc_frame_run.
 *   "a": 1 component, FIXED lambda 0.75, NEAREST; samples 1 (t < 3) then 5.
 *   "b": 4 components, AGE_AWARE lambda 0.8, BILINEAR, age cap 3; samples
 *        (1,2,3,4) (t < 3) then (4,3,2,1).  lambda_eff = min(0.8, n/(n+1))
 *        with n the capped age: 1/2, 2/3, 3/4, 3/4, ...
 *   "c": 1 component, RUNNING_MEAN with confidence 0.5; samples t + 1.
 * The lambda recursion is evaluated here in fp32 as lambda*H + (1-lambda)*s;
 * the kernel may order or fuse those operations differently, so values are
 * compared to 1e-5 relative (the recursion's rounding is ~1e-7).  Mask, age,
 * weight (0.5 exactly) and stats are compared exactly. */
#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The 0.1 headers and nothing newer: RRC_API_VERSION must be 0.1.0 here (a
 * negative array size otherwise), and 0.2's additions must be absent. */
typedef char rrc_abi_header_is_0_1_0[(RRC_API_VERSION == RRC_MAKE_VERSION(0, 1, 0)) ? 1 : -1];
#if defined(RRC_MAX_CHAIN) || defined(RRC_STRUCT_TYPE_EXT_FIRST)
#error "abi_0_1_host.c must be compiled against the 0.1 headers (tests/abi/rrc_0_1), not include/"
#endif

enum { W = 8, H = 4, N = W * H, FRAMES = 7, RESET_FRAME = 5, BACKGROUND_PIXELS = H };

static int failures = 0;
static unsigned long validation_logged = 0;

static void on_log(void* user, rrc_log_level level, const char* message) {
    (void)user;
    if (level == RRC_LOG_VALIDATION) {
        ++validation_logged;
        fprintf(stderr, "validation: %s\n", message);
    }
}

#define CHECK(cond, ...)                                                 \
    do {                                                                 \
        if (!(cond)) {                                                   \
            if (failures < 40) {                                         \
                fprintf(stderr, "%s:%d: FAILED %s: ", __FILE__, __LINE__, #cond); \
                fprintf(stderr, __VA_ARGS__);                            \
                fprintf(stderr, "\n");                                   \
            }                                                            \
            ++failures;                                                  \
        }                                                                \
    } while (0)

static int close_to(float got, float want) {
    float scale = fabsf(want) > 1.0f ? fabsf(want) : 1.0f;
    return fabsf(got - want) <= 1e-5f * scale;
}

static float sample_a(int t) { return t < 3 ? 1.0f : 5.0f; }
static float sample_b(int t, int k) { return t < 3 ? (float)(k + 1) : (float)(4 - k); }
static float sample_c(int t) { return (float)(t + 1); }

/* Everything one frame passes and gets back. */
typedef struct Frame {
    float depth[N], clip[4 * N], sa[N], sb[4 * N], sc[N], wc[N];
    float va[N], vb[4 * N], vc[N], weight_c[N];
    uint16_t age_a[N], age_b[N], age_c[N];
    uint8_t mask[N];
    rrc_channel_input inputs[3];
    rrc_channel_output outs[3];
    rrc_frame_desc desc;
    rrc_frame_output output;
} Frame;

static void make_frame(Frame* f, int t) {
    int i, j, k;
    memset(f, 0, sizeof *f);
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            int p = j * W + i;
            f->depth[p] = i == 0 ? 1.0f : 0.5f;
            f->clip[4 * p + 0] = 2.0f * ((float)i + 0.5f) / (float)W - 1.0f;
            f->clip[4 * p + 1] = 2.0f * ((float)j + 0.5f) / (float)H - 1.0f;
            f->clip[4 * p + 2] = f->depth[p];
            f->clip[4 * p + 3] = 1.0f;
            f->sa[p] = sample_a(t);
            for (k = 0; k < 4; ++k) f->sb[4 * p + k] = sample_b(t, k);
            f->sc[p] = sample_c(t);
            f->wc[p] = 0.5f;
            f->va[p] = f->vc[p] = f->weight_c[p] = -1.0f;
            f->age_a[p] = f->age_b[p] = f->age_c[p] = 999;
        }
    for (k = 0; k < 4 * N; ++k) f->vb[k] = -1.0f;
    memset(f->mask, 0xEE, sizeof f->mask);
    for (k = 0; k < 3; ++k) {
        f->inputs[k].type = RRC_STRUCT_TYPE_CHANNEL_INPUT;
        f->inputs[k].size = sizeof f->inputs[k];
        f->outs[k].type = RRC_STRUCT_TYPE_CHANNEL_OUTPUT;
        f->outs[k].size = sizeof f->outs[k];
    }
    f->inputs[0].samples = f->sa;
    f->inputs[1].samples = f->sb;
    f->inputs[2].samples = f->sc;
    f->inputs[2].confidence = f->wc;
    f->outs[0].values = f->va;
    f->outs[0].age = f->age_a;
    f->outs[1].values = f->vb;
    f->outs[1].age = f->age_b;
    f->outs[2].values = f->vc;
    f->outs[2].age = f->age_c;
    f->outs[2].weight = f->weight_c;
    f->desc.type = RRC_STRUCT_TYPE_FRAME_DESC;
    f->desc.size = sizeof f->desc;
    f->desc.frame_index = (uint64_t)t;
    f->desc.reset = t == RESET_FRAME;
    f->desc.depth = f->depth;
    f->desc.reprojection = f->clip;
    f->desc.channel_count = 3;
    f->desc.channels = f->inputs;
    f->output.type = RRC_STRUCT_TYPE_FRAME_OUTPUT;
    f->output.size = sizeof f->output;
    f->output.mask = f->mask;
    f->output.channel_count = 3;
    f->output.channels = f->outs;
    f->output.stats.hits = 12345;
}

/* The closed-form history of one non-background pixel. */
typedef struct Expected {
    float a, b[4], c;
    unsigned age_a, age_b, age_c;
    int hit;
} Expected;

static void advance(Expected* e, int t) {
    int k;
    const int hit = t > 0 && t != RESET_FRAME;
    e->hit = hit;
    if (!hit) {
        e->a = sample_a(t);
        for (k = 0; k < 4; ++k) e->b[k] = sample_b(t, k);
        e->c = sample_c(t);
        e->age_a = e->age_b = e->age_c = 1;
        return;
    }
    {
        const float la = 0.75f;
        const float lb = fminf(0.8f, (float)e->age_b / (float)(e->age_b + 1));
        const float lc = (float)e->age_c / (float)(e->age_c + 1);
        /* confidence 0.5 everywhere: W' = lc*0.5 + (1-lc)*0.5 = 0.5, so the
         * weighted blend is the plain one. */
        e->a = la * e->a + (1.0f - la) * sample_a(t);
        for (k = 0; k < 4; ++k) e->b[k] = lb * e->b[k] + (1.0f - lb) * sample_b(t, k);
        e->c = lc * e->c + (1.0f - lc) * sample_c(t);
        e->age_a = e->age_a + 1;
        e->age_b = e->age_b + 1 > 3 ? 3 : e->age_b + 1;
        e->age_c = e->age_c + 1;
    }
}

static void check_frame(const Frame* f, const Expected* e, int t) {
    int i, j, k;
    const uint64_t fg = N - BACKGROUND_PIXELS;
    CHECK(f->output.stats.hits == (e->hit ? fg : 0), "frame %d: %lu hits", t, (unsigned long)f->output.stats.hits);
    CHECK(f->output.stats.misses == (e->hit ? 0 : fg), "frame %d: %lu misses", t, (unsigned long)f->output.stats.misses);
    CHECK(f->output.stats.background == BACKGROUND_PIXELS, "frame %d: %lu background", t, (unsigned long)f->output.stats.background);
    CHECK(f->output.stats.invalid_samples == 0 && f->output.stats.invalid_geometry == 0, "frame %d: invalid pixels counted", t);
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            const int p = j * W + i;
            if (i == 0) { /* background: the sample itself, age 0, weight w */
                CHECK(f->mask[p] == RRC_MASK_BACKGROUND, "frame %d pixel %d: mask %u", t, p, (unsigned)f->mask[p]);
                CHECK(f->va[p] == sample_a(t) && f->vc[p] == sample_c(t), "frame %d pixel %d: background values %g %g", t, p,
                      (double)f->va[p], (double)f->vc[p]);
                for (k = 0; k < 4; ++k) CHECK(f->vb[4 * p + k] == sample_b(t, k), "frame %d pixel %d: background b[%d]", t, p, k);
                CHECK(f->age_a[p] == 0 && f->age_b[p] == 0 && f->age_c[p] == 0, "frame %d pixel %d: background age", t, p);
                CHECK(f->weight_c[p] == 0.5f, "frame %d pixel %d: background weight %g", t, p, (double)f->weight_c[p]);
                continue;
            }
            CHECK(f->mask[p] == (e->hit ? RRC_MASK_HIT : 0u), "frame %d pixel %d: mask %u", t, p, (unsigned)f->mask[p]);
            CHECK(close_to(f->va[p], e->a), "frame %d pixel %d: a %.9g, expected %.9g", t, p, (double)f->va[p], (double)e->a);
            for (k = 0; k < 4; ++k)
                CHECK(close_to(f->vb[4 * p + k], e->b[k]), "frame %d pixel %d: b[%d] %.9g, expected %.9g", t, p, k,
                      (double)f->vb[4 * p + k], (double)e->b[k]);
            CHECK(close_to(f->vc[p], e->c), "frame %d pixel %d: c %.9g, expected %.9g", t, p, (double)f->vc[p], (double)e->c);
            CHECK(f->age_a[p] == e->age_a && f->age_b[p] == e->age_b && f->age_c[p] == e->age_c,
                  "frame %d pixel %d: ages %u %u %u, expected %u %u %u", t, p, (unsigned)f->age_a[p], (unsigned)f->age_b[p],
                  (unsigned)f->age_c[p], e->age_a, e->age_b, e->age_c);
            CHECK(f->weight_c[p] == 0.5f, "frame %d pixel %d: weight %g", t, p, (double)f->weight_c[p]);
        }
}

static Frame frames[FRAMES];

int main(void) {
    rrc_channel_desc ch[3];
    rrc_context_desc desc;
    rrc_context* ctx = NULL;
    rrc_result r;
    Expected e;
    uint64_t messages = 1;
    const uint32_t version = rrc_get_version();
    int t, k;

    printf("0.1 caller (header %u.%u.%u) on library %u.%u.%u\n", RRC_VERSION_MAJOR(RRC_API_VERSION), RRC_VERSION_MINOR(RRC_API_VERSION),
           RRC_VERSION_PATCH(RRC_API_VERSION), RRC_VERSION_MAJOR(version), RRC_VERSION_MINOR(version), RRC_VERSION_PATCH(version));
    CHECK(RRC_VERSION_MAJOR(version) == 0 && RRC_VERSION_MINOR(version) >= 1, "library version %u.%u", RRC_VERSION_MAJOR(version),
          RRC_VERSION_MINOR(version));

    memset(ch, 0, sizeof ch);
    for (k = 0; k < 3; ++k) {
        ch[k].type = RRC_STRUCT_TYPE_CHANNEL_DESC;
        ch[k].size = sizeof ch[k];
        ch[k].precision = RRC_HISTORY_FP32;
    }
    strcpy(ch[0].name, "a");
    ch[0].components = 1;
    ch[0].lambda = 0.75f;
    ch[0].blend = RRC_BLEND_FIXED;
    ch[0].filter = RRC_HISTORY_FILTER_NEAREST;
    strcpy(ch[1].name, "b");
    ch[1].components = 4;
    ch[1].lambda = 0.8f;
    ch[1].blend = RRC_BLEND_AGE_AWARE;
    ch[1].filter = RRC_HISTORY_FILTER_BILINEAR;
    ch[1].age_cap = 3;
    strcpy(ch[2].name, "c");
    ch[2].components = 1;
    ch[2].blend = RRC_BLEND_RUNNING_MEAN;
    ch[2].confidence = 1;

    memset(&desc, 0, sizeof desc);
    desc.type = RRC_STRUCT_TYPE_CONTEXT_DESC;
    desc.size = sizeof desc;
    desc.api_version = RRC_API_VERSION; /* 0.1.0 */
    desc.width = W;
    desc.height = H;
    desc.depth_mode = RRC_DEPTH_MODE_STANDARD;
    desc.reprojection = RRC_REPROJECTION_PREV_CLIP;
    desc.channel_count = 3;
    desc.channels = ch;
    desc.enable_validation = 1;
    desc.log = on_log;

    r = rrc_validate_context_desc(&desc);
    CHECK(r == RRC_SUCCESS, "validate: %s: %s", rrc_result_to_string(r), rrc_last_error());
    r = rrc_context_create(&desc, &ctx);
    if (r != RRC_SUCCESS) {
        fprintf(stderr, "create: %s: %s\n", rrc_result_to_string(r), rrc_last_error());
        return 1;
    }

    for (t = 0; t < FRAMES; ++t) make_frame(&frames[t], t);
    memset(&e, 0, sizeof e);
    for (t = 0; t < FRAMES; ++t) {
        if (t == 3) { /* frames 3 and 4 in one batch */
            rrc_frame_desc batch[2];
            rrc_frame_output outputs[2];
            batch[0] = frames[3].desc;
            batch[1] = frames[4].desc;
            outputs[0] = frames[3].output;
            outputs[1] = frames[4].output;
            r = rrc_frame_run_batch(ctx, 2, batch, outputs);
            CHECK(r == RRC_SUCCESS, "batch 3-4: %s: %s", rrc_result_to_string(r), rrc_last_error());
            frames[3].output.stats = outputs[0].stats;
            frames[4].output.stats = outputs[1].stats;
        } else if (t != 4) {
            r = rrc_frame_run(ctx, &frames[t].desc, &frames[t].output);
            CHECK(r == RRC_SUCCESS, "frame %d: %s: %s", t, rrc_result_to_string(r), rrc_last_error());
        }
    }
    for (t = 0; t < FRAMES; ++t) {
        advance(&e, t);
        check_frame(&frames[t], &e, t);
    }

    r = rrc_context_validation_messages(ctx, &messages);
    CHECK(r == RRC_SUCCESS && messages == 0, "%lu validation messages", (unsigned long)messages);
    rrc_context_destroy(ctx);
    CHECK(validation_logged == 0, "%lu validation messages logged", validation_logged);
    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("0.1 caller: %d frames as expected\n", FRAMES);
    return 0;
}
