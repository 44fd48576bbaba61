#!/usr/bin/env python3
"""No test asserts on a clock: timings are printed, and only their presence is checked.

A run on a shared or loaded machine, or under the sanitizers, takes any time,
so an assertion on a measured time fails for reasons that are not a defect.
This scans the sources of tests/, host_sample/ and bench/ (.cpp .h .c .cmake
CMakeLists.txt .py) and fails on an assertion that compares a time:

  C, C++   an assertion macro (any upper-case name holding EXPECT, ASSERT,
           CHECK or REQUIRE, and assert), its arguments without comments,
           string literals or the streamed message;
  CMake    if(), elseif() and while() conditions;
  Python   assert statements, unittest's self.assert*() and calls of a
           function named check or expect.

A time is recognised by the words of its names (identifiers split at '_', at
camelCase and at digits; in CMake and Python also the JSON or dict key a
value is read by):

  clock words   chrono, clock (steady_clock, system_clock, ...), elapsed,
                timestamp(s), CMake's TIMESTAMP: always a measured
                value, so any comparison of one fails the scan, equality
                included;
  timing words  ms, us, ns, msec, usec, nsec, sec, secs, seconds,
                timing(s), duration(s), median(s), fps, latency: measured, or
                made up in a time model's test.  An ordering of one fails the
                scan (<, <=, >, >=, !=; _LT _LE _GT _GE _NE; LESS, GREATER,
                ...; a tolerance wider than 1e-6, a band, is two orderings).
                Equality does not (_EQ, _DOUBLE_EQ, ==, EQUAL, _NEAR or
                abs(a - b) < eps with eps up to 1e-6): that is how a time
                model is tested on made-up timings, and a measured time never
                equals a constant.

A value computed from a time is a time too: in C and C++ a variable assigned
from an expression with a clock word, within the block it is assigned in; in
CMake a variable that set, string, math, list, foreach or file sets from a
time or a timing word.

What a test may check of a timing is its presence: the field exists, it parses
as a number, it is finite, its line is printed; not its value.  There is no
opt-out marker: a test that needs one asserts on a time.

  timed_assertions.py ROOT          scan ROOT/tests, ROOT/host_sample and ROOT/bench; exit 1 on a finding
  timed_assertions.py --self-test   the detectors on known cases; exit 1 if one answers wrong
"""

import ast
import os
import re
import sys

FOLDERS = ("tests", "host_sample", "bench")
SUFFIXES = (".cpp", ".h", ".c", ".cmake", ".py")

CLOCK_WORDS = {"chrono", "clock", "elapsed", "timestamp", "timestamps"}  # not "now": a state is named so too
TIMING_WORDS = {"ms", "us", "ns", "msec", "usec", "nsec", "sec", "secs", "seconds", "timing", "timings",
                "duration", "durations", "median", "medians", "fps", "latency"}


def words(name):
    """The lower-case words of an identifier: split at '_', camelCase and digits."""
    return {p.lower() for p in re.findall(r"[A-Z]+(?=[A-Z][a-z])|[A-Z]?[a-z]+|[A-Z]+", name)}


def kind_of_names(names):
    """'clock', 'timing' or None: the strongest kind of time among the names."""
    found = None
    for name in names:
        w = words(name)
        if w & CLOCK_WORDS:
            return "clock"
        if w & TIMING_WORDS:
            found = "timing"
    return found


def identifiers(text):
    return re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text)


def flagged(kind, comparison):
    """A clock compared in any way, or a timing ordered."""
    return (kind == "clock" and comparison is not None) or (kind == "timing" and comparison == "ordering")


def closing(text, open_at, quotes=""):
    """Index of the parenthesis closing the one at open_at (none inside the quotes given), or -1."""
    depth, quoted = 0, None
    j = open_at
    while j < len(text):
        c = text[j]
        if quoted:
            if c == "\\":
                j += 1
            elif c == quoted:
                quoted = None
        elif c in quotes:
            quoted = c
        elif c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth == 0:
                return j
        j += 1
    return -1


