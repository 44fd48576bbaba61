// The C API's argument checking: every bad descriptor is refused with a
// specific code and a message naming the field, without touching Vulkan;
// calls on a live context leave outputs untouched on error.
#include "support/rrc_test_context.h"
#include "support/static_clip.h"

#include <cmath>
#include <functional>
#include <limits>

using namespace rrc_test;

namespace {

struct DescCase {
    const char* name;
    std::function<void(rrc_context_desc&, std::vector<rrc_channel_desc>&)> mutate;
    rrc_result expected;
    const char* field;  // must appear in the message
};

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// Plain MOTION linearises depth with the planes: the checks on them.
void motion_planes(rrc_context_desc& d, float near_plane, float far_plane) {
    d.reprojection = RRC_REPROJECTION_MOTION;
    d.near_plane = near_plane;
    d.far_plane = far_plane;
}

std::vector<DescCase> desc_cases() {
    using D = rrc_context_desc;
    using C = std::vector<rrc_channel_desc>;
    return {
        {"wrong_type", [](D& d, C&) { d.type = 7; }, RRC_ERROR_INVALID_STRUCT, "desc.type"},
        {"small_size", [](D& d, C&) { d.size = 8; }, RRC_ERROR_INVALID_STRUCT, "desc.size"},
        {"next_set", [](D& d, C&) { d.next = &d; }, RRC_ERROR_INVALID_STRUCT, "desc.next"},
        {"major_version", [](D& d, C&) { d.api_version = RRC_MAKE_VERSION(9, 0, 0); }, RRC_ERROR_INCOMPATIBLE_VERSION, "api_version"},
        {"zero_version", [](D& d, C&) { d.api_version = 0x7FFFFFFF; }, RRC_ERROR_INCOMPATIBLE_VERSION, "api_version"},
        {"zero_width", [](D& d, C&) { d.width = 0; }, RRC_ERROR_INVALID_ARGUMENT, "desc.width"},
        {"zero_height", [](D& d, C&) { d.height = 0; }, RRC_ERROR_INVALID_ARGUMENT, "desc.height"},
        {"absurd_size",
         [](D& d, C&) {
             d.width = 1u << 20;
             d.height = 1u << 20;
         },
         RRC_ERROR_INVALID_ARGUMENT, "desc.width"},
        {"absurd_height", [](D& d, C&) { d.height = RRC_MAX_EXTENT + 1; }, RRC_ERROR_INVALID_ARGUMENT, "desc.height"},
        {"depth_mode", [](D& d, C&) { d.depth_mode = 3; }, RRC_ERROR_INVALID_ARGUMENT, "desc.depth_mode"},
        {"depth_format", [](D& d, C&) { d.depth_format = 17; }, RRC_ERROR_INVALID_ARGUMENT, "desc.depth_format"},
        {"reprojection", [](D& d, C&) { d.reprojection = 4; }, RRC_ERROR_INVALID_ARGUMENT, "desc.reprojection"},
        {"epsilon_nan", [](D& d, C&) { d.epsilon = kNaN; }, RRC_ERROR_INVALID_ARGUMENT, "desc.epsilon"},
        {"epsilon_negative", [](D& d, C&) { d.epsilon = -1.0f; }, RRC_ERROR_INVALID_ARGUMENT, "desc.epsilon"},
        {"epsilon_scale_inf", [](D& d, C&) { d.epsilon_scale = kInf; }, RRC_ERROR_INVALID_ARGUMENT, "desc.epsilon_scale"},
        {"tau_negative", [](D& d, C&) { d.tau = -0.5f; }, RRC_ERROR_INVALID_ARGUMENT, "desc.tau"},
        {"depth_test_unknown", [](D& d, C&) { d.depth_test = 3; }, RRC_ERROR_INVALID_ARGUMENT, "desc.depth_test"},
        {"depth_test_adaptive_with_epsilon_scale", [](D& d, C&) { d.depth_test = RRC_DEPTH_TEST_ADAPTIVE, d.epsilon_scale = 8; },
         RRC_ERROR_INVALID_ARGUMENT, "desc.depth_test"},
        {"depth_test_adaptive_with_tau", [](D& d, C&) { d.depth_test = RRC_DEPTH_TEST_ADAPTIVE, d.tau = 0.02f; },
         RRC_ERROR_INVALID_ARGUMENT, "desc.depth_test"},
        {"background_nan", [](D& d, C&) { d.background_threshold = kNaN; }, RRC_ERROR_INVALID_ARGUMENT, "desc.background_threshold"},
        {"motion_needs_near", [](D& d, C&) { motion_planes(d, 0, 100); }, RRC_ERROR_INVALID_ARGUMENT, "desc.near_plane"},
        {"motion_far_below_near", [](D& d, C&) { motion_planes(d, 1, 0.5f); }, RRC_ERROR_INVALID_ARGUMENT, "desc.far_plane"},
        {"motion_infinite_far_standard", [](D& d, C&) { motion_planes(d, 1, kInf); }, RRC_ERROR_INVALID_ARGUMENT, "desc.far_plane"},
        {"motion_scale_nan", [](D& d, C&) { d.motion_scale[0] = kNaN; }, RRC_ERROR_INVALID_ARGUMENT, "desc.motion_scale"},
        {"no_channels", [](D& d, C&) { d.channel_count = 0; }, RRC_ERROR_INVALID_ARGUMENT, "desc.channel_count"},
        {"too_many_channels", [](D& d, C&) { d.channel_count = RRC_MAX_CHANNELS + 1; }, RRC_ERROR_INVALID_ARGUMENT, "desc.channel_count"},
        {"channels_null", [](D& d, C&) { d.channels = nullptr; }, RRC_ERROR_INVALID_ARGUMENT, "desc.channels"},
        {"channel_type", [](D&, C& c) { c[0].type = RRC_STRUCT_TYPE_FRAME_DESC; }, RRC_ERROR_INVALID_STRUCT, "channels[0].type"},
        {"channel_size", [](D&, C& c) { c[0].size = 4; }, RRC_ERROR_INVALID_STRUCT, "channels[0].size"},
        {"channel_name_empty", [](D&, C& c) { c[0].name[0] = 0; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].name"},
        {"channel_name_unterminated", [](D&, C& c) { std::memset(c[0].name, 'x', RRC_MAX_NAME); }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0].name"},
        {"channel_name_repeated", [](D&, C& c) { std::strcpy(c[1].name, c[0].name); }, RRC_ERROR_INVALID_ARGUMENT, "channels[1].name"},
        {"channel_components", [](D&, C& c) { c[1].components = 3; }, RRC_ERROR_INVALID_ARGUMENT, "channels[1].components"},
        {"channel_precision", [](D&, C& c) { c[0].precision = 2; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].precision"},
        {"lambda_one", [](D&, C& c) { c[0].lambda = 1.0f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].lambda"},
        {"lambda_negative", [](D&, C& c) { c[0].lambda = -0.1f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].lambda"},
        {"lambda_nan", [](D&, C& c) { c[1].lambda = kNaN; }, RRC_ERROR_INVALID_ARGUMENT, "channels[1].lambda"},
        {"blend", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE + 1; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].blend"},
        {"filter", [](D&, C& c) { c[0].filter = 9; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].filter"},
        {"age_cap", [](D&, C& c) { c[0].age_cap = RRC_MAX_AGE_CAP + 1; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].age_cap"},
        // The finishing steps (0.4).
        {"filter_past_gaussian", [](D&, C& c) { c[0].filter = RRC_HISTORY_FILTER_GAUSSIAN + 1; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0].filter"},
        {"rectify_with_reuse", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].rectify = 1; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0]"},
        {"rectify_gamma_large", [](D&, C& c) { c[1].rectify = 1, c[1].rectify_gamma = RRC_MAX_RECTIFY_GAMMA * 2; },
         RRC_ERROR_INVALID_ARGUMENT, "channels[1].rectify_gamma"},
        {"rectify_gamma_nan", [](D&, C& c) { c[1].rectify = 1, c[1].rectify_gamma = kNaN; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[1].rectify_gamma"},
        {"rectify_gamma_without_rectify", [](D&, C& c) { c[0].rectify_gamma = 2.0f; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0].rectify_gamma"},
        {"blur_sigma_without_gaussian", [](D&, C& c) { c[0].blur_sigma = 0.5f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].blur_sigma"},
        {"blur_sigma_large", [](D&, C& c) { c[0].filter = RRC_HISTORY_FILTER_GAUSSIAN, c[0].blur_sigma = 0.9f; },
         RRC_ERROR_INVALID_ARGUMENT, "channels[0].blur_sigma"},
        {"blur_sigma_negative", [](D&, C& c) { c[0].filter = RRC_HISTORY_FILTER_GAUSSIAN, c[0].blur_sigma = -0.5f; },
         RRC_ERROR_INVALID_ARGUMENT, "channels[0].blur_sigma"},
        {"fill_age_past_cap", [](D&, C& c) { c[0].age_cap = 8, c[0].fill_age = 10; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].fill_age"},
        {"fill_radius_large", [](D&, C& c) { c[0].fill_age = 4, c[0].fill_radius = RRC_MAX_FILL_RADIUS + 1; },
         RRC_ERROR_INVALID_ARGUMENT, "channels[0].fill_radius"},
        {"fill_tolerance_nan", [](D&, C& c) { c[0].fill_age = 4, c[0].fill_depth_tolerance = kNaN; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0].fill_depth_tolerance"},
        {"fill_prior_negative", [](D&, C& c) { c[0].fill_age = 4, c[0].fill_prior = -1.0f; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0].fill_prior"},
        {"fill_prior_without_fill", [](D&, C& c) { c[0].fill_prior = 4.0f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0]"},
        // The lag detector (0.5).
        {"antilag_with_reuse", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].antilag = 1; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0]"},
        {"antilag_gamma_large", [](D&, C& c) { c[1].antilag = 1, c[1].antilag_gamma = RRC_MAX_ANTILAG_GAMMA * 2; },
         RRC_ERROR_INVALID_ARGUMENT, "channels[1].antilag_gamma"},
        {"antilag_gamma_negative", [](D&, C& c) { c[1].antilag = 1, c[1].antilag_gamma = -1.0f; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[1].antilag_gamma"},
        {"antilag_gamma_nan", [](D&, C& c) { c[0].antilag = 1, c[0].antilag_gamma = kNaN; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0].antilag_gamma"},
        {"antilag_threshold_large", [](D&, C& c) { c[0].antilag = 1, c[0].antilag_threshold = RRC_MAX_ANTILAG_THRESHOLD * 1.5f; },
         RRC_ERROR_INVALID_ARGUMENT, "channels[0].antilag_threshold"},
        {"antilag_threshold_nan", [](D&, C& c) { c[1].antilag = 1, c[1].antilag_threshold = kNaN; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[1].antilag_threshold"},
        {"antilag_gamma_without_antilag", [](D&, C& c) { c[0].antilag_gamma = 2.0f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0]"},
        {"antilag_threshold_without_antilag", [](D&, C& c) { c[1].antilag_threshold = 0.5f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[1]"},
        // The blur bound (0.6).
        {"blur_bound_negative", [](D&, C& c) { c[0].blur_bound = -0.5f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].blur_bound"},
        {"blur_bound_large", [](D&, C& c) { c[1].blur_bound = RRC_MAX_BLUR_BOUND * 1.5f; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[1].blur_bound"},
        {"blur_bound_nan", [](D&, C& c) { c[1].blur_bound = kNaN; }, RRC_ERROR_INVALID_ARGUMENT, "channels[1].blur_bound"},
        {"blur_bound_inf", [](D&, C& c) { c[0].blur_bound = kInf; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].blur_bound"},
        {"blur_bound_with_reuse", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].blur_bound = 1.0f; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0]"},
        // The view lobe (0.7).
        {"view_lobe_negative", [](D&, C& c) { c[0].view_lobe = -0.01f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].view_lobe"},
        {"view_lobe_large", [](D&, C& c) { c[1].view_lobe = 4.0f; }, RRC_ERROR_INVALID_ARGUMENT, "channels[1].view_lobe"},
        {"view_lobe_nan", [](D&, C& c) { c[1].view_lobe = kNaN; }, RRC_ERROR_INVALID_ARGUMENT, "channels[1].view_lobe"},
        {"view_lobe_inf", [](D&, C& c) { c[0].view_lobe = kInf; }, RRC_ERROR_INVALID_ARGUMENT, "channels[0].view_lobe"},
        {"view_lobe_with_reuse", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].view_lobe = 0.1f; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0]"},
        // The residual (0.9).
        {"residual_with_reuse", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].residual = 1; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0]"},
        // The shading cache (0.3): channel 0 made REUSE where a case needs one.
        {"reuse_with_confidence", [](D&, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].confidence = 1; }, RRC_ERROR_INVALID_ARGUMENT,
         "channels[0]"},
        {"refresh_policy", [](D& d, C& c) { c[0].blend = RRC_BLEND_REUSE, d.refresh_policy = 3, d.refresh_period = 4; },
         RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_policy"},
        {"refresh_without_reuse", [](D& d, C&) { d.refresh_policy = RRC_REFRESH_RANDOM, d.refresh_period = 4; }, RRC_ERROR_INVALID_ARGUMENT,
         "desc.refresh_policy"},
        {"refresh_period_zero", [](D& d, C& c) { c[0].blend = RRC_BLEND_REUSE, d.refresh_policy = RRC_REFRESH_RANDOM; },
         RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_period"},
        {"refresh_period_large", [](D& d, C& c) { c[0].blend = RRC_BLEND_REUSE, d.refresh_policy = RRC_REFRESH_RANDOM, d.refresh_period = RRC_MAX_REFRESH_PERIOD + 1; },
         RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_period"},
        {"refresh_period_without_policy", [](D& d, C& c) { c[0].blend = RRC_BLEND_REUSE, d.refresh_period = 4; }, RRC_ERROR_INVALID_ARGUMENT,
         "desc.refresh_period"},
        {"refresh_tiles_product", [](D& d, C& c) {
             c[0].blend = RRC_BLEND_REUSE, d.refresh_policy = RRC_REFRESH_TILED, d.refresh_period = 8, d.refresh_tiles[0] = 3, d.refresh_tiles[1] = 2;
         }, RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_tiles"},
        {"refresh_tiles_random", [](D& d, C& c) {
             c[0].blend = RRC_BLEND_REUSE, d.refresh_policy = RRC_REFRESH_RANDOM, d.refresh_period = 4, d.refresh_tiles[0] = 2, d.refresh_tiles[1] = 2;
         }, RRC_ERROR_INVALID_ARGUMENT, "desc.refresh_tiles"},
        {"lifetime_without_reuse", [](D& d, C&) { d.max_lifetime = 4; }, RRC_ERROR_INVALID_ARGUMENT, "desc.max_lifetime"},
        {"lifetime_above_age_cap", [](D& d, C& c) { c[0].blend = RRC_BLEND_REUSE, c[0].age_cap = 8, d.max_lifetime = 9; },
         RRC_ERROR_INVALID_ARGUMENT, "desc.max_lifetime"},
        {"view_count", [](D& d, C&) { d.view_count = RRC_MAX_VIEWS + 1; }, RRC_ERROR_INVALID_ARGUMENT, "desc.view_count"},
        // A base struct in a chain (0.2 rule 5): INVALID_STRUCT.
        {"channel_next", [](D&, C& c) { c[1].next = &c[0]; }, RRC_ERROR_INVALID_STRUCT, "channels[1].next"},
    };
}

class DescValidation : public ::testing::TestWithParam<DescCase> {};

TEST_P(DescValidation, RefusedWithCodeAndFieldName) {
    std::vector<rrc_channel_desc> channels = {channel("shadow", 1, 0.6f), channel("color", 4, 0.6f)};
    rrc_context_desc d = context_desc(64, 32, channels);
    ASSERT_EQ(rrc_validate_context_desc(&d), RRC_SUCCESS) << rrc_last_error();
    GetParam().mutate(d, channels);
    EXPECT_EQ(rrc_validate_context_desc(&d), GetParam().expected) << rrc_last_error();
    EXPECT_NE(std::string(rrc_last_error()).find(GetParam().field), std::string::npos) << rrc_last_error();
    // create refuses the same way and leaves the output untouched.
    rrc_context* sentinel = reinterpret_cast<rrc_context*>(0x1234);
    rrc_context* out = sentinel;
    EXPECT_EQ(rrc_context_create(&d, &out), GetParam().expected);
    EXPECT_EQ(out, sentinel);
}

INSTANTIATE_TEST_SUITE_P(Api, DescValidation, ::testing::ValuesIn(desc_cases()),
                         [](const ::testing::TestParamInfo<DescCase>& i) { return std::string(i.param.name); });

TEST(Api, VersionAndResultNames) {
    EXPECT_EQ(RRC_VERSION_MAJOR(rrc_get_version()), RRC_VERSION_MAJOR(RRC_API_VERSION));
    EXPECT_STREQ(rrc_result_to_string(RRC_ERROR_SIZE_MISMATCH), "RRC_ERROR_SIZE_MISMATCH");
    EXPECT_STREQ(rrc_result_to_string(RRC_SUCCESS), "RRC_SUCCESS");
    EXPECT_STREQ(rrc_result_to_string(-999), "RRC_ERROR_UNKNOWN");
}

TEST(Api, NullArgumentsAreRefused) {
    EXPECT_EQ(rrc_validate_context_desc(nullptr), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("desc"), std::string::npos);
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f)};
    rrc_context_desc d = context_desc(8, 8, channels);
    EXPECT_EQ(rrc_context_create(&d, nullptr), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("out_context"), std::string::npos);
    rrc_frame_desc f = frame_desc();
    EXPECT_EQ(rrc_frame_run(nullptr, &f, nullptr), RRC_ERROR_INVALID_HANDLE);
    uint64_t count = 0;
    EXPECT_EQ(rrc_context_validation_messages(nullptr, &count), RRC_ERROR_INVALID_HANDLE);
    char name[8];
    EXPECT_EQ(rrc_context_device_name(nullptr, name, sizeof name), RRC_ERROR_INVALID_HANDLE);
    rrc_context_destroy(nullptr);  // allowed
}

TEST(Api, ForeignHandleIsDetectedWithoutDereferencing) {
    alignas(16) unsigned char garbage[256] = {0xAB};
    auto* fake = reinterpret_cast<rrc_context*>(garbage);
    rrc_frame_desc f = frame_desc();
    EXPECT_EQ(rrc_frame_run(fake, &f, nullptr), RRC_ERROR_INVALID_HANDLE);
    EXPECT_NE(std::string(rrc_last_error()).find("not a live rrc context"), std::string::npos);
    rrc_context_destroy(fake);  // ignored, never freed
}

// A residual channel (0.9) without a fill still needs its base every frame:
// refused, outputs untouched, the history kept (docs/CONVENTIONS.md, "The residual").
TEST(Api, ResidualFrameWithoutItsBaseIsRefused) {
    const uint32_t W = 16, H = 8;
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f)};
    channels[0].residual = 1;
    rrc_context_desc d = context_desc(W, H, channels);
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    Context ctx(d);
    ASSERT_TRUE(ctx);
    std::vector<float> depth(W * H, 0.5f), clip = static_prev_clip(W, H, 0.5f), s(W * H, 1.0f), base(W * H, 0.75f);
    rrc_channel_input in = channel_input(s.data(), nullptr);
    in.fallback = base.data();
    rrc_frame_desc f = frame_desc();
    f.depth = depth.data();
    f.reprojection = clip.data();
    f.channel_count = 1;
    f.channels = &in;
    FrameResult first = ctx.run(f);
    EXPECT_EQ(first.values[0], std::vector<float>(W * H, 1.0f)) << "a fresh pixel shows (s - b) + b";
    rrc_channel_input no_base = in;
    no_base.fallback = nullptr;
    rrc_frame_desc bad = f;
    bad.channels = &no_base;
    FrameResult refused;
    BoundOutput o(refused, channels, W * H, OutputFill{0xEE, -7.0f, 77});
    EXPECT_EQ(rrc_frame_run(ctx.get(), &bad, &o.frame), RRC_ERROR_MISSING_INPUT);
    EXPECT_NE(std::string(rrc_context_last_error(ctx.get())).find("has residual"), std::string::npos) << rrc_context_last_error(ctx.get());
    EXPECT_EQ(refused.values[0], std::vector<float>(W * H, -7.0f));
    EXPECT_EQ(refused.age[0], std::vector<uint16_t>(W * H, 77));
    EXPECT_EQ(refused.mask, std::vector<uint8_t>(W * H, 0xEE));
    // The history survived: the next frame blends (s - b) with the residual 0.25 kept, and shows it plus the new base.
    std::fill(base.begin(), base.end(), 0.5f);
    FrameResult after = ctx.run(f);
    EXPECT_EQ(after.age[0], std::vector<uint16_t>(W * H, 2));
    EXPECT_EQ(after.values[0], std::vector<float>(W * H, 0.5f * 0.25f + 0.5f * 0.5f + 0.5f));
}

// Frame-level errors on a live context: each refused, outputs untouched.
TEST(Api, BadFramesLeaveOutputsUntouched) {
    const uint32_t W = 16, H = 8;
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f, RRC_HISTORY_FP32, RRC_BLEND_FIXED, RRC_HISTORY_FILTER_BILINEAR, 0, 1)};
    channels[0].fill_age = 4;  // 0.4: frames carry a fallback
    channels[0].fill_prior = 2.0f;
    rrc_context_desc d = context_desc(W, H, channels);
    d.reprojection = RRC_REPROJECTION_PREV_CLIP;
    d.use_nocache_mask = 1;
    Context ctx(d);
    ASSERT_TRUE(ctx);
    std::vector<float> depth(W * H, 0.5f), clip = static_prev_clip(W, H, 0.5f), s(W * H, 1.0f), conf(W * H, 1.0f);
    std::vector<uint8_t> nocache(W * H, 0);
    rrc_channel_input in = channel_input(s.data(), conf.data());
    std::vector<float> fallback(W * H, 0.5f);
    in.fallback = fallback.data();
    auto good = [&] {
        rrc_frame_desc f = frame_desc();
        f.depth = depth.data();
        f.reprojection = clip.data();
        f.nocache = nocache.data();
        f.channel_count = 1;
        f.channels = &in;
        return f;
    };
    struct FrameCase {
        const char* field;
        rrc_result code;
        std::function<void(rrc_frame_desc&, rrc_channel_input&)> mutate;
    };
    rrc_channel_input bad_in;
    // A case on the channel's input: the good one, edited, in place of it.
    auto on_input = [&](std::function<void(rrc_channel_input&)> edit) {
        return [&in, edit](rrc_frame_desc& f, rrc_channel_input& i) {
            i = in;
            edit(i);
            f.channels = &i;
        };
    };
    std::vector<FrameCase> cases = {
        {"frame.type", RRC_ERROR_INVALID_STRUCT, [](rrc_frame_desc& f, rrc_channel_input&) { f.type = 0; }},
        {"frame.size", RRC_ERROR_INVALID_STRUCT, [](rrc_frame_desc& f, rrc_channel_input&) { f.size = 3; }},
        {"frame.depth", RRC_ERROR_MISSING_INPUT, [](rrc_frame_desc& f, rrc_channel_input&) { f.depth = nullptr; }},
        {"frame.reprojection", RRC_ERROR_MISSING_INPUT, [](rrc_frame_desc& f, rrc_channel_input&) { f.reprojection = nullptr; }},
        {"frame.nocache", RRC_ERROR_MISSING_INPUT, [](rrc_frame_desc& f, rrc_channel_input&) { f.nocache = nullptr; }},
        {"frame.channel_count", RRC_ERROR_SIZE_MISMATCH, [](rrc_frame_desc& f, rrc_channel_input&) { f.channel_count = 2; }},
        {"frame.channels", RRC_ERROR_MISSING_INPUT, [](rrc_frame_desc& f, rrc_channel_input&) { f.channels = nullptr; }},
        {"frame.jitter", RRC_ERROR_INVALID_ARGUMENT, [](rrc_frame_desc& f, rrc_channel_input&) { f.jitter[1] = kNaN; }},
        {"frame.jitter", RRC_ERROR_INVALID_ARGUMENT, [](rrc_frame_desc& f, rrc_channel_input&) { f.prev_jitter[0] = 3.0f; }},
        {"samples", RRC_ERROR_MISSING_INPUT, on_input([](rrc_channel_input& i) { i.samples = nullptr; })},
        {"confidence", RRC_ERROR_MISSING_INPUT, on_input([](rrc_channel_input& i) { i.confidence = nullptr; })},
        {"fallback", RRC_ERROR_MISSING_INPUT, on_input([](rrc_channel_input& i) { i.fallback = nullptr; })},
        {"frame.channels[0].type", RRC_ERROR_INVALID_STRUCT, on_input([](rrc_channel_input& i) { i.type = 1; })},
    };
    // A first good frame, so a later failure has history to preserve.
    FrameResult before = ctx.run(good());
    for (auto& c : cases) {
        rrc_frame_desc f = good();
        c.mutate(f, bad_in);
        std::vector<float> out(W * H, -7.0f);
        std::vector<uint8_t> mask(W * H, 0xEE);
        rrc_channel_output co;
        std::memset(&co, 0, sizeof co);
        co.type = RRC_STRUCT_TYPE_CHANNEL_OUTPUT;
        co.size = sizeof co;
        co.values = out.data();
        rrc_frame_output o;
        std::memset(&o, 0, sizeof o);
        o.type = RRC_STRUCT_TYPE_FRAME_OUTPUT;
        o.size = sizeof o;
        o.mask = mask.data();
        o.channel_count = 1;
        o.channels = &co;
        o.stats.hits = 4242;
        EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), c.code) << c.field;
        EXPECT_NE(std::string(rrc_context_last_error(ctx.get())).find(c.field), std::string::npos)
            << c.field << " vs " << rrc_context_last_error(ctx.get());
        EXPECT_EQ(out, std::vector<float>(W * H, -7.0f)) << c.field;
        EXPECT_EQ(mask, std::vector<uint8_t>(W * H, 0xEE)) << c.field;
        EXPECT_EQ(o.stats.hits, 4242u) << c.field;
    }
    // The history survived every refused frame: a static frame now hits everywhere.
    FrameResult after = ctx.run(good());
    EXPECT_EQ(after.stats.hits, (uint64_t)W * H);
    EXPECT_EQ(after.age[0], std::vector<uint16_t>(W * H, 2));
}

TEST(Api, WrongOutputDescriptionsAreRefused) {
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f)};
    rrc_context_desc d = context_desc(4, 4, channels);
    d.reprojection = RRC_REPROJECTION_CAMERA;
    Context ctx(d);
    ASSERT_TRUE(ctx);
    std::vector<float> depth(16, 0.5f), s(16, 1.0f), w(16);
    rrc_channel_input in = channel_input(s.data());
    rrc_frame_desc f = frame_desc();
    f.depth = depth.data();
    for (int i = 0; i < 16; i += 5) f.view_proj[i] = f.prev_view_proj[i] = 1.0;
    f.channel_count = 1;
    f.channels = &in;
    rrc_channel_output co;
    std::memset(&co, 0, sizeof co);
    co.type = RRC_STRUCT_TYPE_CHANNEL_OUTPUT;
    co.size = sizeof co;
    co.weight = w.data();  // the channel has no confidence
    rrc_frame_output o;
    std::memset(&o, 0, sizeof o);
    o.type = RRC_STRUCT_TYPE_FRAME_OUTPUT;
    o.size = sizeof o;
    o.channel_count = 1;
    o.channels = &co;
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("output.channels[0].weight"), std::string::npos) << rrc_last_error();
    o.channel_count = 3;
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_ERROR_SIZE_MISMATCH);
    f.view_proj[3] = std::numeric_limits<double>::infinity();
    o.channel_count = 0;
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("view_proj"), std::string::npos);
}

// A view lobe (0.7) reads the frame's camera whatever the source: a PREV_CLIP
// frame without an invertible view_proj, or with a non-finite eye, is refused
// naming the field, and the refused frame leaves the history as it was.
// One 4x4 PREV_CLIP frame of a still surface at depth 0.5 (each pixel's own
// clip position), one channel of constant samples, its age read back.
struct StillFrame {
    std::vector<float> depth = std::vector<float>(16, 0.5f), s = std::vector<float>(16, 1.0f), clip = std::vector<float>(16 * 4);
    std::vector<uint16_t> age = std::vector<uint16_t>(16);
    rrc_channel_input in;
    rrc_frame_desc f = frame_desc();
    rrc_channel_output co = rrc_host::rrc_struct<rrc_channel_output>(RRC_STRUCT_TYPE_CHANNEL_OUTPUT);
    rrc_frame_output o = rrc_host::rrc_struct<rrc_frame_output>(RRC_STRUCT_TYPE_FRAME_OUTPUT);
    StillFrame() : in(channel_input(s.data())) {
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                float* c = &clip[(j * 4 + i) * 4];
                c[0] = (i + 0.5f) / 2.0f - 1.0f, c[1] = (j + 0.5f) / 2.0f - 1.0f, c[2] = 0.5f, c[3] = 1.0f;
            }
        f.depth = depth.data();
        f.reprojection = clip.data();
        f.channel_count = 1;
        f.channels = &in;
        co.age = age.data();
        o.channel_count = 1;
        o.channels = &co;
    }
    StillFrame(const StillFrame&) = delete;
};

TEST(Api, AViewLobeNeedsTheFramesCamera) {
    std::vector<rrc_channel_desc> channels = {channel("env", 1, 0.8f)};
    channels[0].view_lobe = 0.05f;
    Context ctx(context_desc(4, 4, channels));
    ASSERT_TRUE(ctx);
    StillFrame still;
    rrc_frame_desc& f = still.f;
    rrc_frame_output& o = still.o;
    std::vector<uint16_t>& age = still.age;
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_ERROR_INVALID_ARGUMENT) << "view_proj all zero";
    EXPECT_NE(std::string(rrc_last_error()).find("frame.view_proj"), std::string::npos) << rrc_last_error();
    for (int i = 0; i < 16; i += 5) f.view_proj[i] = 1.0;
    f.camera_position[0] = f.prev_camera_position[0] = 5.0;  // the eye did not move: theta = 0 caps nothing
    ASSERT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_SUCCESS) << rrc_last_error();
    ASSERT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(age, std::vector<uint16_t>(16, 2));
    f.prev_camera_position[0] = 0.0, f.prev_camera_position[1] = 5.0;
    f.prev_camera_position[2] = std::numeric_limits<double>::quiet_NaN();
    std::fill(age.begin(), age.end(), 0xEEEE);
    EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("camera_position"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(age, std::vector<uint16_t>(16, 0xEEEE)) << "a refused frame writes nothing";
    f.prev_camera_position[2] = 0.0;
    ASSERT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_SUCCESS) << rrc_last_error();
    // The eyes sit 5 units apart beside a surface ~1 unit away: theta is
    // about 1.4 rad, far wider than the lobe, so every history is dropped.
    EXPECT_EQ(age, std::vector<uint16_t>(16, 1)) << "the refused frame left the history (age 2) and the lobe caps it at 0";
}

TEST(Api, TheLightingsTurnAddsToTheViewTurnAndIsRefusedOutOfRange) {
    std::vector<rrc_channel_desc> channels = {channel("env", 1, 0.8f)};
    channels[0].view_lobe = 0.05f;
    Context ctx(context_desc(4, 4, channels));
    std::vector<rrc_channel_desc> plain_channels = {channel("s", 1, 0.8f)};
    Context plain(context_desc(4, 4, plain_channels));
    ASSERT_TRUE(ctx && plain);
    StillFrame still;
    rrc_frame_desc& f = still.f;
    rrc_frame_output& o = still.o;
    std::vector<uint16_t>& age = still.age;
    for (int i = 0; i < 16; i += 5) f.view_proj[i] = 1.0;
    f.camera_position[0] = f.prev_camera_position[0] = 5.0;  // the eye did not move: theta = 0
    for (int t = 0; t < 4; ++t) ASSERT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(age, std::vector<uint16_t>(16, 4)) << "a still eye and still lighting cap nothing";
    for (float bad : {-0.01f, 3.5f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        f.lighting_turn = bad;
        std::fill(age.begin(), age.end(), 0xEEEE);
        EXPECT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_ERROR_INVALID_ARGUMENT) << bad;
        EXPECT_NE(std::string(rrc_last_error()).find("frame.lighting_turn"), std::string::npos) << rrc_last_error();
        EXPECT_EQ(age, std::vector<uint16_t>(16, 0xEEEE)) << "a refused frame writes nothing";
    }
    // theta = 0, phi = alpha / 2.5: the cap floor(alpha / phi) = 2 on the history of age 4
    // the refused frames left; the stored age is 2 + 1.
    f.lighting_turn = 0.02f;
    ASSERT_EQ(rrc_frame_run(ctx.get(), &f, &o), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(age, std::vector<uint16_t>(16, 3));
    // A turn without a view lobe to apply it to is a mistake, not ignored.
    EXPECT_EQ(rrc_frame_run(plain.get(), &f, &o), RRC_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(rrc_last_error()).find("no channel has a view_lobe"), std::string::npos) << rrc_last_error();
}

TEST(Api, DeviceNameIsQueryable) {
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f)};
    Context ctx(context_desc(4, 4, channels));
    ASSERT_TRUE(ctx);
    char name[256];
    ASSERT_EQ(rrc_context_device_name(ctx.get(), name, sizeof name), RRC_SUCCESS);
    EXPECT_NE(std::string(name).find("llvmpipe"), std::string::npos) << "tests must run on lavapipe, got " << name;
    char tiny[2];
    EXPECT_EQ(rrc_context_device_name(ctx.get(), tiny, sizeof tiny), RRC_ERROR_INVALID_ARGUMENT);
}

TEST(Api, UnknownDeviceNameFailsClearly) {
    std::vector<rrc_channel_desc> channels = {channel("s", 1, 0.5f)};
    rrc_context_desc d = context_desc(4, 4, channels);
    d.device_name = "no such device 42";
    rrc_context* ctx = nullptr;
    EXPECT_EQ(rrc_context_create(&d, &ctx), RRC_ERROR_DEVICE);
    EXPECT_EQ(ctx, nullptr);
    EXPECT_NE(std::string(rrc_last_error()).find("no such device 42"), std::string::npos) << rrc_last_error();
}

}  // namespace

// The shading cache's calls (0.3): bad input is refused with its code and
// field, writes nothing, and leaves the cache as it was.
TEST(Api, ShadingCacheCallsRefuseBadInputAndKeepTheCache) {
    const uint32_t W = 8, H = 6, N = W * H;
    std::vector<rrc_channel_desc> channels = {channel("shade", 1, 0.0f, RRC_HISTORY_FP32, RRC_BLEND_REUSE, RRC_HISTORY_FILTER_NEAREST)};
    rrc_context_desc d = context_desc(W, H, channels);
    d.reprojection = RRC_REPROJECTION_CAMERA;
    Context ctx(d);
    ASSERT_TRUE(ctx);
    std::vector<float> depth(N, 0.5f), s(N);
    for (uint32_t i = 0; i < N; ++i) s[i] = (float)i;
    rrc_channel_input in = channel_input(s.data());
    rrc_frame_desc f = frame_desc();
    f.depth = depth.data();
    for (int i = 0; i < 16; ++i) f.view_proj[i] = f.prev_view_proj[i] = (i % 5 == 0) ? 1.0 : 0.0;
    rrc_resolve_desc rd = rrc_host::rrc_struct<rrc_resolve_desc>(RRC_STRUCT_TYPE_RESOLVE_DESC);
    rd.channel_count = 1;
    rd.channels = &in;

    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &rd, nullptr), RRC_ERROR_INVALID_ARGUMENT) << "nothing classified yet";
    EXPECT_NE(std::string(rrc_last_error()).find("classify"), std::string::npos) << rrc_last_error();

    // First frame: every pixel misses, every quad (4 x 3) is listed.
    std::vector<uint8_t> mask(N, 0xEE);
    std::vector<uint32_t> quads(RRC_QUAD_LIST_BYTES(W, H) / 4, 0xEEEEEEEEu);
    rrc_classify_output co = rrc_host::rrc_struct<rrc_classify_output>(RRC_STRUCT_TYPE_CLASSIFY_OUTPUT);
    co.mask = mask.data();
    co.quads = quads.data();
    co.quad_capacity = 11;  // one short
    co.quad_count = 77;
    EXPECT_EQ(rrc_frame_classify(ctx.get(), &f, &co), RRC_ERROR_SIZE_MISMATCH);
    EXPECT_NE(std::string(rrc_last_error()).find("quad_capacity"), std::string::npos) << rrc_last_error();
    EXPECT_EQ(co.quad_count, 77u) << "nothing written";
    EXPECT_EQ(mask[0], 0xEE);
    EXPECT_EQ(quads[0], 0xEEEEEEEEu);
    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &rd, nullptr), RRC_ERROR_INVALID_ARGUMENT) << "a refused classify classifies nothing";

    co.quad_capacity = 12;
    rrc_classify_output bad = co;
    bad.type = RRC_STRUCT_TYPE_FRAME_OUTPUT;
    EXPECT_EQ(rrc_frame_classify(ctx.get(), &f, &bad), RRC_ERROR_INVALID_STRUCT);
    rrc_frame_desc no_depth = f;
    no_depth.depth = nullptr;
    EXPECT_EQ(rrc_frame_classify(ctx.get(), &no_depth, &co), RRC_ERROR_MISSING_INPUT);
    ASSERT_EQ(rrc_frame_classify(ctx.get(), &f, &co), RRC_SUCCESS) << rrc_last_error();
    EXPECT_EQ(co.quad_count, 12u);

    rrc_resolve_desc wrong = rd;
    wrong.channel_count = 2;
    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &wrong, nullptr), RRC_ERROR_SIZE_MISMATCH);
    rrc_channel_input no_samples = in;
    no_samples.samples = nullptr;
    wrong = rd;
    wrong.channels = &no_samples;
    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &wrong, nullptr), RRC_ERROR_MISSING_INPUT);
    ASSERT_EQ(rrc_frame_resolve(ctx.get(), &rd, nullptr), RRC_SUCCESS) << "the classification survives refused resolves: " << rrc_last_error();
    EXPECT_EQ(rrc_frame_resolve(ctx.get(), &rd, nullptr), RRC_ERROR_INVALID_ARGUMENT) << "one resolve a classification";

    // The next frame hits everywhere and keeps the first frame's values.
    std::vector<float> other(N, -5.0f);
    rrc_channel_input in2 = channel_input(other.data());
    f.frame_index = 1;
    f.channel_count = 1;
    f.channels = &in2;
    const FrameResult r = ctx.run(f);
    for (uint32_t i = 0; i < N; ++i) {
        EXPECT_EQ(r.mask[i], (uint8_t)RRC_MASK_HIT);
        EXPECT_EQ(r.values[0][i], s[i]) << "a REUSE hit keeps the cached value";
    }
}
