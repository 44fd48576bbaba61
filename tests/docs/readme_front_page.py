#!/usr/bin/env python3
"""README.md stays the product's front page: short, the three commands first.

Checks, on ROOT/README.md:
  - at most 120 lines and 1,200 words (as `wc -l` and `wc -w` count them);
  - its first fenced code block is one of the three commands, and all three are
    there, each a code block of its own: `bash .ci/main-job`, `bash .ci/test`,
    `bash .ci/install-library PREFIX`;
  - .ci/run runs exactly README's test command.

  readme_front_page.py ROOT          exit 1 on a finding, each printed
  readme_front_page.py --self-test   the checks on made-up READMEs; exit 1 if one answers wrong
"""

import os
import re
import sys

MAX_LINES, MAX_WORDS = 120, 1200
COMMANDS = ("bash .ci/main-job", "bash .ci/test", "bash .ci/install-library PREFIX")
TEST_COMMAND = "bash .ci/test"


def code_blocks(text):
    """The fenced blocks' contents, in order, each stripped."""
    return [m.group(1).strip() for m in re.finditer(r"^```[^\n]*\n(.*?)^```", text, re.M | re.S)]


def findings(readme, ci_run):
    out = []
    lines = readme.count("\n") + (0 if readme.endswith("\n") or not readme else 1)
    words = len(readme.split())
    if lines > MAX_LINES:
        out.append(f"README.md has {lines} lines, more than {MAX_LINES}")
    if words > MAX_WORDS:
        out.append(f"README.md has {words} words, more than {MAX_WORDS}")
    blocks = code_blocks(readme)
    if not blocks or blocks[0] not in COMMANDS:
        out.append("README.md's first code block is not one of the three commands: " + (repr(blocks[0]) if blocks else "none"))
    for c in COMMANDS:
        if c not in blocks:
            out.append(f"README.md has no code block of its own for `{c}`")
    ran = [l.strip() for l in ci_run.splitlines() if l.strip() and not l.lstrip().startswith("#")]
    ran = [l for l in ran if not l.startswith(("set ", "cd "))]
    if ran != [TEST_COMMAND]:
        out.append(f".ci/run runs {ran}, not exactly README's test command `{TEST_COMMAND}`")
    return out


def self_test():
    good = "# rrc\n\ntext\n\n```sh\nbash .ci/main-job\n```\n\n```sh\nbash .ci/test\n```\n\n```sh\nbash .ci/install-library PREFIX\n```\n"
    run = "#!/usr/bin/env bash\n# CI\nset -euo pipefail\ncd \"$(dirname \"$0\")/..\"\nbash .ci/test\n"
    cases = [
        ("the shape README.md must have", good, run, 0),
        ("121 lines", good + "x\n" * (MAX_LINES + 1 - good.count("\n")), run, 1),
        ("1,201 words", good.replace("text", "w " * (MAX_WORDS + 2 - len(good.split()))), run, 1),
        ("a code snippet first", good.replace("# rrc\n", "# rrc\n```c\nint x;\n```\n"), run, 1),
        ("a command missing", good.replace("bash .ci/install-library PREFIX", "make install"), run, 1),
        ("CI running something else", good, run.replace("bash .ci/test", "bash .ci/test --quick"), 1),
        ("CI running one more step", good, run + "echo done\n", 1),
    ]
    bad = 0
    for name, readme, ci_run, want in cases:
        got = len(findings(readme, ci_run))
        if (got > 0) != (want > 0):
            print(f"self-test: {name}: {got} findings, expected {'some' if want else 'none'}")
            bad += 1
    print(f"readme_front_page self-test: {len(cases)} cases, {bad} wrong")
    return 1 if bad else 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__)
        return 2
    root = argv[1]
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    with open(os.path.join(root, ".ci", "run"), encoding="utf-8") as f:
        ci_run = f.read()
    out = findings(readme, ci_run)
    for line in out:
        print("readme_front_page:", line)
    print(f"readme_front_page: README.md {readme.count(chr(10))} lines, {len(readme.split())} words, {len(out)} findings")
    return 1 if out else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
