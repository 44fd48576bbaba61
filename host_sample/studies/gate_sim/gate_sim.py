#!/usr/bin/env python3
"""Can a per-pixel temporal statistic tell resampling blur from input noise?

  /usr/bin/python3 host_sample/studies/gate_sim/gate_sim.py --size 320x180
  /usr/bin/python3 host_sample/studies/gate_sim/gate_sim.py --size 1280x720

A simulation, not rrc: a plane with fine texture (random sinusoids, 0.01-0.5 cycles a
pixel, standard deviation about 0.21) translates by (5.37, 0.41) px a frame; the input is
the texture at each pixel centre, plus Gaussian noise of the given deviation. The history
is the recursive filter of docs/CONVENTIONS.md, "The recursive filter" (alpha =
max(1 / (age + 1), lambda), lambda 0.1, age cap 16), resampled bilinearly (or with the
clamped Catmull-Rom of docs/CONVENTIONS.md, "Coordinates and jitter"); pixels that
reproject outside the frame start again. A gate restarts a pixel's history (age 0: the
output is its sample) when its statistic says the history disagrees with the samples:

  moments, bilinear  SVGF's second moment m2 = E[x^2], resampled and blended as the value:
                     restart when |x - h| > kappa * sqrt(m2 - h^2)
  moments, nearest   the same with m2 and h fetched from the nearest texel
  deviation bias     the blended mean b and mean square s of d = x - h (rate max(1/(age+1),
                     0.25)): restart when |b| > kappa * sqrt((s - b^2) * rate)

Output: a Markdown table of the output's RMSE against the clean texture over frames 8-24
(the columns 8 px from the right edge, where pixels restart, left out), and the fraction of
pixels each gate restarted a frame (docs/measurements/clean-input.md, "A temporal gate,
simulated").
"""
import argparse

import numpy as np

MOTION = np.array([5.37, 0.41])


def make_texture(rng, count):
    radius = np.exp(rng.uniform(np.log(0.01), np.log(0.5), count))
    theta = rng.uniform(0, 2 * np.pi, count)
    fx, fy = radius * np.cos(theta), radius * np.sin(theta)
    phase = rng.uniform(0, 2 * np.pi, count)
    amp = 0.3 / np.sqrt(count)

    def texture(x, y):
        out = np.full(x.shape, 0.5)
        for i in range(count):
            out += amp * np.sin(2 * np.pi * (fx[i] * x + fy[i] * y) + phase[i])
        return out

    return texture


def fetch(img, x, y):
    h, w = img.shape[:2]
    return img[np.clip(y, 0, h - 1), np.clip(x, 0, w - 1)]


def bilinear(img, x, y):
    """img at (x, y), texel centres at integers (an RGB image: the weights apply to each channel)."""
    i0, j0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - i0, y - j0
    if img.ndim == 3:
        fx, fy = fx[..., None], fy[..., None]
    return ((1 - fx) * (1 - fy) * fetch(img, i0, j0) + fx * (1 - fy) * fetch(img, i0 + 1, j0)
            + (1 - fx) * fy * fetch(img, i0, j0 + 1) + fx * fy * fetch(img, i0 + 1, j0 + 1))


def catmull_rom(img, x, y):
    i0, j0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - i0, y - j0

    def weights(t):
        return [0.5 * (-t**3 + 2 * t**2 - t), 0.5 * (3 * t**3 - 5 * t**2 + 2),
                0.5 * (-3 * t**3 + 4 * t**2 + t), 0.5 * (t**3 - t**2)]

    wx, wy = weights(fx), weights(fy)
    out = sum(wx[a] * wy[b] * fetch(img, i0 + a - 1, j0 + b - 1) for a in range(4) for b in range(4))
    taps = [fetch(img, i0 + a, j0 + b) for a in (0, 1) for b in (0, 1)]
    return np.clip(out, np.minimum.reduce(taps), np.maximum.reduce(taps))


def nearest(img, x, y):
    return fetch(img, np.floor(x).astype(int), np.floor(y).astype(int))


def deviation_gate(b, s, d, n, kappa, cap):
    """The deviation-bias gate: b and s, the blended mean and mean square of d = sample - history
    (resampled to this pixel), take d at the rate max(1 / (min(n, cap) + 1), 0.25), n the samples
    in the history; it fires where the history has at least 2 samples and
    |b| > kappa * sqrt((s - b^2) * rate). Returns the new b, s and where it fired."""
    rate = np.maximum(1.0 / (np.minimum(n, cap) + 1), 0.25)
    b = (1 - rate) * b + rate * d
    s = (1 - rate) * s + rate * d * d
    fire = (np.abs(b) > kappa * np.sqrt(np.maximum(s - b * b, 0) * rate) + 1e-3) & (n >= 2)
    return b, s, fire


