// The host programs' one option parser (options_parser.h): values in both
// spellings, typed readers, and error messages that name the option and the
// value it got.
#include "options_parser.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using rrc_host::ArgCursor;
using rrc_host::OptionError;

struct Parsed {
    long frames = 0;
    float lambda = 0;
    uint32_t width = 0, height = 0;
    std::vector<long> taps;
    std::vector<float> lambdas;
    rrc_blend blend = RRC_BLEND_FIXED;
    std::vector<rrc_blend> blends;
    bool quiet = false, check = false, help = false;
    std::vector<std::string> positional;
};

Parsed parse(std::vector<const char*> args) {
    args.insert(args.begin(), "prog");
    ArgCursor c((int)args.size(), args.data());
    Parsed p;
    while (c.next()) {
        if (c.flag("--quiet"))
            p.quiet = true;
        else if (c.option("--frames"))
            c.once(), p.frames = c.integer(1, 100);
        else if (c.option("--lambda"))
            p.lambda = c.number(0.0f, 0.99f);
        else if (c.option("--size"))
            c.size(p.width, p.height, 8, 8192);
        else if (c.option("--taps"))
            p.taps = c.integers(1, 64);
        else if (c.option("--lambdas"))
            p.lambdas = c.numbers(0.0f, 0.99f);
        else if (c.option("--blend"))
            p.blend = c.choice(rrc_host::kBlendNames);
        else if (c.option("--blends"))
            p.blends = c.choices(rrc_host::kBlendNames);
        else if (c.positional())
            p.positional.push_back(c.arg());
        else
            c.unknown();
    }
    p.check = c.check_only();
    p.help = c.help();
    return p;
}

// The error of parsing `args`; fails the test if there is none.
std::string error_of(std::vector<const char*> args) {
    try {
        parse(std::move(args));
    } catch (const OptionError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
}

void expect_names(const std::string& error, const std::vector<std::string>& fragments) {
    for (const std::string& f : fragments) EXPECT_NE(error.find(f), std::string::npos) << "'" << error << "' lacks '" << f << "'";
}

TEST(Options, ReadsEveryKindInBothSpellings) {
    const Parsed p = parse({"--frames", "12", "--lambda=0.5", "--size", "64x32", "--taps=1,2,4", "--lambdas", "0.6,0.8", "--blend",
                            "age_aware", "--blends=fixed,running_mean", "--quiet", "DIR"});
    EXPECT_EQ(p.frames, 12);
    EXPECT_FLOAT_EQ(p.lambda, 0.5f);
    EXPECT_EQ(p.width, 64u);
    EXPECT_EQ(p.height, 32u);
    EXPECT_EQ(p.taps, (std::vector<long>{1, 2, 4}));
    EXPECT_EQ(p.lambdas, (std::vector<float>{0.6f, 0.8f}));
    EXPECT_EQ(p.blend, RRC_BLEND_AGE_AWARE);
    EXPECT_EQ(p.blends, (std::vector<rrc_blend>{RRC_BLEND_FIXED, RRC_BLEND_RUNNING_MEAN}));
    EXPECT_TRUE(p.quiet);
    EXPECT_EQ(p.positional, std::vector<std::string>{"DIR"});
    EXPECT_FALSE(p.check);
}

TEST(Options, CheckOptionsIsEveryProgramsFlag) {
    EXPECT_TRUE(parse({"--check-options", "--frames", "3"}).check);
    EXPECT_TRUE(parse({"-h"}).help);
    EXPECT_TRUE(parse({"--frames", "3", "--help"}).help);
    expect_names(error_of({"--help=yes"}), {"--help takes no value"});
    expect_names(error_of({"--check-options=1"}), {"--check-options", "'1'"});
}

TEST(Options, ErrorsNameTheOptionAndTheValue) {
    expect_names(error_of({"--frames", "0"}), {"--frames", "'0'", "[1, 100]"});
    expect_names(error_of({"--frames", "12x"}), {"--frames", "'12x'"});
    expect_names(error_of({"--frames=101"}), {"--frames", "'101'"});
    expect_names(error_of({"--lambda", "1.5"}), {"--lambda", "'1.5'", "a number"});
    expect_names(error_of({"--lambda", "nan"}), {"--lambda", "'nan'"});
    expect_names(error_of({"--size", "64"}), {"--size", "'64'", "WxH"});
    expect_names(error_of({"--size", "4x32"}), {"--size", "'4x32'"});
    expect_names(error_of({"--taps", "1,,2"}), {"--taps", "'1,,2'"});
    expect_names(error_of({"--taps", "1,99"}), {"--taps", "'99'"});
    expect_names(error_of({"--lambdas", "0.5,x"}), {"--lambdas", "'x'"});
    expect_names(error_of({"--blend", "mean"}), {"--blend", "'mean'", "fixed, age_aware or running_mean"});
    expect_names(error_of({"--blends", "fixed,mean"}), {"--blends", "'mean'"});
}

TEST(Options, MissingValuesUnknownOptionsAndRepeats) {
    expect_names(error_of({"--frames"}), {"--frames needs a value"});
    expect_names(error_of({"--frames", "--quiet"}), {"--frames needs a value", "'--quiet'"});
    expect_names(error_of({"--quiet=yes"}), {"--quiet takes no value", "'yes'"});
    expect_names(error_of({"--bogus"}), {"unknown option --bogus (--help lists them)"});
    expect_names(error_of({"--bogus=3"}), {"unknown option --bogus "});
    expect_names(error_of({"--frames", "2", "--frames=3"}), {"--frames given more than once"});
}

}  // namespace
