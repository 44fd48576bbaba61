#!/usr/bin/env python3
"""rrc-sweep --study rectify's plot: lag error (light moving), static
variance and static RMSE (light fixed) against lambda, rectification off and
on and the lag detector on, one column per application.  Reads DIR/rectify.csv, writes DIR/rectify.png."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def variant(r):
    """One curve: rectification and its gamma, the lag detector and its gamma_a, and for the
    rows fed the lighting's turn the view lobe's alpha (the filter column's "lobeA")."""
    lobe = ""
    if int(r.get("lighting_turn", "0")):
        lobe = next((p[4:] for p in r["filter"].split("+") if p.startswith("lobe")), "0")
    return (int(r["rectify"]), r["gamma"], int(r.get("antilag", "0")), r.get("antilag_gamma", ""), lobe)


def main(out):
    with open(os.path.join(out, "rectify.csv")) as f:
        # rrc-sample's preset rows are one lambda each: the table has them, not the curves.
        rows = [r for r in csv.DictReader(f) if not r.get("preset")]
    apps = []
    for r in rows:
        if r["app"] not in apps:
            apps.append(r["app"])
    variants = []
    for r in rows:
        v = variant(r)
        if v not in variants:
            variants.append(v)
    fig, axes = plt.subplots(3, len(apps), figsize=(4.2 * len(apps), 9.0), squeeze=False)
    speed = rows[0]["light_speed"] if rows else "?"
    for c, app in enumerate(apps):
        for v in variants:
            (on, gamma, lag_on, lag_gamma, lobe) = v
            sel = [r for r in rows if r["app"] == app and variant(r) == v]
            if not sel:
                continue
            sel.sort(key=lambda r: float(r["lambda"]))
            lam = [float(r["lambda"]) for r in sel]
            if lobe:
                label = "view lobe α = %.3g rad, lighting's turn" % float(lobe)
                style = "d-."
            elif lag_on:
                label = "lag detector, γ_a = %s" % lag_gamma.rstrip("0").rstrip(".")
                style = "^:"
            elif on:
                label = "rectify, γ = %s" % gamma.rstrip("0").rstrip(".")
                style = "o-"
            else:
                label = "neither"
                style = "s--"

            def val(r, key):
                try:
                    return float(r[key])
                except ValueError:
                    return math.nan

            axes[0][c].plot(lam, [val(r, "lag_rmse") for r in sel], style, label=label)
            axes[1][c].plot(lam, [val(r, "static_variance") for r in sel], style, label=label)
            axes[2][c].plot(lam, [val(r, "static_rmse") for r in sel], style, label=label)
        lag = [r["lag_rmse"] for r in rows if r["app"] == app]
        if all(v in ("n/a", "nan", "") for v in lag):
            axes[0][c].text(0.5, 0.5, "no pixel's target changed\n(the area lamp does not move)", ha="center", va="center",
                            transform=axes[0][c].transAxes)
        axes[0][c].set_title("%s: lag error, light %s°/frame" % (app, speed))
        axes[1][c].set_title("%s: static variance, light fixed" % app)
        axes[2][c].set_title("%s: static RMSE (bias² + variance)" % app)
        axes[1][c].set_yscale("log")
        for r in range(3):
            axes[r][c].set_xlabel("λ")
            axes[r][c].grid(True, alpha=0.3)
        axes[0][c].set_ylabel("RMSE on changed pixels")
        axes[1][c].set_ylabel("variance across seeds")
        axes[2][c].set_ylabel("RMSE, every scored pixel")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "rectify.png"), dpi=110)
    print("rectify_plot.py: %s" % os.path.join(out, "rectify.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: rectify_plot.py DIR (with DIR/rectify.csv)")
    main(sys.argv[1])
