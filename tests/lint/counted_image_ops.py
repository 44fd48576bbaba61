#!/usr/bin/env python3
"""Every image load and store of the counted passes goes through the counters.

rrc_vulkan_frame_desc.count_io counts what the per-pixel passes load and store
(compute/rrc_io.glsl; docs/measurements/PERFORMANCE.md, "What a pixel moves").
A load or store written beside the counters would be done but not counted, and
the counts would still look exact.  This scans compute/*.glsl and *.comp
(comments removed) and fails on:

  a load     imageLoad, texelFetch or textureGather whose call is not inside
             the arguments of an RRC_LOAD(texels, bytes, expr);
  a store    imageStore without an rrc_io_store( call in the same statement
             block before it: on its line or on the line above.

The modules that count nothing are exempt: rrc_module_copy_out.comp and
rrc_module_list.comp (rrc_vulkan_record_frame runs neither).

  counted_image_ops.py ROOT        scan ROOT/compute
  counted_image_ops.py --self-test the scan finds the forms above
"""
import pathlib
import re
import sys

EXEMPT = {"rrc_module_copy_out.comp", "rrc_module_list.comp"}
LOADS = re.compile(r"\b(imageLoad|texelFetch|textureGather)\s*\(")
STORE = re.compile(r"\bimageStore\s*\(")
WRAP = re.compile(r"\bRRC_LOAD\s*\(")


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def closing(text, open_index):
    """The index of the parenthesis that closes the one at open_index."""
    depth = 0
    for i in range(open_index, len(text)):
        if text[i] == "(":
            depth += 1
        elif text[i] == ")":
            depth -= 1
            if depth == 0:
                return i
    return len(text)


def problems(name, text):
    text = strip_comments(text)
    covered = []
    for m in WRAP.finditer(text):
        start = m.end() - 1
        covered.append((start, closing(text, start)))
    lines = text.split("\n")
    out = []
    for m in LOADS.finditer(text):
        if not any(a < m.start() < b for a, b in covered):
            line = text.count("\n", 0, m.start()) + 1
            out.append(f"{name}:{line}: {m.group(1)} outside RRC_LOAD(texels, bytes, ...): not counted")
    for m in STORE.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        here = lines[line - 1][: m.start() - (text.rfind("\n", 0, m.start()) + 1)]
        above = lines[line - 2] if line >= 2 else ""
        if "rrc_io_store(" not in here and "rrc_io_store(" not in above:
            out.append(f"{name}:{line}: imageStore without rrc_io_store(bytes) before it: not counted")
    return out


def scan(root):
    found = []
    files = sorted(pathlib.Path(root, "compute").glob("*.glsl")) + sorted(pathlib.Path(root, "compute").glob("*.comp"))
    if not files:
        return [f"no kernels under {root}/compute"]
    for f in files:
        if f.name in EXEMPT:
            continue
        found += problems(f.name, f.read_text())
    return found


def self_test():
    bad = {
        "bare load": "float d = imageLoad(u_depth, px).r;",
        "load beside the wrapper": "float d = RRC_LOAD(1u, 4u, 0.0) + texelFetch(s_depth, px, 0).r;",
        "gather": "vec4 g = textureGather(s_gate[0], uv, 0);",
        "bare store": "if (store) {\n    x = 1;\n    imageStore(u_mask, px, uvec4(m));\n}",
    }
    good = {
        "wrapped load": "float d = RRC_LOAD(1u, 4u, imageLoad(u_depth, px).r);",
        "wrapped across lines": "#define L(t) (A ? RRC_LOAD(1u, 8u, \\\n    imageLoad(u_h, t)) : 0.0)",
        "counted store": "if (store) {\n    rrc_io_store(1u);\n    imageStore(u_mask, px, uvec4(m));\n}",
        "a comment": "// imageLoad(u_depth, px) and imageStore(u_mask, ...) in prose",
    }
    failed = []
    for what, src in bad.items():
        if not problems("self", src):
            failed.append(f"not flagged: {what}")
    for what, src in good.items():
        if problems("self", src):
            failed.append(f"flagged: {what}: {problems('self', src)}")
    return failed


def main(argv):
    if len(argv) == 2 and argv[1] == "--self-test":
        failed = self_test()
    elif len(argv) == 2:
        failed = scan(argv[1])
    else:
        print(__doc__)
        return 2
    for f in failed:
        print(f)
    print("counted_image_ops: " + ("FAILED" if failed else "ok"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