def line_of(text, at):
    return text.count("\n", 0, at) + 1


# ------------------------------------------------------------------ C, C++

def strip_c(text):
    """Comments and string/char literals blanked; newlines kept, so line numbers hold."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif c == '"' and i > 0 and text[i - 1] == "R" and re.match(r'"([^()\s\\]{0,16})\(', text[i:]):
            delim = re.match(r'"([^()\s\\]{0,16})\(', text[i:]).group(1)
            end = text.find(")" + delim + '"', i)
            j = n if end < 0 else end + len(delim) + 2
        elif c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):  # 1'000 is a digit separator
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
        else:
            out.append(c)
            i += 1
            continue
        out.append(re.sub(r"[^\n]", " ", text[i:j]))
        i = j
    return "".join(out)


ASSERTION_C = re.compile(r"\b([A-Z_]*(?:EXPECT|ASSERT|CHECK|REQUIRE)[A-Z_]*|assert)\s*\(")
DEFINE_C = re.compile(r"^\s*#\s*define\s*$")
ORDERING_SUFFIX = re.compile(r"_(LT|LE|GT|GE|NE)$")
EQUALITY_SUFFIX = re.compile(r"_(EQ|STREQ|STRNE|STRCASEEQ|STRCASENE)$")
# A tolerance up to this is an equality (a model's arithmetic); a wider one is a band, two orderings.
EQUALITY_TOLERANCE = 1e-6
NO_COMPARISON_SUFFIX = re.compile(r"_(THROW|NO_THROW|ANY_THROW|NO_FATAL_FAILURE|DEATH|EXIT)$")
# An operator between spaces: 'a < b' compares, 'duration<double>' is a template.
ORDERING_C = re.compile(r"\s(?:<|>|<=|>=|!=)\s")
EQUALITY_C = re.compile(r"==")
ASSIGNMENT_C = re.compile(r"\b([A-Za-z_][A-Za-z0-9_]*)\s*(?:\[[^\]]*\]\s*)?[-+*/]?=(?!=)([^;{}]*);")


def tight(tolerance):
    """Whether a tolerance (source text) is a number no wider than EQUALITY_TOLERANCE."""
    try:
        return abs(float(tolerance.strip().rstrip("fFlL"))) <= EQUALITY_TOLERANCE
    except ValueError:
        return False


def top_level_split(args):
    """Macro arguments split at the commas outside brackets."""
    parts, depth, start = [], 0, 0
    for j, c in enumerate(args):
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(args[start:j])
            start = j + 1
    return parts + [args[start:]]


def c_comparison(name, args):
    """'ordering', 'equality' or None: what an assertion macro's arguments compare."""
    if NO_COMPARISON_SUFFIX.search(name):
        return None
    if ORDERING_SUFFIX.search(name):
        return "ordering"
    if EQUALITY_SUFFIX.search(name):
        return "equality"
    if name.endswith("_NEAR"):
        return "equality" if tight(top_level_split(args)[-1]) else "ordering"
    spaced = " " + " ".join(args.split()) + " "
    if ORDERING_C.search(spaced):
        return "ordering"
    if EQUALITY_C.search(args):
        return "equality"
    return None


