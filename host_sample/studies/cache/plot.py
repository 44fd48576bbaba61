#!/usr/bin/env python3
"""rrc-cache's speed-up against refresh period n, per policy, with the Amdahl bound (matplotlib, Agg)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4))
    for policy, colour in (("tiled", "tab:blue"), ("random", "tab:orange")):
        for lifetime, style in ((False, "-"), (True, "--")):
            pts = []
            # The runs at the first octave count only (named without _oN; runs.csv's octaves column).
            base = rows[0].get("octaves") if rows else None
            for r in rows:
                if base is not None and r.get("octaves") != base:
                    continue
                parts = r["name"].split("_")
                if parts[0] != policy or (len(parts) == 3) != lifetime:
                    continue
                pts.append((int(parts[1]), float(r["speedup"]), float(r["amdahl_bound"]), float(r["rmse"])))
            if not pts:
                continue
            pts.sort()
            n = [p[0] for p in pts]
            label = policy + (" + lifetime 2n" if lifetime else "")
            ax.plot(n, [p[1] for p in pts], style, color=colour, marker="o", label=label + " measured")
            ax.plot(n, [p[2] for p in pts], style, color=colour, alpha=0.35, label=label + " Amdahl bound")
            ax2.plot(n, [p[3] for p in pts], style, color=colour, marker="o", label=label)
    ax.axhline(1.0, color="grey", lw=0.8)
    ax.set_xscale("log", base=2)
    ax.set_xlabel("refresh period n (frames)")
    ax.set_ylabel("speed-up over shading every pixel")
    ax.legend(fontsize=7)
    ax2.set_xscale("log", base=2)
    ax2.set_xlabel("refresh period n (frames)")
    ax2.set_ylabel("RMSE against shading every pixel")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
