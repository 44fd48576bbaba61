#!/usr/bin/env python3
"""rrc-sweep --bias-maps: where the bias sits (README.md, "Bias maps").

Reads OUT/bias_regions_<app>.csv and OUT/bias_maps/*.exr (written by rrc-sweep) and writes
  OUT/bias_regions_<app>.md  the rows' bias² and variance by region (shares and per-pixel means)
  OUT/bias_<app>.png         the regions, the target and the signed bias maps (seed mean - target)
                             of the age-aware bilinear rows and brute force, at every checkpoint
Needs matplotlib, Pillow and OpenImageIO's Python module (Debian: python3-matplotlib, python3-pil,
python3-openimageio).

usage: bias_maps.py OUT [--checkpoints T,T...] [--dpi N]
       bias_maps.py --table OUT...   one markdown table of every OUT's age-aware bilinear rows, rectified rows
                                     and brute force (docs/measurements/BIAS.md), on stdout
"""
import csv
import glob
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import OpenImageIO as oiio  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

REGIONS = ["object", "edge", "young", "changed", "static"]
REGION_COLOURS = ["#d62728", "#ff7f0e", "#9467bd", "#2ca02c", "#c7c7c7"]


def read_exr(path):
    """Every channel of an EXR as a dict name -> 2D float array."""
    buf = oiio.ImageBuf(path)
    spec = buf.spec()
    px = np.asarray(buf.get_pixels(oiio.FLOAT))
    return {name: px[:, :, i] for i, name in enumerate(spec.channelnames)}


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fmt(v, digits=2):
    v = float(v)
    if math.isnan(v):
        return "–"
    if v == 0.0:
        return "0"
    return "%.*e" % (digits - 1, v)


def pct(v):
    v = float(v)
    return "–" if math.isnan(v) else "%.0f %%" % (100.0 * v)


def describe(row):
    if row["method"] == "brute":
        return "brute k=%s" % row["k"]
    lam = "" if row["lambda"] == "-" else " λ=%s" % row["lambda"]
    cap = "" if row["age_cap"] == "-" else " cap %s" % row["age_cap"]
    return "rrc k=%s %s%s %s%s" % (row["k"], row["blend"], lam, row["filter"], cap)


def tables(out, app, rows):
    """bias_regions_<app>.md: one table of shares, one of per-pixel means."""
    labels = []
    by = {}
    for r in rows:
        if r["label"] not in by:
            labels.append(r["label"])
            by[r["label"]] = {}
        by[r["label"]][r["region"]] = r
    first = by[labels[0]]
    lines = ["# bias² by region: %s" % app, "",
             "Regions by precedence object > edge > young > changed > static (README.md, \"Bias maps\"); "
             "shares of the scored pixels, mean over checkpoints: "
             + ", ".join("%s %s" % (g, pct(first[g]["pixel_share"])) for g in REGIONS)
             + " (each test alone: " + ", ".join("%s %s" % (g, pct(first[g]["raw_pixel_share"])) for g in REGIONS) + ").", "",
             "## Share of the row's bias² (bias² + variance = MSE; the parts add up to the totals)", "",
             "| row | RMSE | bias² | variance | " + " | ".join(REGIONS) + " |",
             "|---|---|---|---|" + "---|" * len(REGIONS)]
    for lab in labels:
        r = by[lab]
        t = r["total"]
        lines.append("| %s | %.4f | %s | %s | " % (describe(t), float(t["rmse"]), fmt(t["bias2"]), fmt(t["variance"]))
                     + " | ".join(pct(r[g]["bias2_share"]) for g in REGIONS) + " |")
    lines += ["", "## bias² and variance per pixel of each region (the region's part over its share of the pixels)", "",
              "| row | " + " | ".join("%s bias²" % g for g in REGIONS) + " | " + " | ".join("%s var" % g for g in REGIONS) + " |",
              "|---|" + "---|" * (2 * len(REGIONS))]
    for lab in labels:
        r = by[lab]
        lines.append("| %s | " % describe(r["total"]) + " | ".join(fmt(r[g]["bias2_per_pixel"]) for g in REGIONS) + " | "
                     + " | ".join(fmt(r[g]["variance_per_pixel"]) for g in REGIONS) + " |")
    lines += ["", "## bias² of each region as a part of the row's total (absolute)", "",
              "| row | " + " | ".join(REGIONS) + " | total |", "|---|" + "---|" * (len(REGIONS) + 1)]
    for lab in labels:
        r = by[lab]
        lines.append("| %s | " % describe(r["total"]) + " | ".join(fmt(r[g]["bias2"]) for g in REGIONS) + " | %s |" % fmt(r["total"]["bias2"]))
    with open(os.path.join(out, "bias_regions_%s.md" % app), "w") as f:
        f.write("\n".join(lines) + "\n")
    return labels, by


