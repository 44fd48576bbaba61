#!/usr/bin/env python3
"""Plots an rrc-bench run: usage  plot.py bench.json bench.png

Left: kernel / roof per configuration (median, bar; whiskers the
interquartile range of the interleaved pairs: min-max on a shared machine is
mostly the load), with the 1.45 target of the base.  Right: kernel and
roof milliseconds against megapixels over the resolution rows, each with a
least-squares line (intercept = fixed cost of a frame).  The Agg backend:
no display is needed.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)


def linear_fit(xs, ys):
    """Ordinary least squares y = a + b x; (a, b), or None with fewer than two points."""
    n = len(xs)
    if n < 2:
        return None
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        return None
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return my - b * mx, b


def main(json_path, png_path):
    with open(json_path) as f:
        run = json.load(f)
    rows = run["rows"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.5))

    names = [r["name"] for r in rows]
    ratio = [r["ratio_median"] for r in rows]
    low = [r["ratio_median"] - r["ratio_q1"] for r in rows]
    high = [r["ratio_q3"] - r["ratio_median"] for r in rows]
    left.bar(range(len(rows)), ratio, yerr=[low, high], capsize=3, color="#4477aa")
    left.axhline(1.45, color="#cc3311", linestyle="--", linewidth=1, label="target 1.45 (base)")
    left.axhline(1.0, color="black", linewidth=0.8)
    left.set_xticks(range(len(rows)))
    left.set_xticklabels(names, rotation=60, ha="right", fontsize=8)
    left.set_ylabel("kernel / roof (median, whiskers IQR)")
    left.set_title("kernel time over roof time, per configuration")
    left.legend(fontsize=8)

    res = sorted((r for r in rows if r["factor"] in ("resolution", "base")), key=lambda r: r["megapixels"])
    for key, colour, label in (("kernel_ms_median", "#4477aa", "kernel"), ("roof_ms_median", "#228833", "roof")):
        xs = [r["megapixels"] for r in res]
        ys = [r[key] for r in res]
        right.plot(xs, ys, "o", color=colour, label=label)
        fit = linear_fit(xs, ys)
        if fit:
            a, b = fit
            top = max(xs)
            right.plot([0, top], [a, a + b * top], "-", color=colour, linewidth=1,
                       label="%s fit: %.2f + %.2f ms/MP" % (label, a, b))
    right.set_xlabel("megapixels")
    right.set_ylabel("ms (median)")
    right.set_title("time against frame size")
    right.set_xlim(left=0)
    right.set_ylim(bottom=0)
    right.legend(fontsize=8)

    fig.suptitle("rrc-bench on %s, commit %s, %s" % (run["device"], run["commit"], run["date"]), fontsize=10)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
