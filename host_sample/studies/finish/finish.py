#!/usr/bin/env python3
"""The finishing steps' figures (docs/measurements/finish/), from rrc-sample runs.

  python3 host_sample/studies/finish/finish.py --sample build/release/bin/rrc-sample --out out/finish --docs docs/measurements/finish

Runs rrc-sample a few times (lavapipe: about 3 minutes in all), then writes the tables
(tables.md) and the figures (PNG, matplotlib) into --docs:
  A  soft shadows: young (newly disoccluded) pixels' RMSE over their first 8 frames for the
     --soft-prior 4 display, and rrc's own fill (--soft-fill) with the PCSS fallback and
     without it, for three windows and tolerances (young.csv of each run);
     Figure-9-like convergence after a reset (frames 1, 3, 7, 20, 256) and its error curve.
  B  PCF finishing: plain, Gaussian-blurred history, + smoothstep, + threshold (display only).
  C  PCF confidence: RMSE against frames with and without confidence.
"""
import argparse, csv, math, os, subprocess, sys, time

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

ENV = dict(os.environ)
ENV.setdefault("VK_ICD_FILENAMES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json")
ENV.setdefault("XDG_RUNTIME_DIR", "/tmp")


REUSE = False


def run(sample, out, args, log):
    cmd = [sample, "--quiet", "--no-images", "--out", out] + args
    stamp = os.path.join(out, "finish_run.txt")
    if REUSE and os.path.exists(stamp):  # --reuse: a finished run of the same command
        rc, secs, prev = open(stamp).read().split(" ", 2)
        if prev.strip() == " ".join(args):
            log.append((" ".join(["rrc-sample"] + args), int(rc), float(secs)))
            return int(rc) == 0
    t = time.time()
    p = subprocess.run(cmd, env=ENV, capture_output=True, text=True)
    log.append((" ".join(["rrc-sample"] + args), p.returncode, time.time() - t))
    if p.returncode:
        print(p.stdout[-2000:], p.stderr[-2000:], file=sys.stderr)
    os.makedirs(out, exist_ok=True)
    with open(stamp, "w") as f:
        f.write("%d %.1f %s\n" % (p.returncode, time.time() - t, " ".join(args)))
    return p.returncode == 0


def rmse_on(im, ref, surface):
    return math.sqrt(float(np.mean((im[surface] - ref[surface]) ** 2)))


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def num(v):
    return float(v) if v not in ("", None) else float("nan")


def read_young(path):
    """young.csv -> {tracks: {age (int) or "pooled": row}}."""
    out = {}
    for r in rows(path):
        k = "pooled" if "-" in r["age"] else int(r["age"])
        out.setdefault(r["tracks"], {})[k] = r
    return out