def mapped_rows(labels, by):
    """The maps drawn: the plain age-aware bilinear rows, the other age-aware rows at λ = 0.8 (a finishing
    step or a cure: the presets' λ), then the largest brute force."""
    plain = [l for l in labels if by[l]["total"]["blend"] == "age-aware" and by[l]["total"]["filter"] == "bilinear"]
    other = [l for l in labels if by[l]["total"]["method"] == "rrc" and l not in plain and by[l]["total"]["blend"] == "age-aware"
             and by[l]["total"]["lambda"] == "0.8" and by[l]["total"]["filter"] != "gaussian"]
    brute = [l for l in labels if by[l]["total"]["method"] == "brute"]
    return plain + other[:2] + brute[-1:]


def maps(out, app, labels, by, only=None, dpi=110):
    regions = read_exr(os.path.join(out, "bias_maps", "%s_regions.exr" % app))
    cps = sorted(int(n.split(".cp")[1]) for n in regions if n.startswith("region.cp"))
    if only:
        cps = [c for c in cps if c in only]
    rows = mapped_rows(labels, by)
    images = {l: read_exr(os.path.join(out, "bias_maps", l + ".exr")) for l in rows}
    # One symmetric range for every map of the application: the 99.5th percentile of |bias|.
    vals = np.concatenate([np.abs(im["bias.cp%d" % c][np.isfinite(im["bias.cp%d" % c])]) for im in images.values() for c in cps])
    vmax = float(np.percentile(vals, 99.5)) if vals.size else 1.0
    vmax = vmax if vmax > 0 else 1.0
    # Crop to the scored pixels (env scores the mirror sphere only), with a margin.
    scored = np.zeros(regions["region.cp%d" % cps[0]].shape, dtype=bool)
    for c in cps:
        scored |= regions["region.cp%d" % c] < 255
    ys, xs = np.nonzero(scored)
    y0, y1 = max(int(ys.min()) - 4, 0), min(int(ys.max()) + 5, scored.shape[0])
    x0, x1 = max(int(xs.min()) - 4, 0), min(int(xs.max()) + 5, scored.shape[1])
    crop = (slice(y0, y1), slice(x0, x1))
    regions = {n: v[crop] for n, v in regions.items()}
    images = {l: {n: v[crop] for n, v in im.items()} for l, im in images.items()}
    h, w = regions["region.cp%d" % cps[0]].shape
    n_rows = 2 + len(rows)
    fig, axes = plt.subplots(n_rows, len(cps), figsize=(3.2 * len(cps) * max(w / h, 1.0) * 0.75 + 1.2, 2.1 * n_rows + 0.6),
                             squeeze=False, constrained_layout=True)
    cmap_regions = ListedColormap(REGION_COLOURS)
    im_bias = None
    for j, c in enumerate(cps):
        reg = regions["region.cp%d" % c].astype(float)
        reg[reg >= 255] = np.nan
        ax = axes[0][j]
        ax.imshow(reg, cmap=cmap_regions, vmin=-0.5, vmax=len(REGIONS) - 0.5, interpolation="nearest")
        ax.set_title("regions, frame %d" % c, fontsize=8)
        ax = axes[1][j]
        ax.imshow(regions["target.cp%d" % c], cmap="gray", vmin=0.0, vmax=1.0, interpolation="nearest")
        ax.set_title("target, frame %d" % c, fontsize=8)
        for i, l in enumerate(rows):
            ax = axes[2 + i][j]
            im_bias = ax.imshow(images[l]["bias.cp%d" % c], cmap="RdBu_r", vmin=-vmax, vmax=vmax, interpolation="nearest")
            ax.set_title("%s, frame %d" % (describe(by[l]["total"]), c), fontsize=7)
    for ax in axes.flat:
        ax.set_xticks([])
        ax.set_yticks([])
    handles = [matplotlib.patches.Patch(color=REGION_COLOURS[i], label=g) for i, g in enumerate(REGIONS)]
    axes[0][-1].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7)
    if im_bias is not None:
        fig.colorbar(im_bias, ax=axes[2:, :].ravel().tolist(), shrink=0.6, label="seed mean − target (%s)" % app)
    fig.suptitle("%s: regions, target and signed bias (red: too bright, blue: too dark)" % app, fontsize=9)
    path = os.path.join(out, "bias_%s.png" % app)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    # 256 colours are plenty for a colour map and a few region colours, and keep the file small (docs/measurements/bias/).
    from PIL import Image
    Image.open(path).convert("RGB").quantize(colors=256).save(path, optimize=True)