def balanced_age(b, s, n, kappa):
    """The soft form of the gate: the history keeps at most the age at which its bias b equals
    kappa standard errors of the deviations, n' = max(1, floor(kappa^2 (s - b^2) / b^2)), where
    that is below its own n (n >= 2). Returns the new n and where it was cut."""
    cap = np.maximum(1, np.floor(kappa * kappa * np.maximum(s - b * b, 0) / np.maximum(b * b, 1e-12)))
    cut = (n >= 2) & (cap < n)
    return np.where(cut, cap, n), cut


def run(texture, size, noise, gate, kappa, resample, seed, frames=25, lam=0.1, cap=16):
    w, h = size
    rng = np.random.default_rng(seed)
    ys, xs = np.mgrid[0:h, 0:w].astype(float)
    # Frame k's pixel centre p sees the plane at p + k * MOTION; frame k - 1 saw it at p + MOTION.
    px, py = xs + MOTION[0], ys + MOTION[1]
    inside = (px <= w - 1) & (py >= 0) & (py <= h - 1)
    hist = None
    errors, restarted = [], []
    for k in range(frames):
        clean = texture(xs + 0.5 + k * MOTION[0], ys + 0.5 + k * MOTION[1])
        x = clean + rng.normal(0, noise, clean.shape) if noise else clean
        if hist is None:
            hist, age, m2, b, s = x.copy(), np.zeros_like(x), x * x, np.zeros_like(x), np.zeros_like(x)
            continue
        hp = resample(hist, px, py)
        prev_age = np.where(inside, nearest(age, px, py), -1)
        restart = np.zeros(x.shape, bool)
        if gate == "moments, bilinear":
            m2p = bilinear(m2, px, py)
            restart = np.abs(x - hp) > kappa * np.sqrt(np.maximum(m2p - hp * hp, 0)) + 1e-3
        elif gate == "moments, nearest":
            m2p, m1p = nearest(m2, px, py), nearest(hist, px, py)
            restart = np.abs(x - hp) > kappa * np.sqrt(np.maximum(m2p - m1p * m1p, 0)) + 1e-3
        elif gate == "deviation bias":  # age counts the frames after the first: n = age + 1
            b, s, restart = deviation_gate(bilinear(b, px, py), bilinear(s, px, py), x - hp, prev_age + 1, kappa, cap)
        restart &= prev_age >= 0
        restarted.append(restart[inside].mean())
        prev_age = np.where(restart, -1, prev_age)
        age = np.minimum(prev_age + 1, cap)
        alpha = np.where(prev_age < 0, 1.0, np.maximum(1.0 / (age + 1), lam))
        hist = (1 - alpha) * hp + alpha * x
        if gate.startswith("moments"):
            m2 = np.where(prev_age < 0, x * x, (1 - alpha) * m2p + alpha * x * x)
        if gate == "deviation bias":
            b, s = np.where(prev_age < 0, 0, b), np.where(prev_age < 0, 0, s)
        if k >= 8:
            errors.append(np.sqrt(np.mean((hist - clean)[:, : w - 8] ** 2)))
    return float(np.mean(errors)), float(np.mean(restarted))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", default="320x180", help="WxH (default 320x180)")
    ap.add_argument("--sinusoids", type=int, default=64, help="terms of the texture (default 64)")
    ap.add_argument("--noise", default="0,0.05,0.15", help="input noise deviations (default 0,0.05,0.15)")
    args = ap.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    texture = make_texture(np.random.default_rng(1), args.sinusoids)
    noises = [float(v) for v in args.noise.split(",")]
    rows = [("none", None, bilinear, "bilinear"), ("none", None, catmull_rom, "Catmull-Rom")]
    for gate in ("moments, bilinear", "moments, nearest", "deviation bias"):
        for kappa in (1.0, 2.0, 3.0):
            rows.append((gate, kappa, bilinear, "bilinear"))
    for kappa in (1.25, 1.5):
        rows.append(("deviation bias", kappa, bilinear, "bilinear"))
    for kappa in (1.0, 1.5):
        rows.append(("deviation bias", kappa, catmull_rom, "Catmull-Rom"))
    print(f"{size[0]}x{size[1]}, texture deviation "
          f"{float(np.std(texture(*np.mgrid[0:size[0], 0:size[1]].astype(float)))):.3f}; "
          "RMSE against the clean texture, frames 8-24 (restarted: pixels a frame)\n")
    print("| gate | kappa | resample | " + " | ".join(f"noise {n}" for n in noises) + " |")
    print("|---|---|---|" + "---|" * len(noises))
    for gate, kappa, resample, name in rows:
        cells = []
        for i, n in enumerate(noises):
            err, frac = run(texture, size, n, gate, kappa, resample, seed=7 + i)
            cells.append(f"{err:.4f}" + (f" ({100 * frac:.1f} %)" if kappa else ""))
        print(f"| {gate} | {kappa if kappa else '-'} | {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
