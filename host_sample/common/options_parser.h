// The one command-line parser of the host programs (rrc-sample, rrc-sweep,
// rrc-cache, rrc-accumulate, rrc-make-demo-sequence, rrc-bench,
// rrc-blender-check): an argument cursor with typed readers whose every error
// names the option and the value it got, so that each program spells only its
// options, their ranges and its help text (host_sample/testbed/README.md,
// "Checking a command line").
//
//     rrc_host::ArgCursor c(argc, argv);
//     while (c.next()) {
//         if (c.flag("--quiet")) o.quiet = true;
//         else if (c.option("--frames")) o.frames = c.integer(1, 100000);
//         else c.unknown();
//     }
//
// Options take their value as the next argument or after '=' (--frames=8).
// --help (-h) and --check-options are recognised here, for every program:
// help() and check_only() say they were given; with --check-options the
// program stops after its own checks (print_options_ok).
#pragma once

#include "enum_names.h"

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrc_host {

/** A bad command line; what() names the option and the value. */
class OptionError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** "'text'": how messages quote a value. */
std::string quoted(const std::string& text);

class ArgCursor {
public:
    ArgCursor(int argc, const char* const* argv);

    /** Moves to the next argument (taking --help, -h and --check-options); false at the end. */
    bool next();

    /** The current argument, without an "=value" part. */
    const std::string& arg() const { return name_; }
    /** The current argument does not start with '-': a positional argument. */
    bool positional() const;

    /** The current argument is the flag `name`; a flag given "=value" throws. */
    bool flag(const char* name);
    /** The current argument is the option `name`, which takes a value. */
    bool option(const char* name);
    /** Throws "option NAME given more than once" if the current option was given before. */
    void once() const;
    /** How many times `name` was matched so far (flag() or option()). */
    int given(const std::string& name) const;

    /** The current option's value: after '=' or the next argument; "NAME needs a value" if none. */
    std::string value();
    /** The value as an integer / a finite number in [lo, hi]. */
    long integer(long lo, long hi);
    float number(float lo, float hi);
    /** WxH, each side in [lo, hi]. */
    void size(uint32_t& width, uint32_t& height, long lo, long hi);
    /** Comma-separated lists; an empty item is an error. */
    std::vector<std::string> names();
    std::vector<long> integers(long lo, long hi);
    std::vector<float> numbers(float lo, float hi);

    /** One of `table`'s names; the message lists them. */
    template <typename T, std::size_t N>
    T choice(const EnumName<T> (&table)[N]) {
        return pick(table, value());
    }
    /** A comma list of `table`'s names. */
    template <typename T, std::size_t N>
    std::vector<T> choices(const EnumName<T> (&table)[N]) {
        std::vector<T> out;
        for (const std::string& item : names()) out.push_back(pick(table, item));
        return out;
    }

    /** Throws "NAME 'value': what" (the value last taken). */
    [[noreturn]] void fail(const std::string& what) const;
    /** Throws "unknown option --x (--help lists them)", or "unexpected argument" for a positional one. */
    [[noreturn]] void unknown() const;

    /** --check-options was given: validate, print print_options_ok's line, exit 0. */
    bool check_only() const { return check_only_; }
    /** --help or -h was given. */
    bool help() const { return help_; }

private:
    template <typename T, std::size_t N>
    T pick(const EnumName<T> (&table)[N], const std::string& text) const {
        T v{};
        if (!enum_value(table, text, v)) fail_value(text, "expected " + enum_choices(table));
        return v;
    }
    [[noreturn]] void fail_value(const std::string& text, const std::string& what) const;
    bool match(const char* name);

    std::vector<std::string> args_;
    std::size_t i_ = 0;
    std::string name_, inline_value_, last_value_;
    bool has_inline_ = false, check_only_ = false, help_ = false;
    std::map<std::string, int> given_;
};

/** The --help line of --check-options, in the column layout of rrc-sample's and rrc-sweep's help. */
std::string check_options_help(const char* program);

/** "PROGRAM: options ok" on stdout: what --check-options prints when every option passed. */
void print_options_ok(const char* program);

/** The programs' common start.  Runs `parse` (which throws OptionError): on an
 *  error prints "PROGRAM: message" (and `usage` if usage_on_error) to stderr
 *  and returns 2; with --help prints `usage`, returns 0; with --check-options
 *  prints "PROGRAM: options ok", returns 0; otherwise returns -1: run. */
template <typename Options, typename Parse>
int parse_command_line(const char* program, Parse parse, const std::string& usage, Options& out, bool usage_on_error = false);

int report_option_error(const char* program, const OptionError& e, const std::string& usage, bool usage_on_error);
int report_help_or_check(const char* program, bool help, bool check_only, const std::string& usage);

template <typename Options, typename Parse>
int parse_command_line(const char* program, Parse parse, const std::string& usage, Options& out, bool usage_on_error) {
    try {
        out = parse();
    } catch (const OptionError& e) {
        return report_option_error(program, e, usage, usage_on_error);
    }
    return report_help_or_check(program, out.help, out.check_options, usage);
}

}  // namespace rrc_host
