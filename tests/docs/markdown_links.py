#!/usr/bin/env python3
"""Every relative link in the repository's Markdown leads somewhere, and every
docs/ path the code cites exists.

Checks each [text](target) and ![alt](target) of README.md, CHANGELOG.md, docs/**/*.md and
host_sample/**/*.md whose target is not a URL: the file or folder it names
exists (relative to the linking file), and a #fragment names a heading of the
target file (GitHub's anchors: lower case, punctuation but '-' and '_'
dropped, spaces as '-', a repeated heading numbered -1, -2, ...).  Then each
`docs/...` path cited in the tracked code (C, C++, GLSL, CMake, Python, shell)
names a file or folder that exists.

    markdown_links.py --root SOURCE [--doc FILE ...]    (--doc: those Markdown files only, no code)
"""
import argparse
import glob
import os
import re
import subprocess
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*(```|~~~)")


def markdown_files(root):
    files = [os.path.join(root, "README.md"), os.path.join(root, "CHANGELOG.md")]
    files += glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True)
    files += glob.glob(os.path.join(root, "host_sample", "**", "*.md"), recursive=True)
    return sorted(f for f in files if os.path.isfile(f))


def slug(heading):
    text = re.sub(r"`|\*\*|\*", "", heading.strip().lower())
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"[^\w\- ]", "", text, flags=re.UNICODE)
    return text.replace(" ", "-")


def anchors(path):
    out, seen, in_fence = set(), {}, False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if FENCE.match(line):
                in_fence = not in_fence
            if in_fence:
                continue
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if m:
                s = slug(m.group(2))
                n = seen.get(s, 0)
                seen[s] = n + 1
                out.add(s if n == 0 else "%s-%d" % (s, n))
    return out


def links(path):
    """(line number, target) of each link outside code blocks and code spans."""
    in_fence = False
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if FENCE.match(line):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            for m in LINK.finditer(re.sub(r"`[^`]*`", "", line)):
                yield n, m.group(1)


CODE = re.compile(r"\.(h|hpp|c|cpp|comp|glsl|def|cmake|py|sh)$|(^|/)CMakeLists\.txt$|^\.ci/")
FROZEN = ("tests/abi/rrc_0_1/",)
CITED = re.compile(r"(?<![\w/.-])docs/[A-Za-z0-9_./-]*[A-Za-z0-9_/]")


def cited_docs_paths(root):
    """(file, line number, path) of each docs/ path the tracked code cites."""
    git = subprocess.run(["git", "-C", root, "ls-files"], capture_output=True, text=True)
    if git.returncode == 0:
        files = git.stdout.split()
    else:  # not a git checkout: every file but build outputs
        files = [os.path.relpath(os.path.join(d, f), root) for d, dirs, names in os.walk(root) for f in names
                 if not os.path.relpath(d, root).split(os.sep)[0] in ("build", "out", ".git")]
    for rel in files:
        # The 0.1 headers kept verbatim (tests/abi: abi_0_1_headers_verbatim) cite the docs as they were.
        if not CODE.search(rel) or rel.startswith(FROZEN):
            continue
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for n, line in enumerate(f, 1):
                for m in CITED.finditer(line):
                    yield rel, n, m.group(0).rstrip(".")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--doc", action="append")
    a = ap.parse_args()
    files = [os.path.join(a.root, d) for d in a.doc] if a.doc else markdown_files(a.root)
    cache, bad, count = {}, 0, 0
    for path in files:
        for n, target in links(path):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            count += 1
            name, _, fragment = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(path), name)) if name else path
            rel = os.path.relpath(path, a.root)
            if not os.path.exists(dest):
                print("%s:%d: %s: no such file" % (rel, n, target))
                bad += 1
            elif fragment and dest.endswith(".md"):
                if dest not in cache:
                    cache[dest] = anchors(dest)
                if fragment.lower() not in cache[dest]:
                    print("%s:%d: %s: no heading with that anchor" % (rel, n, target))
                    bad += 1
    print("%d relative links checked in %d files, %d broken" % (count, len(files), bad))
    if not a.doc:
        cited = missing = 0
        for rel, n, p in cited_docs_paths(a.root):
            cited += 1
            # A CMake file names its sources relative to its own folder (tests/docs/...).
            local = rel.endswith("CMakeLists.txt") and os.path.exists(os.path.join(a.root, os.path.dirname(rel), p))
            if not os.path.exists(os.path.join(a.root, p)) and not local:
                print("%s:%d: cites %s, which does not exist" % (rel, n, p))
                missing += 1
        print("%d docs/ paths cited in the code, %d missing" % (cited, missing))
        bad += missing
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