def block_end(code, at):
    """End of the innermost {...} block around position at (the file's end at top level)."""
    depth = 0
    for j in range(at, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            if depth == 0:
                return j
            depth -= 1
    return len(code)


def clock_variables(code):
    """(name, start, end): variables assigned from a clock, and the span of code they hold it in."""
    spans = []
    changed = True
    while changed:
        changed = False
        for m in ASSIGNMENT_C.finditer(code):
            ids = identifiers(m.group(2))
            if kind_of_names(ids) == "clock" or any(v in ids and s <= m.start() < e for v, s, e in spans):
                entry = (m.group(1), m.start(), block_end(code, m.start()))
                if entry not in spans:
                    spans.append(entry)
                    changed = True
    return spans


def scan_c(text):
    """[(line, assertion)] of the timed assertions in C or C++ source."""
    code = strip_c(text)
    spans = clock_variables(code)
    found = []
    for m in ASSERTION_C.finditer(code):
        if DEFINE_C.match(code[code.rfind("\n", 0, m.start()) + 1:m.start()]):
            continue  # the macro's own definition
        close_at = closing(code, m.end() - 1)
        if close_at < 0:
            continue
        args = code[m.end():close_at]
        ids = identifiers(args)
        kind = kind_of_names(ids)
        if any(v in ids and s <= m.start() < e for v, s, e in spans):
            kind = "clock"
        if flagged(kind, c_comparison(m.group(1), args)):
            found.append((line_of(code, m.start()), f"{m.group(1)}({' '.join(args.split())})"))
    return found


# ------------------------------------------------------------------ CMake

def strip_cmake(text):
    """Comments blanked; quoted arguments kept (variable references live in them)."""
    out = []
    for line in text.split("\n"):
        quoted, i = False, 0
        while i < len(line):
            if line[i] == "\\":
                i += 2
                continue
            if line[i] == '"':
                quoted = not quoted
            elif line[i] == "#" and not quoted and not line.startswith("[", i + 1):
                line = line[:i]
                break
            i += 1
        out.append(line)
    return "\n".join(out)


CMAKE_COMMAND = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*\(", re.M)
CMAKE_ORDERING = {"LESS", "GREATER", "LESS_EQUAL", "GREATER_EQUAL", "VERSION_LESS", "VERSION_GREATER",
                  "VERSION_LESS_EQUAL", "VERSION_GREATER_EQUAL", "STRLESS", "STRGREATER", "STRLESS_EQUAL",
                  "STRGREATER_EQUAL"}
CMAKE_EQUALITY = {"EQUAL", "VERSION_EQUAL", "STREQUAL"}


def cmake_commands(code):
    """(command, arguments, line) of each command call."""
    pos = 0
    while True:
        m = CMAKE_COMMAND.search(code, pos)
        if not m:
            return
        close_at = closing(code, m.end() - 1, quotes='"')
        if close_at < 0:
            return
        yield m.group(1).lower(), code[m.end():close_at], line_of(code, m.start())
        pos = close_at + 1


def cmake_tokens(args):
    return re.findall(r'"(?:\\.|[^"\\])*"|[^\s()]+', args)


def cmake_kind(tokens, timed):
    """The kind of time the tokens carry: variables already timed, or words of their names."""
    kind = None
    for tok in tokens:
        for ident in identifiers(tok):
            k = timed.get(ident) or kind_of_names([ident])
            if k == "clock":
                return "clock"
            kind = kind or k
    return kind


def cmake_assignment(command, tokens):
    """(variables set, the tokens they are set from, clock) for a command that sets variables."""
    mode = tokens[0] if tokens else ""
    if command in ("set", "foreach"):
        return tokens[:1], tokens[1:], False
    if command == "math" and len(tokens) > 1:
        return tokens[1:2], tokens[2:], False
    if command == "string" and len(tokens) > 1:
        if mode == "TIMESTAMP":
            return tokens[1:2], [], True
        if mode in ("JSON", "APPEND", "PREPEND", "CONCAT", "RANDOM"):
            return tokens[1:2], tokens[2:], False
        if mode == "JOIN" and len(tokens) > 2:
            return tokens[2:3], tokens[3:], False
        if mode == "REGEX" and len(tokens) > 3:
            at = 4 if tokens[1] == "REPLACE" else 3
            return tokens[at:at + 1], tokens[at + 1:] + tokens[3:at], False
        if mode == "REPLACE" and len(tokens) > 3:
            return tokens[3:4], tokens[1:3] + tokens[4:], False
        return tokens[-1:], tokens[1:-1], False
    if command == "list" and len(tokens) > 1:
        if mode in ("GET", "LENGTH", "JOIN", "SUBLIST", "FIND"):
            return tokens[-1:], tokens[1:-1], False
        if mode in ("POP_FRONT", "POP_BACK"):
            return tokens[2:], tokens[1:2], False
        return tokens[1:2], tokens[2:], False
    if command == "file" and len(tokens) > 2:
        if mode == "TIMESTAMP":
            return tokens[2:3], [], True
        if mode in ("READ", "STRINGS", "SIZE"):
            return tokens[2:3], tokens[1:2], False
    return [], [], False


def scan_cmake(text):
    """[(line, condition)] of the timed comparisons in a CMake script."""
    code = strip_cmake(text)
    timed = {}  # variable -> 'clock' or 'timing'
    found = []
    for command, args, line in cmake_commands(code):
        tokens = cmake_tokens(args)
        outs, sources, clock = cmake_assignment(command, tokens)
        for out in outs:
            out = out.strip('"')
            kind = "clock" if clock else cmake_kind(sources, timed) or kind_of_names([out])
            if kind and timed.get(out) != "clock":
                timed[out] = kind
        if command not in ("if", "elseif", "while"):
            continue
        for i, tok in enumerate(tokens):
            comparison = "ordering" if tok in CMAKE_ORDERING else "equality" if tok in CMAKE_EQUALITY else None
            if comparison and flagged(cmake_kind(tokens[max(0, i - 1):i] + tokens[i + 1:i + 2], timed), comparison):
                found.append((line, f"{command}({' '.join(args.split())})"))
                break
    return found


# ------------------------------------------------------------------ Python

def py_names(node):
    """Names, attributes and string subscripts ('time_ms' of row['time_ms']) under a node."""
    names = []
    for sub in ast.walk(node):
        if isinstance(sub, ast.Name):
            names.append(sub.id)
        elif isinstance(sub, ast.Attribute):
            names.append(sub.attr)
        elif isinstance(sub, ast.Subscript):
            key = sub.slice.value if isinstance(sub.slice, ast.Index) else sub.slice  # ast.Index: before 3.9
            if isinstance(key, ast.Constant) and isinstance(key.value, str):
                names.append(key.value)
    return names


def py_call_name(node):
    return getattr(node.func, "attr", getattr(node.func, "id", "")) if isinstance(node, ast.Call) else ""


def py_timed(expr):
    """Whether the expression compares a time (abs(a - b) < eps is an equality)."""
    for sub in ast.walk(expr):
        if not isinstance(sub, ast.Compare):
            continue
        if any(isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.NotEq)) for op in sub.ops):
            comparison = "ordering"
            operands = [sub.left] + sub.comparators
            if len(operands) == 2 and any(py_call_name(o) in ("abs", "fabs") for o in operands) and any(
                    isinstance(o, ast.Constant) and isinstance(o.value, (int, float)) and tight(str(o.value))
                    for o in operands):
                comparison = "equality"
        elif any(isinstance(op, ast.Eq) for op in sub.ops):
            comparison = "equality"
        else:
            continue  # is, in: presence
        if flagged(kind_of_names(py_names(sub)), comparison):
            return True
    return False


