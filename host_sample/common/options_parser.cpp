#include "options_parser.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rrc_host {

std::string quoted(const std::string& text) { return "'" + text + "'"; }

ArgCursor::ArgCursor(int argc, const char* const* argv) {
    for (int i = 1; i < argc; ++i) args_.push_back(argv[i] ? argv[i] : "");
}

bool ArgCursor::next() {
    while (i_ < args_.size()) {
        const std::string& a = args_[i_++];
        has_inline_ = false;
        inline_value_.clear();
        last_value_.clear();
        name_ = a;
        // --opt=value: only for options, so a positional "a=b" stays whole.
        const std::size_t eq = a.find('=');
        if (a.rfind("--", 0) == 0 && eq != std::string::npos) {
            name_ = a.substr(0, eq);
            inline_value_ = a.substr(eq + 1);
            has_inline_ = true;
        }
        bool* common = name_ == "--check-options" ? &check_only_ : name_ == "--help" || name_ == "-h" ? &help_ : nullptr;
        if (common) {
            if (has_inline_) throw OptionError("option " + name_ + " takes no value, got " + quoted(inline_value_));
            *common = true;
            continue;
        }
        return true;
    }
    return false;
}

bool ArgCursor::positional() const { return name_.empty() || name_[0] != '-'; }

bool ArgCursor::match(const char* name) {
    if (name_ != name) return false;
    ++given_[name_];
    return true;
}

bool ArgCursor::flag(const char* name) {
    if (!match(name)) return false;
    if (has_inline_) throw OptionError("option " + name_ + " takes no value, got " + quoted(inline_value_));
    return true;
}

bool ArgCursor::option(const char* name) { return match(name); }

void ArgCursor::once() const {
    if (given(name_) > 1) throw OptionError("option " + name_ + " given more than once");
}

int ArgCursor::given(const std::string& name) const {
    const auto it = given_.find(name);
    return it == given_.end() ? 0 : it->second;
}

std::string ArgCursor::value() {
    if (has_inline_) return last_value_ = inline_value_;
    if (i_ >= args_.size()) throw OptionError("option " + name_ + " needs a value");
    // "--out --quiet" is a forgotten value, not a directory named --quiet.
    if (args_[i_].rfind("--", 0) == 0) throw OptionError("option " + name_ + " needs a value, got the option " + quoted(args_[i_]));
    return last_value_ = args_[i_++];
}

void ArgCursor::fail_value(const std::string& text, const std::string& what) const {
    throw OptionError("option " + name_ + " " + quoted(text) + ": " + what);
}

void ArgCursor::fail(const std::string& what) const { fail_value(last_value_, what); }

void ArgCursor::unknown() const {
    if (positional()) throw OptionError("unexpected argument " + quoted(name_) + " (--help lists the options)");
    throw OptionError("unknown option " + name_ + " (--help lists them)");
}

namespace {

bool read_integer(const std::string& text, long& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtol(text.c_str(), &end, 10);
    return !*end && !errno;
}

bool read_number(const std::string& text, float& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (*end || !std::isfinite(v)) return false;
    out = (float)v;
    return std::isfinite(out);
}

std::string range(double lo, double hi, const char* what) {
    char s[96];
    std::snprintf(s, sizeof s, "expected %s in [%g, %g]", what, lo, hi);
    return s;
}

}  // namespace

long ArgCursor::integer(long lo, long hi) {
    const std::string v = value();
    long x = 0;
    if (!read_integer(v, x) || x < lo || x > hi) fail_value(v, range((double)lo, (double)hi, "an integer"));
    return x;
}

float ArgCursor::number(float lo, float hi) {
    const std::string v = value();
    float x = 0;
    if (!read_number(v, x) || !(x >= lo && x <= hi)) fail_value(v, range(lo, hi, "a number"));
    return x;
}

void ArgCursor::size(uint32_t& width, uint32_t& height, long lo, long hi) {
    const std::string v = value();
    const std::size_t x = v.find('x');
    long w = 0, h = 0;
    if (x == std::string::npos || !read_integer(v.substr(0, x), w) || !read_integer(v.substr(x + 1), h) || w < lo || w > hi || h < lo ||
        h > hi)
        fail_value(v, "expected WxH, each side an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    width = (uint32_t)w;
    height = (uint32_t)h;
}

std::vector<std::string> ArgCursor::names() {
    const std::string v = value();
    std::vector<std::string> items;
    std::size_t pos = 0;
    while (true) {
        const std::size_t comma = v.find(',', pos);
        items.push_back(v.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        if (items.back().empty()) fail_value(v, "expected a comma-separated list without empty items");
        if (comma == std::string::npos) return items;
        pos = comma + 1;
    }
}

std::vector<long> ArgCursor::integers(long lo, long hi) {
    std::vector<long> out;
    for (const std::string& item : names()) {
        long x = 0;
        if (!read_integer(item, x) || x < lo || x > hi) fail_value(item, range((double)lo, (double)hi, "integers"));
        out.push_back(x);
    }
    return out;
}

std::vector<float> ArgCursor::numbers(float lo, float hi) {
    std::vector<float> out;
    for (const std::string& item : names()) {
        float x = 0;
        if (!read_number(item, x) || !(x >= lo && x <= hi)) fail_value(item, range(lo, hi, "numbers"));
        out.push_back(x);
    }
    return out;
}

std::string check_options_help(const char* program) {
    return std::string("  --check-options          check the options as a run would, print \"") + program + ": options ok\" and exit\n";
}

void print_options_ok(const char* program) { std::printf("%s: options ok\n", program); }

int report_option_error(const char* program, const OptionError& e, const std::string& usage, bool usage_on_error) {
    std::fprintf(stderr, "%s: %s\n%s", program, e.what(), usage_on_error ? usage.c_str() : "");
    return 2;
}

int report_help_or_check(const char* program, bool help, bool check_only, const std::string& usage) {
    if (help) {
        std::fputs(usage.c_str(), stdout);
        return 0;
    }
    if (check_only) {
        print_options_ok(program);
        return 0;
    }
    return -1;
}

}  // namespace rrc_host