def table(dirs):
    """The doc's table: per application and run, the plain age-aware bilinear rows, the rectified ones and
    brute force: RMSE, bias², variance, and each region's share of the pixels and of the bias²."""
    lines = ["| run | app | row | RMSE | bias² | variance | " + " | ".join(REGIONS) + " |",
             "|---|---|---|---|---|---|" + "---|" * len(REGIONS)]
    for d in dirs:
        run = os.path.basename(os.path.normpath(d))
        for path in sorted(glob.glob(os.path.join(d, "bias_regions_*.csv"))):
            app = os.path.basename(path)[len("bias_regions_"):-len(".csv")]
            by = {}
            order = []
            for r in read_rows(path):
                if r["label"] not in by:
                    order.append(r["label"])
                    by[r["label"]] = {}
                by[r["label"]][r["region"]] = r
            first = by[order[0]]
            lines.append("| %s | %s | *pixels* | | | | " % (run, app) + " | ".join(pct(first[g]["pixel_share"]) for g in REGIONS) + " |")
            for lab in order:
                t = by[lab]["total"]
                keep = t["method"] == "brute" or (t["blend"] == "age-aware" and t["filter"] in ("bilinear", "bilinear+rectify", "bilinear+fill8"))
                if not keep:
                    continue
                # Brute force is unbiased: its bias² is noise around 0, and shares of it mean nothing.
                shares = (["–"] * len(REGIONS) if t["method"] == "brute" else [pct(by[lab][g]["bias2_share"]) for g in REGIONS])
                lines.append("| %s | %s | %s | %.4f | %s | %s | " % (run, app, describe(t), float(t["rmse"]), fmt(t["bias2"]), fmt(t["variance"]))
                             + " | ".join(shares) + " |")
    print("\n".join(lines))


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    if argv[1] == "--table":
        table(argv[2:])
        return
    out = argv[1]
    only, dpi = None, 110
    if "--checkpoints" in argv:
        only = [int(v) for v in argv[argv.index("--checkpoints") + 1].split(",")]
    if "--dpi" in argv:
        dpi = int(argv[argv.index("--dpi") + 1])
    found = sorted(glob.glob(os.path.join(out, "bias_regions_*.csv")))
    if not found:
        sys.exit("bias_maps.py: no bias_regions_*.csv in " + out)
    for path in found:
        app = os.path.basename(path)[len("bias_regions_"):-len(".csv")]
        labels, by = tables(out, app, read_rows(path))
        maps(out, app, labels, by, only, dpi)
        print("bias_maps.py: %s/bias_regions_%s.md, bias_%s.png" % (out, app, app))


if __name__ == "__main__":
    main(sys.argv)
