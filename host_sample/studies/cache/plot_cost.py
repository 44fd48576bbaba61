#!/usr/bin/env python3
"""rrc-cache's speed-up of TILED n = 4 against the shader's cost (speedup_vs_cost.csv; matplotlib, Agg).

x: the full shading pass a frame (ms), each point labelled with its octave count; the Amdahl bound beside
the measured speed-up; speed-up = 1 and the break-even shader (linear between measured points, the rule of
cache_targets.cpp's break_even); the paper's 1.7-1.9x at n = 4 (Nehab et al. 2007) as a band.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

PAPER = (1.7, 1.9)  # cache_targets.h, kPaperSpeedupLow/High


def break_even(points):
    """(octaves, ms, kind) where the speed-up first reaches 1, from (octaves, ms, speed-up) sorted by octaves."""
    for i, (octaves, ms, s) in enumerate(points):
        if s < 1.0:
            continue
        if i == 0:
            return octaves, ms, "at or below"
        o0, m0, s0 = points[i - 1]
        t = (1.0 - s0) / (s - s0)
        return o0 + t * (octaves - o0), m0 + t * (ms - m0), "between"
    return None


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    pts = sorted((int(r["octaves"]), float(r["full_shade_ms"]), float(r["speedup"]), float(r["amdahl_bound"])) for r in rows)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.axhspan(PAPER[0], PAPER[1], color="tab:green", alpha=0.15, label="Nehab et al. 2007, n = 4: %.1f-%.1fx" % PAPER)
    ax.axhline(1.0, color="grey", lw=0.8, label="break-even (speed-up = 1)")
    if pts:
        ms = [p[1] for p in pts]
        ax.plot(ms, [p[2] for p in pts], "-o", color="tab:blue", label="TILED n = 4, measured")
        ax.plot(ms, [p[3] for p in pts], "--", color="tab:blue", alpha=0.4, label="Amdahl bound")
        for octaves, x, s, _ in pts:
            ax.annotate("%d oct" % octaves, (x, s), textcoords="offset points", xytext=(4, -12), fontsize=8)
        be = break_even([(p[0], p[1], p[2]) for p in pts])
        if be:
            octaves, x, kind = be
            ax.axvline(x, color="tab:red", lw=0.8, ls=":")
            where = "at or below " if kind == "at or below" else ""
            ax.plot([x], [1.0], "D", color="tab:red",
                    label="break-even: %s%.1f octaves, %.1f ms (linear between points)" % (where, octaves, x))
        else:
            ax.text(0.02, 0.04, "break-even not reached up to %d octaves" % pts[-1][0], transform=ax.transAxes, color="tab:red")
    ax.set_xlabel("shader cost: full shading pass a frame (ms)")
    ax.set_ylabel("speed-up over shading every pixel")
    ax.set_ylim(0, max([PAPER[1] + 0.2] + [p[3] * 1.05 for p in pts if p[3] < 100]))
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
