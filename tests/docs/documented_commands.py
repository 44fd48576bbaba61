#!/usr/bin/env python3
"""Every rrc-* command line the documentation shows still parses.

Extracts each command of the host programs from README.md, CHANGELOG.md, docs/**/*.md and
host_sample/**/README.md (fenced code blocks and inline `code` spans), and
runs it with the program from the build's bin/ directory plus
--check-options, which parses and validates every option as a run would
without touching the GPU or a file (host_sample/testbed/README.md, "Checking
a command line").  A documented option that no longer exists, or a value out
of its range, fails here.

    documented_commands.py --bin BUILD/bin --root SOURCE [--doc FILE ...]

--doc checks only the given files (the test's own failure check uses it).
"""
import argparse
import glob
import os
import re
import shlex
import subprocess
import sys

PROGRAMS = ("rrc-sample", "rrc-sample-peers", "rrc-sweep", "rrc-cache", "rrc-accumulate", "rrc-make-demo-sequence", "rrc-bench", "rrc-blender-check")

# Snippets that cannot be checked, each with its reason: (file, a regular expression the snippet matches).
EXEMPT = [
    # Prose naming rrc-blender-check's mode, not a command line.
    ("docs/measurements/OFFLINE.md", r"^rrc-blender-check --hits$"),
    # Prose with a placeholder value T (the fill age), not a command line.
    ("docs/measurements/finish/README.md", r"^rrc-sample --soft-fill T$"),
]



def doc_files(root):
    files = [os.path.join(root, "README.md"), os.path.join(root, "CHANGELOG.md")]
    files += sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    files += sorted(glob.glob(os.path.join(root, "host_sample", "**", "README.md"), recursive=True))
    return [f for f in files if os.path.isfile(f)]


LOOP = re.compile(r"\bfor (\w+) in (\S+)[^;\n]*; do\b")


def snippets(text):
    """(line number, inline?, text) of each code-block line (continuations joined) and each inline
    code span.  In a code block, a shell loop's variable ($s, ${s}) is replaced by the loop's first
    value from the loop's line on, so a command inside the loop is checked with a value it takes."""
    out = []
    lines = text.split("\n")
    in_block = False
    loops = {}
    pending, pending_line = "", 0

    def emit(n, snippet):
        for var, first in loops.items():
            snippet = re.sub(r"\$\{?" + var + r"\b\}?", first, snippet)
        out.append((n, False, snippet))

    for n, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            in_block = not in_block
            if pending:
                emit(pending_line, pending)
            pending = ""
            loops = {}
            continue
        if in_block:
            loops.update(dict(LOOP.findall(line)))
            if not pending:
                pending_line = n
            if line.rstrip().endswith("\\"):
                pending += line.rstrip()[:-1] + " "
                continue
            emit(pending_line, pending + line)
            pending = ""
        else:
            for m in re.finditer(r"``?([^`]+)``?", line):
                out.append((n, True, m.group(1)))
    return out


def unbracket(token):
    """[--flag] -> --flag; [...] and ... -> nothing: an optional part is checked as given."""
    if token in ("...", "[...]", "…"):
        return None
    return token.strip("[]") or None


SEPARATORS = {";", "&&", "||", "|", "&", "(", ")", ">", ">>", "<", "2>", "2>&1"}
KEYWORDS = {"do", "then", "else", "time", "exec", "!"}
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")


def shell_words(snippet):
    lex = shlex.shlex(snippet, posix=True, punctuation_chars=";&|()<>")
    lex.whitespace_split = True
    lex.commenters = "#"
    try:
        return list(lex)
    except ValueError:  # an unbalanced quote in prose
        return snippet.split()


def commands(snippet):
    """The rrc-* commands in one snippet: (program, arguments).  A program counts only where a
    shell command starts (after environment assignments), not as another program's argument."""
    found = []
    words = shell_words(snippet)
    i = 0
    while i < len(words):
        # The start of a shell command: skip assignments and keywords.
        while i < len(words) and (ASSIGNMENT.match(words[i]) or words[i] in KEYWORDS):
            i += 1
        if i >= len(words):
            break
        first = words[i]
        j = i + 1
        while j < len(words) and words[j] not in SEPARATORS:
            j += 1
        if first != "for" and os.path.basename(first) in PROGRAMS:
            args = [t for t in (unbracket(w) for w in words[i + 1:j]) if t is not None]
            found.append((os.path.basename(first), args))
        i = j + 1
    return found


def exempt(path, snippet):
    for where, fragment in EXEMPT:
        if path == where and re.search(fragment, snippet.strip()):
            return True
    return False


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--root", required=True)
    ap.add_argument("--doc", action="append")
    a = ap.parse_args()
    files = a.doc or doc_files(a.root)
    env = dict(os.environ)
    checked, failed, skipped, seen = 0, [], 0, set()
    for path in files:
        rel = os.path.relpath(path, a.root)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for line, inline, snippet in snippets(text):
            for program, args in commands(snippet):
                if inline and not args:
                    continue  # `rrc-sweep` in prose names the program; it is no command
                if exempt(rel, snippet):
                    skipped += 1
                    continue
                key = (program, tuple(args))
                if key in seen:
                    continue
                seen.add(key)
                cmd = [os.path.join(a.bin, program)] + args + ["--check-options"]
                shown = f"{rel}:{line}: {program} {shlex.join(args)}"
                if not os.path.isfile(cmd[0]):
                    failed.append(f"{shown}\n    {program} is not built in {a.bin}")
                    print("FAIL " + shown + " (not built)")
                    continue
                r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=60)
                checked += 1
                if r.returncode != 0:
                    failed.append(f"{shown}\n    exit {r.returncode}: {(r.stderr or r.stdout).strip().splitlines()[0] if (r.stderr or r.stdout).strip() else ''}")
                    print("FAIL " + shown)
                else:
                    print("ok   " + shown)
    print(f"{checked} documented commands checked, {len(failed)} failed, {skipped} exempt")
    for f in failed:
        print(f, file=sys.stderr)
    return 1 if failed or not checked else 0


if __name__ == "__main__":
    sys.exit(main())
