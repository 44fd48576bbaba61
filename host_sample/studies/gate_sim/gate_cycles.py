#!/usr/bin/env python3
"""The deviation-bias gate of gate_sim.py on Cycles frames: a numpy model of the offline preset.

  for s in strafe_a strafe_b check96 fence; do
    /usr/bin/python3 host_sample/studies/gate_sim/gate_cycles.py /work/blender_seqs/$s --inputs ref,spp4,spp1
  done

SEQ is a folder that host_sample/tools/accumulate/blender/error_study.py rendered: ref/,
spp4/ and spp1/ hold frame_0001.exr ... (Combined, Depth, Vector, IndexOB). A model, not
rrc: the preset's filter (docs/guide/offline.md, "The preset": AGE_AWARE, lambda 0.85,
bilinear history, motion from Vector.X/Y, a hit where the nearest previous texel's depth is
within 0.04 of this depth, relative, and its IndexOB is this pixel's) without its
rectification and fill. With --kappas other than 0 the gate (gate_sim.deviation_gate, on
the Rec. 709 luminance of sample - history) restarts a pixel's history when it fires; with
--soft it cuts the history's age to gate_sim.balanced_age instead.

Prints, for each input and kappa, the RMSE against ref/ over frames 8-24 as a ratio to the
4-spp input's RMSE, as error_study.py reports rrc-accumulate's, and the hit pixels the gate
restarted (or whose age it cut) a frame (docs/measurements/clean-input.md,
"A temporal gate, simulated").
"""
import argparse
import os

import numpy as np
import OpenImageIO as oiio

from gate_sim import balanced_age, bilinear, deviation_gate, fetch

LUMA = np.array([0.2126, 0.7152, 0.0722])


def load(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        raise SystemExit(f"gate_cycles.py: cannot read {path}: {oiio.geterror()}")
    names = list(image.spec().channelnames)
    pixels = image.read_image(oiio.FLOAT)
    image.close()

    def channel(name):
        return pixels[:, :, names.index("ViewLayer." + name)]

    rgb = np.stack([channel("Combined.R"), channel("Combined.G"), channel("Combined.B")], -1)
    return rgb, channel("Depth.Z"), channel("Vector.X"), channel("Vector.Y"), channel("IndexOB.X")


def frame(seq, folder, f):
    return load(os.path.join(seq, folder, f"frame_{f:04d}.exr"))


def run(seq, folder, kappa, soft, frames, first_scored, lam=0.85, cap=255, tau=0.04):
    squared, restarted = [], []
    hist = None
    for f in range(1, frames + 1):
        sample, depth, vx, vy, ids = frame(seq, folder, f)
        reference = frame(seq, "ref", f)[0]
        h, w = depth.shape
        rows, cols = np.mgrid[0:h, 0:w].astype(float)
        background = depth > 1e9
        if hist is None:
            hist, age = sample.copy(), np.where(background, 0, 1)
            b, s = np.zeros((h, w)), np.zeros((h, w))
        else:
            # The previous frame's sample coordinate (docs/guide/offline.md: pixels, y up), rows downward.
            qx, qy = cols + 0.5 + vx, rows + 0.5 - vy
            ni, nj = np.floor(qx).astype(int), np.floor(qy).astype(int)
            inside = (qx >= 0) & (qx <= w) & (qy >= 0) & (qy <= h)
            hit = (inside & ~background & (np.abs(fetch(prev_depth, ni, nj) - depth) <= tau * depth)
                   & (fetch(prev_ids, ni, nj) == ids))
            resampled = bilinear(hist, qx - 0.5, qy - 0.5)
            n = np.where(hit, fetch(age, ni, nj), 0)
            b, s, fire = deviation_gate(bilinear(b, qx - 0.5, qy - 0.5), bilinear(s, qx - 0.5, qy - 0.5),
                                        (sample - resampled) @ LUMA, n, kappa, cap)
            if not kappa:
                fire[:] = False
            elif soft:
                n, fire = balanced_age(b, s, n, kappa)
            restarted.append(fire[hit].mean())
            n = np.where(fire & ~soft, 0, n)
            lam_eff = np.minimum(lam, n / (n + 1))[..., None]
            hist = np.where((n >= 1)[..., None], lam_eff * resampled + (1 - lam_eff) * sample, sample)
            age = np.where(background, 0, np.minimum(n + 1, cap))
            b, s = np.where(n >= 1, b, 0), np.where(n >= 1, s, 0)
        prev_depth, prev_ids = depth, ids
        if f >= first_scored:
            squared.append(np.mean((hist - reference) ** 2))
    return float(np.sqrt(np.mean(squared))), float(np.mean(restarted))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("seq", help="a sequence folder with ref/, spp4/ and the --inputs folders")
    ap.add_argument("--inputs", default="ref,spp4,spp1", help="input folders (default ref,spp4,spp1)")
    ap.add_argument("--kappas", default="0,1,1.5,2,2.5", help="gate thresholds, 0 = no gate (default 0,1,1.5,2,2.5)")
    ap.add_argument("--soft", action="store_true", help="cut the history's age to gate_sim.balanced_age instead of restarting it")
    ap.add_argument("--frames", type=int, default=24)
    ap.add_argument("--from", dest="first", type=int, default=8, help="first scored frame (default 8)")
    args = ap.parse_args()
    four = np.sqrt(np.mean([np.mean((frame(args.seq, "spp4", f)[0] - frame(args.seq, "ref", f)[0]) ** 2)
                            for f in range(args.first, args.frames + 1)]))
    name = os.path.basename(os.path.normpath(args.seq))
    print(f"{name}: 4-spp RMSE {four:.4f}; output RMSE / 4-spp RMSE (restarted: hit pixels a frame)")
    for folder in args.inputs.split(","):
        for kappa in (float(k) for k in args.kappas.split(",")):
            err, frac = run(args.seq, folder, kappa, args.soft, args.frames, args.first)
            print(f"| {name} | {folder} | {kappa:g} | {err / four:.3f} | {100 * frac:.1f} % |", flush=True)


if __name__ == "__main__":
    main()