PY_ORDERING = {"assertLess", "assertLessEqual", "assertGreater", "assertGreaterEqual", "assertNotEqual",
               "assertNotAlmostEqual"}
PY_EQUALITY = {"assertEqual", "assertAlmostEqual", "assertEquals"}


def scan_python(text):
    """[(line, assertion)] of the timed assertions in a Python script."""
    try:
        tree = ast.parse(text)
    except SyntaxError as err:
        return [(err.lineno or 0, f"cannot parse: {err.msg}")]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assert):
            if py_timed(node.test):
                found.append((node.lineno, "assert " + ast.unparse(node.test)))
            continue
        func = py_call_name(node)
        if func in PY_ORDERING or func in PY_EQUALITY:
            kind = kind_of_names([n for a in node.args[:2] for n in py_names(a)])
            timed = flagged(kind, "ordering" if func in PY_ORDERING else "equality")
        elif func.startswith("assert") or func in ("check", "expect"):
            timed = bool(node.args) and py_timed(node.args[0])
        else:
            continue
        if timed:
            found.append((node.lineno, ast.unparse(node)))
    return found


# ------------------------------------------------------------------ the scan

def scan_file(path):
    with open(path, encoding="utf-8", errors="replace") as handle:
        text = handle.read()
    if path.endswith(".py"):
        return scan_python(text)
    if path.endswith(".cmake") or os.path.basename(path) == "CMakeLists.txt":
        return scan_cmake(text)
    return scan_c(text)