def load(d, name, frame, size):
    w, h = size
    p = os.path.join(d, "finish", "%s_%04d.f32" % (name, frame))
    return np.fromfile(p, dtype=np.float32).reshape(h, w) if os.path.exists(p) else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sample", default="build/release/bin/rrc-sample")
    ap.add_argument("--out", default="out/finish")
    ap.add_argument("--docs", default="docs/measurements/finish")
    ap.add_argument("--young-frames", type=int, default=24)
    ap.add_argument("--fill", type=int, default=8, help="T of the fill")
    ap.add_argument("--smoothstep", default="0.2,0.8")
    ap.add_argument("--threshold", default="0.5")
    ap.add_argument("--skip", default="", help="parts to skip: A, B, C")
    ap.add_argument("--reuse", action="store_true", help="keep the runs already in --out (redraw only)")
    a = ap.parse_args()
    global REUSE
    REUSE = a.reuse
    os.makedirs(a.out, exist_ok=True)
    os.makedirs(a.docs, exist_ok=True)
    log, md = [], []
    T = str(a.fill)

    if "A" not in a.skip:
        # A1: young pixels on the default moving-camera scene, the soft reference on every frame.
        # One run without a fill (rrc's history, the --soft-prior blend, PCSS), then rrc's own fill
        # for each window and tolerance, with the PCSS fallback (P = 4) and without it (P = 0): the
        # fill is display-only, so every run has the same ages and the same young tracks.
        base = ["--frames", str(a.young_frames), "--reference-every", "1", "--signals", "soft"]
        d0 = os.path.join(a.out, "young")
        cmd0 = base + ["--soft-fill", "0"]
        run(a.sample, d0, cmd0, log)
        y0 = read_young(os.path.join(d0, "young.csv"))
        windows = [("r = 2, tau = 0.005 (the library's defaults)", "", []),
                   ("r = 1, tau = 0.02", "_r1", ["--fill-radius", "1", "--fill-depth-tolerance", "0.02"]),
                   ("r = 2, tau = 0.05", "_t05", ["--fill-depth-tolerance", "0.05"])]
        fills = []  # (label, short label, command, young.csv)
        for wlab, wtag, wopts in windows:
            for prior in ("4", "0"):
                cmd = base + ["--soft-fill", T, "--fill-prior", prior] + wopts
                d = os.path.join(a.out, "young_fill%s_p%s" % (wtag, prior))
                if run(a.sample, d, cmd, log):
                    what = "rrc's fill, %s, T = %s, %s" % ("PCSS fallback (P = 4)" if prior == "4" else "no fallback", T, wlab)
                    fills.append((what, "fill P=%s%s" % (prior, wtag.replace("_", ", ")), cmd, read_young(os.path.join(d, "young.csv"))))
        md.append("## A. Young soft-shadow pixels: RMSE over their first 8 frames against the 16x16-grid reference\n")
        md.append("Moving camera, 256x160, %d frames, the reference on every frame. A track starts at a miss on a surface "
                  "(age 1) after frame 0 and follows the pixel as rrc's age does (nearest at the previous position) while it hits; "
                  "*disoccluded* tracks start on a point the oracle says was not visible in the previous frame, the others at a "
                  "miss of the depth test on a visible point (silhouettes). The fill's rows are rrc's own fill (its output, "
                  "`rmse_accumulated` of a `--soft-fill` run).\n" % a.young_frames)
        for tracks in ("disoccluded", "all"):
            md.append("### %s tracks\n" % ("Disoccluded" if tracks == "disoccluded" else "All young"))
            pooled = y0[tracks]["pooled"]
            shown = num(pooled["rmse_shown"])
            md.append("%s pixel-frames. Target: RMSE at least 30%% below the `--soft-prior 4` display (ratio <= 0.70).\n" % pooled["pixels"])
            md.append("| display | command | RMSE | / `--soft-prior 4` | target |\n|---|---|---|---|---|")
            md.append("| current display, `--soft-prior 4` | `%s` | %.4f | 1 | |" % (" ".join(cmd0), shown))
            for what, _, cmd, y in fills:
                v = num(y[tracks]["pooled"]["rmse_accumulated"])
                md.append("| %s | `%s` | %.4f | %.3f | %s |" % (what, " ".join(cmd), v, v / shown, "met" if v / shown <= 0.70 else "not met"))
            for col, what in [("rmse_accumulated", "rrc's value alone (no fill, no prior)"), ("rmse_pcss", "PCSS alone"), ("rmse_raw", "this frame's one sample")]:
                v = num(pooled[col])
                md.append("| %s | | %.4f | %.3f | |" % (what, v, v / shown))
            md.append("\nPer age (RMSE):\n\n| age | pixels | one sample | rrc alone | `--soft-prior 4` | PCSS |" +
                      "".join(" %s |" % short for _, short, _, _ in fills) + "\n|---|---|---|---|---|---|" + "---|" * len(fills))
            for g in sorted(k for k in y0[tracks] if k != "pooled"):
                r = y0[tracks][g]
                md.append("| %d | %s | %.4f | %.4f | %.4f | %.4f |" % (g, r["pixels"], num(r["rmse_raw"]), num(r["rmse_accumulated"]),
                          num(r["rmse_shown"]), num(r["rmse_pcss"])) + "".join(" %.4f |" % num(y[tracks][g]["rmse_accumulated"]) for _, _, _, y in fills))
            md.append("")
        fig, axs = plt.subplots(1, 2, figsize=(11, 4))
        for ax, tracks in zip(axs, ("disoccluded", "all")):
            y = y0[tracks]
            ages = sorted(k for k in y if k != "pooled")
            for col, lab in [("rmse_shown", "--soft-prior 4"), ("rmse_accumulated", "rrc alone"), ("rmse_pcss", "PCSS")]:
                ax.plot(ages, [num(y[g][col]) for g in ages], "o-", label=lab)
            for _, short, _, t in fills:
                ax.plot(ages, [num(t[tracks][g]["rmse_accumulated"]) for g in ages], "s--", label="rrc's " + short)
            ax.set_title("%s tracks" % tracks, fontsize=9)
            ax.set_xlabel("frames since the miss (age)"); ax.set_ylabel("RMSE"); ax.legend(fontsize=7); ax.grid(alpha=0.3)
        fig.tight_layout(); fig.savefig(os.path.join(a.docs, "soft_young.png"), dpi=110); plt.close(fig)

        # A2: Figure 9: a reset at frame 0, still camera (the torus still moves), 256 frames; without
        # a fill, and rrc's fill with and without the PCSS fallback.
        frames = [0, 1, 2, 3, 4, 6, 9, 14, 19, 31, 49, 79, 127, 199, 255]
        fig9 = ["--static-camera", "--frames", "256", "--reference-every", "0", "--reference-frames", ",".join(map(str, frames)),
                "--signals", "soft", "--size", "128x80", "--dump-soft", "--fill-depth-tolerance", "0.005"]
        runs9 = [("fig9", ["--soft-fill", "0"]), ("fig9_fill_p4", ["--soft-fill", T, "--fill-prior", "4"]),
                 ("fig9_fill_p0", ["--soft-fill", T, "--fill-prior", "0"])]
        for tag, extra in runs9:
            run(a.sample, os.path.join(a.out, tag), fig9 + extra, log)
        d9 = os.path.join(a.out, "fig9")
        c = rows(os.path.join(d9, "curve.csv"))
        cp4 = rows(os.path.join(a.out, "fig9_fill_p4", "curve.csv"))
        cp0 = rows(os.path.join(a.out, "fig9_fill_p0", "curve.csv"))
        size = tuple(int(v) for v in open(os.path.join(d9, "finish", "size.txt")).read().split())
        show = [0, 2, 6, 19, 255]
        kinds = [(d9, "soft_raw", "one sample"), (d9, "soft_accumulated", "rrc (no fill)"), (d9, "soft_shown", "--soft-prior 4"),
                 (os.path.join(a.out, "fig9_fill_p4"), "soft_accumulated", "rrc's fill + PCSS\n(tau=0.005)"),
                 (os.path.join(a.out, "fig9_fill_p0"), "soft_accumulated", "rrc's fill,\nno fallback")]
        fig, ax = plt.subplots(len(kinds) + 1, len(show), figsize=(2.2 * len(show), 1.5 * (len(kinds) + 1)))
        for j, f in enumerate(show):
            ref = load(d9, "soft_reference", f, size)
            surface = load(d9, "age", f, size) > 0
            ax[0, j].imshow(ref, cmap="gray", vmin=0, vmax=1); ax[0, j].set_title("frame %d" % (f + 1), fontsize=8)
            for i, (d, k, lab) in enumerate(kinds):
                im = load(d, k, f, size)
                ax[i + 1, j].imshow(im, cmap="gray", vmin=0, vmax=1)
                ax[i + 1, j].set_xlabel("RMSE %.3f" % rmse_on(im, ref, surface), fontsize=7)
        ax[0, 0].set_ylabel("reference", fontsize=8)
        for i, (_, k, lab) in enumerate(kinds): ax[i + 1, 0].set_ylabel(lab, fontsize=8)
        for q in ax.flat: q.set_xticks([]); q.set_yticks([])
        fig.tight_layout(); fig.savefig(os.path.join(a.docs, "soft_fig9.png"), dpi=110); plt.close(fig)
        fig, ax = plt.subplots(figsize=(6, 4))
        xs = [int(r["frames_since_reset"]) for r in c]
        for rs, col, lab in [(c, "rmse_raw", "one sample"), (c, "rmse_accumulated", "rrc (no fill)"), (c, "rmse_shown", "--soft-prior 4"),
                             (cp4, "rmse_accumulated", "rrc's fill + PCSS (tau=0.005)"), (cp0, "rmse_accumulated", "rrc's fill, no fallback (tau=0.005)"),
                             (c, "rmse_pcss", "PCSS")]:
            ax.plot(xs, [num(r[col]) for r in rs], "o-", ms=3, label=lab)
        ax.set_xscale("log"); ax.set_xlabel("frames since the reset"); ax.set_ylabel("RMSE (every surface pixel)")
        ax.legend(fontsize=7); ax.grid(alpha=0.3, which="both")
        fig.tight_layout(); fig.savefig(os.path.join(a.docs, "soft_fig9_curve.png"), dpi=110); plt.close(fig)
        md.append("## A. Figure 9: convergence after a reset\n\n`rrc-sample %s` with `%s`\n" % (" ".join(fig9), "`, `".join(" ".join(e) for _, e in runs9)))
        md.append("| frames since reset | one sample | rrc | --soft-prior 4 | rrc's fill + PCSS | rrc's fill, no fallback | PCSS |\n|---|---|---|---|---|---|---|")
        for r, p4, p0 in zip(c, cp4, cp0):
            md.append("| %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f |" % (r["frames_since_reset"], num(r["rmse_raw"]), num(r["rmse_accumulated"]),
                      num(r["rmse_shown"]), num(p4["rmse_accumulated"]), num(p0["rmse_accumulated"]), num(r["rmse_pcss"])))
        md.append("\n![Figure 9](soft_fig9.png) ![curve](soft_fig9_curve.png) ![young](soft_young.png)\n")

    if "B" not in a.skip:
        pb = ["--signals", "pcf", "--frames", "60", "--reference-every", "10"]
        steps = [("plain (bilinear)", "plain", []),
                 ("Gaussian history (--history-filter gaussian)", "blur", ["--history-filter", "gaussian"]),
                 ("Gaussian + smoothstep %s" % a.smoothstep, "smooth", ["--history-filter", "gaussian", "--pcf-smoothstep", a.smoothstep]),
                 ("Gaussian + smoothstep + threshold %s" % a.threshold, "thresh",
                  ["--history-filter", "gaussian", "--pcf-smoothstep", a.smoothstep, "--pcf-threshold", a.threshold]),
                 ("plain + smoothstep %s (no blur)" % a.smoothstep, "plain_smooth", ["--pcf-smoothstep", a.smoothstep]),
                 ("plain, still camera", "still_plain", ["--static-camera"]),
                 ("Gaussian history, still camera", "still_blur", ["--static-camera", "--history-filter", "gaussian"]),
                 ("Gaussian history sigma 0.8, still camera", "still_blur08", ["--static-camera", "--history-filter", "gaussian", "--blur-sigma", "0.8"])]
        md.append("## B. PCF finishing, RMSE against the fixed target (the exact disk mean), mean over the 6 checkpoints\n")
        md.append("`rrc-sample %s ...` (256x160, the default moving camera)\n" % " ".join(pb))
        md.append("| step | options | RMSE displayed | RMSE of the history (accumulated) |\n|---|---|---|---|")
        imgs = []
        for lab, tag, extra in steps:
            d = os.path.join(a.out, "pcf_" + tag)
            ok = run(a.sample, d, pb + extra + ["--dump-soft"], log)
            if not ok:
                md.append("| %s | `%s` | refused by this library build | |" % (lab, " ".join(extra)))
                continue
            e = [r for r in rows(os.path.join(d, "errors.csv")) if r["signal"] == "pcf"]
            acc = np.mean([num(r["rmse_accumulated"]) for r in e])
            shown = np.mean([num(r["rmse_shown"]) for r in e]) if e[0]["rmse_shown"] else acc
            md.append("| %s | `%s` | %.4f | %.4f |" % (lab, " ".join(extra), shown, acc))
            if "still" not in tag:
                imgs.append((lab, d, tag))
        md.append("")
        if imgs:
            size = tuple(int(v) for v in open(os.path.join(imgs[0][1], "finish", "size.txt")).read().split())
            n = len(imgs)
            fig, ax = plt.subplots(2, n + 1, figsize=(2.9 * (n + 1), 4.4))
            ref = load(imgs[0][1], "pcf_reference", 59, size)
            surface = load(imgs[0][1], "age", 59, size) > 0
            ax[0, 0].imshow(ref, cmap="gray", vmin=0, vmax=1); ax[0, 0].set_title("target (exact disk mean)", fontsize=7)
            ax[1, 0].imshow(surface, cmap="gray", vmin=0, vmax=1); ax[1, 0].set_title("surface (scored pixels)", fontsize=7)
            for i, (lab, d, tag) in enumerate(imgs):
                im = load(d, "pcf_shown", 59, size)
                if im is None: im = load(d, "pcf_accumulated", 59, size)
                ax[0, i + 1].imshow(im, cmap="gray", vmin=0, vmax=1)
                ax[0, i + 1].set_title(lab, fontsize=7)
                ax[1, i + 1].imshow(np.abs(im - ref) * surface, cmap="magma", vmin=0, vmax=0.5)
                ax[1, i + 1].set_title("|error| (0..0.5), RMSE %.4f" % rmse_on(im, ref, surface), fontsize=7)
            for q in ax.flat: q.set_xticks([]); q.set_yticks([])
            fig.tight_layout(); fig.savefig(os.path.join(a.docs, "pcf_steps.png"), dpi=110); plt.close(fig)
            md.append("![PCF steps, frame 60](pcf_steps.png)\n")

    if "C" not in a.skip:
        md.append("## C. PCF confidence: RMSE against frames since the reset (still camera, the torus moves)\n")
        pc = ["--signals", "pcf", "--frames", "64", "--reference-every", "1", "--static-camera"]
        md.append("`rrc-sample %s [--pcf-confidence]`\n" % " ".join(pc))
        res = {}
        for tag, extra in [("plain", []), ("confidence", ["--pcf-confidence"])]:
            d = os.path.join(a.out, "conf_" + tag)
            run(a.sample, d, pc + extra, log)
            res[tag] = [r for r in rows(os.path.join(d, "errors.csv")) if r["signal"] == "pcf"]
        fig, ax = plt.subplots(figsize=(6, 4))
        for tag, e in res.items():
            ax.plot([int(r["frame"]) + 1 for r in e], [num(r["rmse_accumulated"]) for r in e], label=tag + ", against the disk mean")
        e = res["confidence"]
        ax.plot([int(r["frame"]) + 1 for r in e], [num(r["rmse_accumulated_vs_weighted"]) for r in e], "--",
                label="confidence, against the weighted disk mean")
        ax.set_xscale("log"); ax.set_xlabel("frames since the reset"); ax.set_ylabel("RMSE"); ax.legend(fontsize=7); ax.grid(alpha=0.3, which="both")
        fig.tight_layout(); fig.savefig(os.path.join(a.docs, "pcf_confidence.png"), dpi=110); plt.close(fig)
        md.append("| frames since reset | plain | confidence (vs disk mean) | confidence (vs weighted mean) | weighted mean vs disk mean |\n|---|---|---|---|---|")
        for i in [0, 1, 3, 7, 15, 31, 63]:
            if i < len(e):
                md.append("| %d | %.4f | %.4f | %.4f | %.4f |" % (i + 1, num(res["plain"][i]["rmse_accumulated"]), num(e[i]["rmse_accumulated"]),
                          num(e[i]["rmse_accumulated_vs_weighted"]), num(e[i]["rmse_weighted_vs_target"])))
        md.append("\n![confidence](pcf_confidence.png)\n")

    md.append("## Runs\n\n| command | exit | seconds |\n|---|---|---|")
    for c, rc, s in log:
        md.append("| `%s` | %d | %.1f |" % (c, rc, s))
    with open(os.path.join(a.docs, "tables.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