def scan(root):
    findings, files = [], 0
    for folder in FOLDERS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, folder)):
            dirnames.sort()
            for f in sorted(filenames):
                if f.endswith(SUFFIXES) or f == "CMakeLists.txt":
                    path = os.path.join(dirpath, f)
                    files += 1
                    for line, what in scan_file(path):
                        findings.append(f"{os.path.relpath(path, root)}:{line}: {what}")
    return findings, files


# ------------------------------------------------------------------ self-test

# (language, source, findings expected)
SELF_TEST_CASES = [
    # Timed: the three assertions this scan replaced, as they were written.
    ("c", """
TEST(SceneFrame, RenderIsCheap) {
    Scene s(SceneConfig{});
    const auto t0 = std::chrono::steady_clock::now();
    for (int t = 0; t < 5; ++t) (void)s.render(t);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / 5;
    std::printf("96x64 frame: %.2f ms\\n", ms);
    EXPECT_LT(ms, 500.0);  // loose: sanitizer builds are ~10x slower
}""", 1),
    ("c", "EXPECT_GT(r.frames[5].timings.rrc, 0.0);", 1),
    ("cmake", """
foreach(key kernel_ms_median roof_ms_median ratio_median kernel_ms_min roof_ms_min wall_ms_median)
  string(JSON v GET "${json}" rows ${i} ${key})
  if(NOT v GREATER 0)
    message(FATAL_ERROR "${name}: ${key} = ${v}, not positive")
  endif()
endforeach()""", 1),
    ("cmake", """
  if(name STREQUAL "standalone")
    string(JSON fps GET "${json}" rows ${i} standalone_fps)
    string(JSON sb GET "${json}" rows ${i} standalone_bytes)
    if(NOT fps GREATER 0 OR NOT sb GREATER 0)
      message(FATAL_ERROR "standalone: fps ${fps}, bytes ${sb}")
    endif()
  endif()""", 1),
    # Timed: clocks under other names, equality on a clock, other languages' forms.
    ("c", """
void f() {
    auto start = std::chrono::steady_clock::now();
    auto took = std::chrono::steady_clock::now() - start;
    EXPECT_TRUE(took.count() < 5);
}""", 1),
    ("c", "ASSERT_EQ(elapsed, 3.0);", 1),
    ("c", "ASSERT_NEAR(frame.cpu_frame_ms, 16.6, 5.0) << \"a 60 Hz frame\";", 1),
    ("python", "check(abs(row['frame_ms'] - 16.6) < 5, 'a 60 Hz frame')", 1),
    ("c", "CHECK(frame_ms <= 16.6, \"slow\");", 1),
    ("c", "assert(kernelMs >= 0);", 1),
    ("cmake", "string(TIMESTAMP t \"%s\")\nmath(EXPR took \"${t} - ${t0}\")\nif(took GREATER 5)\nendif()", 1),
    ("cmake", "file(READ x.json j)\nstring(JSON v GET \"${j}\" total_seconds)\nif(v LESS_EQUAL 60)\nendif()", 1),
    ("python", "assert elapsed < 5", 1),
    ("python", "self.assertLess(result['time_ms'], 3)", 1),
    ("python", "self.assertEqual(start_timestamp, 0)", 1),
    ("python", "check(row['rrc_ms'] > 0, 'positive')", 1),
    # Not timed: presence, equality on made-up timings, counts, names and words
    # in messages or comments, a clock's variable name reused in another block.
    ("c", "EXPECT_TRUE(std::isfinite(r.frames[5].timings.rrc));", 0),
    ("c", "EXPECT_TRUE(r.frames[5].timings.from_timestamps) << \"rrc's GPU time was measured\";", 0),
    ("c", "EXPECT_DOUBLE_EQ(pass_ms(Timing{0.2, 2.5}, floor, false), 0.2) << \"timestamps as measured\";", 0),
    ("c", "EXPECT_NEAR(b.shade_ms, 20 + 20.0 / 3, 1e-12);", 0),
    ("c", "EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);", 0),
    ("c", "EXPECT_GT(lifetime_refreshes, kN) << \"the lifetime, not the policy\";", 0),
    ("c", "EXPECT_GT(hits, 1000u) << \"elapsed 5 ms\";  // EXPECT_LT(ms, 5)", 0),
    ("c", "EXPECT_LE(params.items, 4u); EXPECT_GT(terms, 1'000);", 0),
    ("c", "EXPECT_EQ(cost.rfind(\"octaves,run,full_shade_ms\\n\", 0), 0u);", 0),
    ("c", "EXPECT_THROW(parse({\"--ms\", \"-1\"}), std::runtime_error);", 0),
    ("c", "void a() { auto t = std::chrono::steady_clock::now(); (void)t; }\nvoid b() { int t = 3; EXPECT_GT(t, 1); }", 0),
    ("c", "EXPECT_EQ(committed.expected.mask, now.expected.mask);", 0),
    ("c", "EXPECT_GT(counts.begin()->second, 0u);", 0),
    ("c", "#define CHECK(cond, ...) if (!(cond)) { fail(__VA_ARGS__); }", 0),
    ("cmake", "string(JSON type TYPE \"${json}\" rows ${i} kernel_ms_median)\nif(NOT type MATCHES \"^NUMBER$\")\nendif()", 0),
    ("cmake", "string(JSON young GET \"${json}\" rows ${i} young_fraction)\nif(young LESS 0 OR young GREATER 1)\nendif()", 0),
    ("cmake", "if(NOT rc EQUAL 0)  # ms GREATER 5\n  message(FATAL_ERROR \"took (ms GREATER 5\")\nendif()", 0),
    ("cmake", "list(POP_FRONT costs name seconds)\nset_tests_properties(${name} PROPERTIES COST ${seconds})", 0),
    ("python", "check(abs(t1['t_lo'] - 1.7) < 1e-12, 'range')", 0),
    ("python", "check(front == [(0.5, 9)], f'elapsed {ms}')", 0),
    ("python", "check(r['time_ms'] == 3.5, 'the model adds')", 0),
    ("python", "assert os.path.getsize(p) <= LIMIT_BYTES", 0),
    ("python", "assert 'elapsed_ms' in report and report['elapsed_ms'] is not None", 0),
    ("python", "s = 'assert elapsed < 5'", 0),
]


def self_test():
    scanners = {"c": scan_c, "cmake": scan_cmake, "python": scan_python}
    wrong = 0
    for language, source, expected in SELF_TEST_CASES:
        got = scanners[language](source)
        if len(got) != expected:
            wrong += 1
            print(f"self-test FAILED ({language}: {expected} finding(s) expected, {got}):\n{source}\n",
                  file=sys.stderr)
    if wrong:
        print(f"self-test: {wrong} of {len(SELF_TEST_CASES)} cases answered wrong", file=sys.stderr)
        return 1
    print(f"self-test: all {len(SELF_TEST_CASES)} cases answered right")
    return 0


def main(argv):
    if argv == ["--self-test"]:
        return self_test()
    if len(argv) != 1 or not os.path.isdir(argv[0]):
        print(__doc__, file=sys.stderr)
        return 2
    findings, files = scan(argv[0])
    for f in findings:
        print(f)
    if findings:
        print(f"{len(findings)} timed assertion(s) in {files} files: print the time, and check only that it is "
              "reported (tests/lint/timed_assertions.py says what counts)", file=sys.stderr)
        return 1
    print(f"no timed assertion in {files} files of {', '.join(f + '/' for f in FOLDERS)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
