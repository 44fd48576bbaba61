#!/usr/bin/python3
"""Error against render time: rrc-accumulate on Cycles sequences against brute-force samples.

Development script (no test runs it; CI has no Blender).  docs/measurements/OFFLINE.md,
section 7, gives the results and how the preset's defaults follow from them.

    python3 host_sample/tools/accumulate/blender/error_study.py WORK_DIR \\
        [--tool build/.../rrc-accumulate] [--size 96x64] [--frames 24] [--ref-spp 1024] [--seeds 4] \\
        [--decompose BLEND,VALUE,FILTER ...] [--scene-args 'KEY=VALUE ...'] [--spps 1,2,4,8,16] \
        [--timing-frames 12] [--centre-spp 256]
    python3 host_sample/tools/accumulate/blender/error_study.py WORK_DIR --evaluate NAME \
        [--tool ...] [--rrc-args 'OPTIONS'] [--eval-signal SPEC ...] [--spp 1] [--split-ids A-B] [--clean-input]

The second form renders nothing: it evaluates rrc-accumulate settings on the
renders a first run left in WORK_DIR (it reads that run's size, frames,
spps and scene from WORK_DIR/study.json).  For each setting (the preset's own
defaults, i.e. no --signal, then every --eval-signal SPEC, given as
rrc-accumulate's --signal takes it), with --rrc-args appended to every
rrc-accumulate command, it prints and writes to WORK_DIR/evaluate/NAME.md the
RMSE over frames >= --from against the reference, its ratio to the 4-spp
RMSE, and the decomposition below.  Re-measuring the preset with a new option
on the 320x180 sequences of docs/measurements/OFFLINE.md, section 7:

    for s in strafe_a strafe_b; do
      nice -n 10 /usr/bin/python3 host_sample/tools/accumulate/blender/error_study.py /work/blender_seqs/$s \
        --tool build/release/bin/rrc-accumulate --evaluate mytry --rrc-args '--some-option value' \
        --eval-signal 'ViewLayer.Combined:lambda=0.8,blend=age_aware,filter=catmull_rom'
    done

--clean-input (with --evaluate) feeds rrc-accumulate the reference renders
themselves (colours, depth, vectors, ids): the RMSE of its output against
those same frames is what rrc adds to a clean input (the decomposition's
"blur and lag", measured directly); it writes WORK_DIR/evaluate/NAME.md with
that RMSE, its ratio to the 4-spp RMSE and where the squared error lies.
That split (in both modes): the pixels whose object index (IndexOB) lies
in --split-ids A-B (thin geometry: the fence's poles are 10-24), then the
other pixels younger than --young (4) samples after the frame (the output's
age channel: misses, disocclusions), then the rest; each as a share of the
MSE over frames >= --from and of the pixels.  On the fence sequence:

    nice -n 15 /usr/bin/python3 host_sample/tools/accumulate/blender/error_study.py /work/blender_seqs/fence \
      --tool build/release/bin/rrc-accumulate --evaluate clean --clean-input --split-ids 10-24

The decomposition assumes that rrc is linear in the samples for a fixed
geometry (decompose()); an option whose weights depend on the colours (a lag
detector, a clamp) makes its variance / blur-and-lag / centre split
approximate, and the seeds columns (independent sequences, no model) are then
the check.

Needs Debian's blender (3.4.1), python3-numpy, python3-openimageio and, for
the figure, python3-matplotlib; rrc-accumulate runs on any Vulkan device
(lavapipe: VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json).

What it does, all under WORK_DIR (renders and rrc runs are kept and reused
while their command, and for rrc the tool, are unchanged):
  1. Renders render_check_scene.py (moving camera, moving sphere, soft sun
     shadow, checkered ground; --scene-args passes it KEY=VALUE options for
     another camera path, mover, pillars or the fence) at --spps (1, 2, 4, 8 and 16) spp
     with an animated seed
     (base seed 0), a reference at --ref-spp with another base seed, a
     centre-sampled image (pixel filter 0.01 px, --centre-spp: what a frame's
     first sample converges to, for Cycles puts it at the pixel centre), and
     --seeds more 1-spp sequences with base seeds 1.. for the bias/variance
     check.  Times come from separate short renders (--timing-frames,
     --timing-repeats; 1..64 spp): Blender's log gives each frame's render
     time and the times of its first and last "Sample i/N" lines; path
     tracing is the time between them, the rest of the frame (scene sync,
     BVH, film, writing) the fixed cost, what the log's total adds Blender's
     start-up; a least-squares fit time = F + c * spp checks them.
     --timing-frames 0 skips them and takes the times from the sequences'
     own renders (on a busy machine, upper bounds).
  2. Runs rrc-accumulate --preset blender on the 1- and 2-spp sequences (those of --spps) with
     every candidate --signal setting (blend fixed / age_aware with lambda,
     running_mean with max_age; bilinear and catmull_rom history) and reads
     the RMSE against the reference from its --metrics CSV.  The error is
     over frames >= --from (8): every pixel, R, G and B, as the CSV counts it.
     Brute force is the same CSV's input RMSE.  rrc-accumulate's own cost is
     timed without --reference.
  3. Splits the MSE of chosen settings (--decompose; default the best of each
     blend at 1 spp) into variance, blur and lag, and centre sampling; see
     decompose().  The --seeds independent sequences check it.
  4. Writes WORK_DIR/results.json, WORK_DIR/results.md (the tables) and
     WORK_DIR/fronts.png (RMSE against time per frame).
"""
import argparse
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "render_check_scene.py")
LAYER = "ViewLayer.Combined"
RGB = [LAYER + ".R", LAYER + ".G", LAYER + ".B"]
TIMING_SPPS = [1, 2, 4, 8, 16, 64]


def log(*a):
    print(*a, flush=True)


# ---------------------------------------------------------------- rendering

def clock(text):
    """'MM:SS.ss' or 'HH:MM:SS.ss' -> seconds."""
    s = 0.0
    for part in text.split(":"):
        s = s * 60 + float(part)
    return s


def parse_blender_log(text):
    """Per frame: total render time (Blender's ' Time:' line, saving excluded) and path tracing
    time (first to last 'Sample i/N' progress line)."""
    frames, current = {}, {}
    sample = re.compile(r"^Fra:(\d+) .*\| Time:([\d:.]+) \|.*\| Sample (\d+)/(\d+)")
    total = re.compile(r"^ Time: ([\d:.]+) \(Saving: ([\d:.]+)\)")
    saved = re.compile(r"^Saved: '.*?(\d+)\.exr'")
    last_saved = None
    for line in text.splitlines():
        m = sample.match(line)
        if m:
            f, t = int(m.group(1)), clock(m.group(2))
            d = current.setdefault(f, {})
            d.setdefault("pt_start", t)
            d["pt_end"] = t
            continue
        m = saved.match(line)
        if m:
            last_saved = int(m.group(1))
            continue
        m = total.match(line)
        if m and last_saved is not None:
            d = current.get(last_saved, {})
            frames[last_saved] = {"total": clock(m.group(1)) - clock(m.group(2)), "saving": clock(m.group(2)),
                                  "path_tracing": d.get("pt_end", 0.0) - d.get("pt_start", 0.0)}
    return frames


def render(work, name, spp, seed, args, extra=(), frames=None):
    frames = frames or args.frames
    extra = list(extra) + args.scene_args.split()
    out = os.path.join(work, name)
    info_path = os.path.join(out, "render.json")
    if os.path.exists(info_path):
        with open(info_path) as fp:
            info = json.load(fp)
        if info.get("key") == [spp, seed, args.size, frames] + list(extra):
            return info
    os.makedirs(out, exist_ok=True)
    cmd = ["blender", "-b", "--factory-startup", "--python", SCENE, "--", out, str(spp), "float", "seed",
           str(frames), "seed=%d" % seed, "size=" + args.size] + extra
    log("render", name, ":", " ".join(cmd))
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.monotonic() - t0
    with open(os.path.join(out, "blender.log"), "w") as fp:
        fp.write(p.stdout)
    if p.returncode != 0:
        sys.exit("blender failed, see " + os.path.join(out, "blender.log"))
    parsed = parse_blender_log(p.stdout)
    if sorted(parsed) != list(range(1, frames + 1)):
        sys.exit("could not read every frame's time from " + os.path.join(out, "blender.log"))
    info = {"key": [spp, seed, args.size, frames] + list(extra), "spp": spp, "seed": seed, "wall": wall,
            "frames": {str(k): v for k, v in parsed.items()}}
    with open(info_path, "w") as fp:
        json.dump(info, fp, indent=1)
    return info


def frame_times(info):
    """Median per-frame times over frames 2.. (frame 1 also loads the kernels; the median, as the machine may be shared)."""
    fr = [v for k, v in info["frames"].items() if int(k) >= 2]
    tot = np.median([v["total"] for v in fr])
    pt = np.median([v["path_tracing"] for v in fr])
    first = info["frames"]["1"]["total"]
    startup = info["wall"] - sum(v["total"] + v["saving"] for v in info["frames"].values())
    return {"total": tot, "path_tracing": pt, "fixed": tot - pt, "first_frame": first, "startup": startup}


# ---------------------------------------------------------------- images

def read_rgb(path):
    buf = oiio.ImageBuf(path)
    spec = buf.spec()
    names = list(spec.channelnames)
    px = buf.get_pixels(oiio.FLOAT)
    if px is None or px.size == 0:
        sys.exit("cannot read " + path)
    idx = [names.index(c) for c in RGB]
    return np.asarray(px)[:, :, idx].astype(np.float64)


def read_channel(path, name):
    buf = oiio.ImageBuf(path)
    names = list(buf.spec().channelnames)
    return np.asarray(buf.get_pixels(oiio.FLOAT))[:, :, names.index(name)]


AGE_GROUPS = (("background (age 0)", 0, 0), ("miss (age 1)", 1, 1), ("age 2-4", 2, 4), ("age 5-15", 5, 15),
              ("age >= 16", 16, 1 << 30))


def write_expected(src, centre, ref, n, dst):
    """dst = src's every channel (its geometry), with Combined = what an n-spp
    frame converges to: (centre + (n - 1) * reference) / n.  Cycles puts a
    frame's sample 0 at the pixel centre whatever the seed (it writes Depth
    and IndexOB from that sample alone), the others over the pixel filter."""
    buf = oiio.ImageBuf(src)
    spec = buf.spec()
    names = list(spec.channelnames)
    px = np.array(buf.get_pixels(oiio.FLOAT))
    cols = []
    for path in (centre, ref):
        cbuf = oiio.ImageBuf(path)
        cnames = list(cbuf.spec().channelnames)
        cols.append((np.asarray(cbuf.get_pixels(oiio.FLOAT)), cnames))
    for c in RGB + [LAYER + ".A"]:
        (cp, cn), (rp, rn) = cols
        px[:, :, names.index(c)] = (cp[:, :, cn.index(c)] + (n - 1) * rp[:, :, rn.index(c)]) / n
    outspec = oiio.ImageSpec(spec.width, spec.height, spec.nchannels, oiio.FLOAT)
    outspec.channelnames = tuple(names)
    outspec.attribute("compression", "zip")
    out = oiio.ImageOutput.create(dst)
    if not out or not out.open(dst, outspec) or not out.write_image(px.astype(np.float32)):
        sys.exit("cannot write " + dst + ": " + oiio.geterror())
    out.close()


def expected_sequence(args, work, spp, n):
    """The spp-spp sequence's geometry with the colours an n-spp frame converges to (n = 0: the reference's)."""
    d = os.path.join(work, "expected_%dspp_n%d" % (spp, n))
    if not os.path.exists(os.path.join(d, "frame_%04d.exr" % args.frames)):
        os.makedirs(d, exist_ok=True)
        for f in range(1, args.frames + 1):
            fr = "frame_%04d.exr" % f
            if n == 0:
                write_expected(os.path.join(work, "spp%d" % spp, fr), os.path.join(work, "ref", fr), os.path.join(work, "ref", fr), 1,
                               os.path.join(d, fr))
            else:
                write_expected(os.path.join(work, "spp%d" % spp, fr), os.path.join(work, "centre", fr), os.path.join(work, "ref", fr), n,
                               os.path.join(d, fr))
    return d


# ---------------------------------------------------------------- rrc

def rrc_run(args, work, name, inputs, signal, reference=True):
    out = os.path.join(work, args.rrc_dir, name)
    os.makedirs(out, exist_ok=True)
    cmd = [args.tool, "--preset", "blender", "--input", os.path.join(inputs, "frame_%04d.exr"),
           "--frames", "1-%d" % args.frames, "--output", os.path.join(out, "acc_%04d.exr"), "--progress", "lines"]
    if signal:
        cmd += ["--signal", signal]
    cmd += args.rrc_args.split()
    if reference:
        cmd += ["--reference", os.path.join(work, "ref", "frame_%04d.exr"), "--metrics", os.path.join(out, "metrics.csv")]
    # A run is kept while the command and the tool are unchanged.
    cache = os.path.join(out, "run.json")
    stdout = None
    if os.path.exists(cache) and os.path.getmtime(cache) > os.path.getmtime(args.tool):
        with open(cache) as fp:
            kept = json.load(fp)
        if kept["cmd"] == cmd:
            stdout = kept["stdout"]
    if stdout is None:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if p.returncode != 0:
            sys.exit("rrc-accumulate failed:\n" + " ".join(cmd) + "\n" + p.stdout)
        stdout = p.stdout
        with open(cache, "w") as fp:
            json.dump({"cmd": cmd, "stdout": stdout}, fp)
    run_ms, total_ms = [], []
    for m in re.finditer(r"^frame (\d+):.*?([\d.]+) ms \(rrc_frame_run\), ([\d.]+) ms total", stdout, re.M):
        if int(m.group(1)) >= 2:
            run_ms.append(float(m.group(2)))
            total_ms.append(float(m.group(3)))
    res = {"dir": out, "rrc_frame_run_ms": float(np.mean(run_ms)), "rrc_total_ms": float(np.mean(total_ms))}
    if reference:
        res.update(csv_rmse(os.path.join(out, "metrics.csv"), args.first))
    return res


def csv_rmse(path, first):
    """RMSE over frames >= first from the tool's CSV (per-frame MSE weighted by the value count)."""
    sums = {"input": 0.0, "output": 0.0}
    n = 0
    hit = []
    with open(path) as fp:
        for row in csv.DictReader(fp):
            if int(row["frame"]) < first:
                continue
            v = int(row["values"])
            n += v
            for k in sums:
                sums[k] += float(row[k + "_rmse"]) ** 2 * v
            hit.append(float(row["hit_ratio"]))
    return {"input_rmse": math.sqrt(sums["input"] / n), "output_rmse": math.sqrt(sums["output"] / n),
            "hit_ratio": float(np.mean(hit))}


def signal_spec(blend, value, filt):
    s = LAYER + ":blend=" + blend
    s += (",max_age=%d" % value) if blend == "running_mean" else (",lambda=%g" % value)
    return s + ",filter=" + filt


def label(blend, value, filt):
    v = ("cap %d" % value) if blend == "running_mean" else ("λ %g" % value)
    return "%s %s %s" % (blend, v, filt)


CANDIDATES = ([("fixed", l) for l in (0.6, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95)] +
              [("age_aware", l) for l in (0.6, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95)] +
              [("running_mean", c) for c in (4, 8, 16, 32, 64, 255)])
FILTERS = ("bilinear", "catmull_rom")
PRESET = ("age_aware", 0.85, "bilinear")  # --preset blender's signal (options.h) less its fill=4 and rectify=on, marked in the figure


def mean_sq(a, b, frames):
    return float(np.mean([np.mean((a[f] - b[f]) ** 2) for f in frames]))


def decompose(args, work, spp, cfg, seeds_dirs, spec=None, text=None, name=None):
    """MSE over frames >= first = variance + bias^2, bias^2 = blur and lag + centre sampling.

    rrc is linear in the samples for fixed geometry (its weights depend on
    depth, vectors, ids and ages only), so the mean of its output is rrc
    applied to the mean of its input.  An n-spp Cycles frame's mean is
    (centre + (n - 1) * reference) / n (write_expected), so
      bias^2 = |rrc(expected) - reference|^2,
      blur and lag = |rrc(reference) - reference|^2 (what the filter does to
        converged colours: resampling blur, shading that moves over the
        surface, the edges),
      centre sampling = the rest of the bias (the aliasing of sample 0 that
        the accumulation did not average out),
      variance = MSE - bias^2.
    The --seeds independent 1-spp sequences check it: their per-pixel spread
    is the variance, the error of their mean (less spread / K) the bias."""
    if cfg is not None:  # a sweep setting; else spec (None: the preset's defaults), text and name
        blend, value, filt = cfg
        name = "decomp_%dspp_%s_%g_%s" % (spp, blend, value, filt)
        spec, text = signal_spec(blend, value, filt), label(*cfg)
    frames = range(args.first, args.frames + 1)
    rd = lambda d: {f: read_rgb(os.path.join(d, "acc_%04d.exr" % f)) for f in frames}
    ref = {f: read_rgb(os.path.join(work, "ref", "frame_%04d.exr" % f)) for f in frames}
    noisy = rrc_run(args, work, name, os.path.join(work, "spp%d" % spp), spec)
    of_ref = rrc_run(args, work, name + "_of_ref", expected_sequence(args, work, spp, 0), spec)
    of_mean = rrc_run(args, work, name + "_of_mean", expected_sequence(args, work, spp, spp), spec)
    noisy_px, ref_px, mean_px = rd(noisy["dir"]), rd(of_ref["dir"]), rd(of_mean["dir"])
    res = {"config": text, "spp": spp, "mse": noisy["output_rmse"] ** 2, "rmse": noisy["output_rmse"]}
    res["bias2"] = mean_sq(mean_px, ref, frames)
    res["blur_lag"] = mean_sq(ref_px, ref, frames)
    res["centre"] = res["bias2"] - res["blur_lag"]
    res["variance"] = res["mse"] - res["bias2"]
    # The input itself (brute force at this spp): its bias is the centre sampling alone.
    inp = {f: read_rgb(os.path.join(work, "spp%d" % spp, "frame_%04d.exr" % f)) for f in frames}
    exp_in = {f: read_rgb(os.path.join(expected_sequence(args, work, spp, spp), "frame_%04d.exr" % f)) for f in frames}
    res["input_mse"] = mean_sq(inp, ref, frames)
    res["input_centre"] = mean_sq(exp_in, ref, frames)
    res["input_variance"] = res["input_mse"] - res["input_centre"]
    # Split by the pixel's age after this frame (0: background, 1: a miss or
    # a first sample, ...): each group's share of the MSE and of the bias^2
    # (the sums over the groups are the MSE and the bias^2) and of the pixels.
    ages = {f: read_channel(os.path.join(noisy["dir"], "acc_%04d.exr" % f), LAYER + ".age") for f in frames}
    groups = {}
    npx = sum(ages[f].size for f in frames)
    for gname, lo, hi in AGE_GROUPS:
        e_tot = e_b = cnt = 0.0
        for f in frames:
            m = (ages[f] >= lo) & (ages[f] <= hi)
            e_tot += np.sum(np.mean((noisy_px[f] - ref[f]) ** 2, axis=2)[m])
            e_b += np.sum(np.mean((mean_px[f] - ref[f]) ** 2, axis=2)[m])
            cnt += np.sum(m)
        groups[gname] = {"pixels": cnt / npx, "mse": e_tot / npx, "bias2": e_b / npx}
    res["by_age"] = groups
    # Seeds: K independent sequences through the same setting.
    outs = [rd(rrc_run(args, work, name + "_seed%d" % (k + 1), d, spec, reference=False)["dir"]) for k, d in enumerate(seeds_dirs)]
    if len(outs) >= 2:
        K = len(outs)
        var, b2 = [], []
        for f in frames:
            stack = np.stack([o[f] for o in outs])
            v = np.var(stack, axis=0, ddof=1)
            var.append(np.mean(v))
            b2.append(np.mean((stack.mean(axis=0) - ref[f]) ** 2) - np.mean(v) / K)
        res.update({"seeds": K, "variance_seeds": float(np.mean(var)), "bias2_seeds": float(np.mean(b2))})
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("work")
    ap.add_argument("--tool", default=os.path.join(os.getcwd(), "build/offline/bin/rrc-accumulate"))
    ap.add_argument("--size", default="96x64")
    ap.add_argument("--frames", type=int, default=24)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--ref-seed", type=int, default=1000)
    ap.add_argument("--centre-spp", type=int, default=256, help="samples of the centre-sampled image")
    ap.add_argument("--seeds", type=int, default=4, help="extra independent 1-spp sequences for the bias/variance check")
    ap.add_argument("--timing-frames", type=int, default=12, help="frames of each timing render")
    ap.add_argument("--timing-repeats", type=int, default=2, help="renders of each timing spp (the fastest counts)")
    ap.add_argument("--from", dest="first", type=int, default=8, help="first frame of the error")
    ap.add_argument("--decompose", action="append", default=[],
                    help="BLEND,VALUE,FILTER to decompose (repeatable); default: the best of each blend at 1 spp")
    ap.add_argument("--scene-args", default="", help="KEY=VALUE options for render_check_scene.py, space-separated")
    ap.add_argument("--spps", default="1,2,4,8,16", help="the brute-force sample counts to render (must hold 4)")
    ap.add_argument("--evaluate", metavar="NAME", help="render nothing: evaluate settings on a previous run's renders")
    ap.add_argument("--rrc-args", default="", help="options appended to every rrc-accumulate command (space-separated)")
    ap.add_argument("--eval-signal", action="append", default=[], help="with --evaluate: a --signal SPEC (repeatable)")
    ap.add_argument("--spp", type=int, default=1, help="with --evaluate: the input sequence's spp")
    ap.add_argument("--clean-input", action="store_true",
                    help="with --evaluate: accumulate the reference renders themselves (what rrc adds to a clean input)")
    ap.add_argument("--split-ids", metavar="A-B", default="",
                    help="with --evaluate: split the squared error into the pixels of object indices A..B, the other "
                         "pixels younger than --young samples, and the rest")
    ap.add_argument("--young", type=int, default=4, help="with --evaluate: the age below which a pixel counts as young")
    ap.add_argument("--jitter", action="store_true",
                    help="render the 1- and 2-spp sequences (and the centre-sampled image) with the camera jittered "
                         "through the pixel filter (render_check_scene.py jitter=filter); the reference and the "
                         "brute-force sequences of 4 spp and more stay unjittered")
    ap.add_argument("--jitter-width", type=float, default=1.0,
                    help="with --jitter: the Blackman-Harris width the jitter is drawn through, pixels (1, jitter_camera.py's "
                         "default for the reference's 1.5-px filter)")
    args = ap.parse_args()
    args.rrc_dir = "rrc"
    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)
    if not os.path.exists(args.tool):
        sys.exit("no rrc-accumulate at " + args.tool + " (--tool)")
    if args.evaluate:
        return evaluate(args, work)
    spps = [int(x) for x in args.spps.split(",")]
    if 4 not in spps:
        sys.exit("--spps must hold 4 (the error is a ratio to the 4-spp RMSE)")
    with open(os.path.join(work, "study.json"), "w") as fp:
        json.dump({"size": args.size, "frames": args.frames, "from": args.first, "ref_spp": args.ref_spp, "spps": spps,
                   "scene_args": args.scene_args, "seeds": args.seeds, "jitter": args.jitter and args.jitter_width}, fp, indent=1)

    # 1. Renders and their times.
    # --jitter: the sequences rrc accumulates move their first sample over the
    # pixel filter from frame to frame (docs/measurements/OFFLINE.md, section 7).
    jit = ["jitter=filter", "jitter_width=%g" % args.jitter_width] if args.jitter else []
    renders = {spp: render(work, "spp%d" % spp, spp, 0, args, jit if spp <= 2 else []) for spp in spps}
    ref = render(work, "ref", args.ref_spp, args.ref_seed, args)
    # What a frame's sample 0 converges to: the pixel-centre image (filter width 0.01 px),
    # with --jitter at each frame's jittered centre.
    render(work, "centre", args.centre_spp, args.ref_seed + 1, args, ["filter=0.01"] + jit)
    seed_dirs = []
    for k in range(1, args.seeds + 1):
        render(work, "spp1_seed%d" % k, 1, k, args, jit)
        seed_dirs.append(os.path.join(work, "spp1_seed%d" % k))
    # Times: separate, short renders one after the other (the long renders
    # above may share the machine with other work), each repeated; per spp
    # the repeat with the lowest median frame time.  64 spp fixes the slope.
    times = {}
    timing_spps = TIMING_SPPS if args.timing_frames else spps
    for spp in timing_spps:
        if not args.timing_frames:  # no timing renders: the sequences' own times
            times[spp] = frame_times(renders[spp])
            continue
        reps = [frame_times(render(work, "timing/spp%d_run%d" % (spp, k), spp, 0, args, frames=args.timing_frames))
                for k in range(args.timing_repeats)]
        times[spp] = min(reps, key=lambda t: t["total"])
    times["reference"] = frame_times(ref)
    xs = np.array(timing_spps, dtype=float)
    ys = np.array([times[s]["total"] for s in timing_spps])
    (F, c), *_ = np.linalg.lstsq(np.stack([np.ones_like(xs), xs], axis=1), ys, rcond=None)
    fit = {"fixed_s": float(F), "per_spp_s": float(c)}
    log("per-frame time: %.4f s + %.3f ms x spp (least squares over %s spp)" % (F, 1e3 * c, timing_spps))

    # Where a 1-spp frame's one sample lies: the mean of the independent
    # 1-spp renders (base seeds 0..K) against the filtered reference and
    # against the centre-sampled image; the noise floor is sqrt(spread / (K+1)).
    centre_check = None
    if seed_dirs:
        frames = range(args.first, args.frames + 1)
        to_ref, to_centre, floor = [], [], []
        for f in frames:
            fr = "frame_%04d.exr" % f
            stack = np.stack([read_rgb(os.path.join(d, fr)) for d in [os.path.join(work, "spp1")] + seed_dirs])
            m = stack.mean(axis=0)
            to_ref.append(np.mean((m - read_rgb(os.path.join(work, "ref", fr))) ** 2))
            to_centre.append(np.mean((m - read_rgb(os.path.join(work, "centre", fr))) ** 2))
            floor.append(np.mean(np.var(stack, axis=0, ddof=1)) / len(stack))
        centre_check = {"renders": len(seed_dirs) + 1, "mean_to_reference_rmse": math.sqrt(np.mean(to_ref)),
                        "mean_to_centre_rmse": math.sqrt(np.mean(to_centre)), "noise_floor_rmse": math.sqrt(np.mean(floor))}
        log("mean of %d 1-spp renders: RMSE %.4f to the reference, %.4f to the centre-sampled image (noise floor %.4f)" %
            (centre_check["renders"], centre_check["mean_to_reference_rmse"], centre_check["mean_to_centre_rmse"],
             centre_check["noise_floor_rmse"]))
    # Which way the centre sampling's aliasing runs: motion averages it only
    # along the direction the surface moves under the pixel centres.  Its MSE
    # (centre-sampled image against the reference) as is, after a 9-px box
    # along x and along y (rows / columns away from the ends), and the mean
    # |Vector.X|, |Vector.Y| over the pixels that see geometry (px a frame).
    e, ex, ey, vx, vy = [], [], [], [], []
    box = np.ones(9) / 9
    for f in range(args.first, args.frames + 1):
        fr = "frame_%04d.exr" % f
        d = read_rgb(os.path.join(work, "centre", fr)) - read_rgb(os.path.join(work, "ref", fr))
        e.append(np.mean(d ** 2))
        ex.append(np.mean(np.apply_along_axis(lambda a: np.convolve(a, box, "same"), 1, d)[:, 4:-4] ** 2))
        ey.append(np.mean(np.apply_along_axis(lambda a: np.convolve(a, box, "same"), 0, d)[4:-4] ** 2))
        geometry = read_channel(os.path.join(work, "spp1", fr), "ViewLayer.IndexOB.X") > 0
        vx.append(np.mean(np.abs(read_channel(os.path.join(work, "spp1", fr), "ViewLayer.Vector.X"))[geometry]))
        vy.append(np.mean(np.abs(read_channel(os.path.join(work, "spp1", fr), "ViewLayer.Vector.Y"))[geometry]))
    aliasing = {"centre_mse": float(np.mean(e)), "after_box_x": float(np.mean(ex)), "after_box_y": float(np.mean(ey)),
                "mean_abs_vector_x": float(np.mean(vx)), "mean_abs_vector_y": float(np.mean(vy))}
    log("centre sampling's aliasing: MSE %.3e, after a 9-px box along x %.3e, along y %.3e; mean |Vector| on geometry x %.2f, y %.2f px" %
        (aliasing["centre_mse"], aliasing["after_box_x"], aliasing["after_box_y"], aliasing["mean_abs_vector_x"],
         aliasing["mean_abs_vector_y"]))

    # 2. Brute force and the candidate sweep.
    brute = {}
    for spp in spps:
        r = rrc_run(args, work, "brute_%dspp" % spp, os.path.join(work, "spp%d" % spp), None)
        brute[spp] = {"rmse": r["input_rmse"], **{k: float(v) for k, v in times[spp].items()}}
        log("brute %2d spp: RMSE %.5f" % (spp, r["input_rmse"]))
    sweep = []
    acc_spps = [s for s in (1, 2) if s in spps]
    for spp in acc_spps:
        for blend, value in CANDIDATES:
            for filt in FILTERS:
                r = rrc_run(args, work, "sweep_%dspp_%s_%g_%s" % (spp, blend, value, filt),
                            os.path.join(work, "spp%d" % spp), signal_spec(blend, value, filt))
                row = {"spp": spp, "blend": blend, "value": value, "filter": filt, "rmse": r["output_rmse"],
                       "ratio_to_4spp": r["output_rmse"] / brute[4]["rmse"], "hit_ratio": r["hit_ratio"],
                       "rrc_frame_run_ms": r["rrc_frame_run_ms"], "rrc_total_ms": r["rrc_total_ms"]}
                sweep.append(row)
                log("%d spp %-36s RMSE %.5f (%.3fx 4 spp)  rrc %.2f ms run, %.1f ms total" %
                    (spp, label(blend, value, filt), row["rmse"], row["ratio_to_4spp"], row["rrc_frame_run_ms"],
                     row["rrc_total_ms"]))
    # The tool's own defaults for the preset (whatever this build has), for
    # the record, and its cost without --reference (what a production run
    # pays: read the frame, run, write the output), median of 3 runs.
    r = rrc_run(args, work, "preset_default_1spp", os.path.join(work, "spp1"), None)
    timing = []
    for k in range(3):
        shutil.rmtree(os.path.join(work, "rrc", "timing"), ignore_errors=True)
        timing.append(rrc_run(args, work, "timing", os.path.join(work, "spp1"), None, reference=False))
    timing.sort(key=lambda t: t["rrc_total_ms"])
    preset_default = {"rmse": r["output_rmse"], "ratio_to_4spp": r["output_rmse"] / brute[4]["rmse"],
                      "rrc_total_ms": timing[1]["rrc_total_ms"], "rrc_frame_run_ms": timing[1]["rrc_frame_run_ms"]}
    log("preset defaults at 1 spp: RMSE %.5f (%.3fx 4 spp)" % (preset_default["rmse"], preset_default["ratio_to_4spp"]))

    # 3. Decomposition.
    configs = []
    for d in args.decompose:
        b, v, f = d.split(",")
        configs.append((b, int(v) if b == "running_mean" else float(v), f))
    if not configs:
        for blend in ("fixed", "age_aware", "running_mean"):
            best = min((s for s in sweep if s["spp"] == 1 and s["blend"] == blend), key=lambda s: s["rmse"])
            configs.append((blend, best["value"], best["filter"]))
    decomp = []
    for cfg in configs:
        for spp in acc_spps:
            d = decompose(args, work, spp, cfg, seed_dirs if spp == 1 else [])
            decomp.append(d)
            log("decomposition %d spp %s: MSE %.3e = variance %.3e + blur/lag %.3e + centre sampling %.3e%s" %
                (spp, d["config"], d["mse"], d["variance"], d["blur_lag"], d["centre"],
                 "; seeds: bias^2 %.3e variance %.3e" % (d["bias2_seeds"], d["variance_seeds"]) if "seeds" in d else ""))

    results = {"size": args.size, "scene_args": args.scene_args, "jitter": args.jitter and args.jitter_width, "frames": args.frames, "from": args.first, "ref_spp": args.ref_spp,
               "time_fit": fit, "times": {str(k): {kk: float(vv) for kk, vv in v.items()} for k, v in times.items()},
               "brute": {str(k): v for k, v in brute.items()}, "sweep": sweep, "preset_default": preset_default,
               "decomposition": decomp, "centre_check": centre_check, "aliasing": aliasing,
               "timing_renders": bool(args.timing_frames)}
    with open(os.path.join(work, "results.json"), "w") as fp:
        json.dump(results, fp, indent=1)
    write_markdown(work, results)
    plot(work, results)


def evaluate(args, work):
    """--evaluate NAME: rrc-accumulate settings on a previous run's renders (see the module's doc)."""
    with open(os.path.join(work, "study.json")) as fp:
        st = json.load(fp)
    args.size, args.frames, args.first, args.scene_args = st["size"], st["frames"], st["from"], st["scene_args"]
    args.jitter = st.get("jitter", False)
    if args.jitter is True:  # a study.json written before --jitter-width
        args.jitter = 1.5
    if args.spp not in st["spps"]:
        sys.exit("no %d-spp sequence in %s (it has %s)" % (args.spp, work, st["spps"]))
    args.rrc_dir = os.path.join("evaluate", args.evaluate)
    brute4 = rrc_run(args, work, "brute_4spp", os.path.join(work, "spp4"), None)["input_rmse"]
    if args.clean_input:
        return evaluate_clean(args, work, brute4)
    seed_dirs = [os.path.join(work, "spp1_seed%d" % k) for k in range(1, st["seeds"] + 1)] if args.spp == 1 else []
    rows = []
    for i, spec in enumerate([None] + args.eval_signal):
        text = spec or "the preset's defaults"
        d = decompose(args, work, args.spp, None, seed_dirs, spec=spec, text=text, name="eval%d_%dspp" % (i, args.spp))
        d["ratio_to_4spp"] = d["rmse"] / brute4
        d["regions"] = region_split(args, work, os.path.join(work, args.rrc_dir, "eval%d_%dspp" % (i, args.spp)),
                                    os.path.join(work, "spp%d" % args.spp))
        rows.append(d)
        log("%s: RMSE %.5f = %.3fx 4 spp; MSE %.3e = variance %.3e + blur/lag %.3e + centre sampling %.3e" %
            (text, d["rmse"], d["ratio_to_4spp"], d["mse"], d["variance"], d["blur_lag"], d["centre"]))
    L = ["Sequence %s (%s, %d frames, render_check_scene.py %s%s), %d spp, error over frames %d..%d" %
         (work, args.size, args.frames, args.scene_args or "(the check scene)", " jitter=filter jitter_width=%g" % args.jitter if args.jitter else "",
          args.spp, args.first, args.frames), "",
         "Command: " + " ".join(sys.argv), "",
         "rrc-accumulate --preset blender %s [--signal SPEC]; 4-spp RMSE %.5f" % (args.rrc_args, brute4), "",
         "| setting | RMSE | / 4-spp RMSE | MSE | variance | blur and lag | centre sampling | seeds: variance | seeds: bias² |",
         "|---|---|---|---|---|---|---|---|---|"]
    pc = lambda x, d: "%.2e (%.0f%%)" % (x, 100 * x / d["mse"])
    for d in rows:
        L.append("| %s | %.5f | %.3f | %.3e | %s | %s | %s | %s | %s |" %
                 (d["config"], d["rmse"], d["ratio_to_4spp"], d["mse"], pc(d["variance"], d), pc(d["blur_lag"], d),
                  pc(d["centre"], d), "%.2e" % d["variance_seeds"] if "seeds" in d else "",
                  "%.2e" % d["bias2_seeds"] if "seeds" in d else ""))
    L += region_table(args, rows)
    os.makedirs(os.path.join(work, "evaluate"), exist_ok=True)
    with open(os.path.join(work, "evaluate", args.evaluate + ".md"), "w") as fp:
        fp.write("\n".join(L) + "\n")
    log("\n".join(L))


def region_split(args, work, out_dir, inputs):
    """Shares of the MSE over frames >= --from (and of the pixels) of: the --split-ids objects' pixels (the
    input frame's IndexOB), the other pixels younger than --young after the frame (the output's age), the rest."""
    lo, hi = (int(v) for v in args.split_ids.split("-")) if args.split_ids else (None, None)
    names = (["ids %d-%d" % (lo, hi)] if args.split_ids else []) + ["age < %d" % args.young, "the rest"]
    err, cnt, total, npx = dict.fromkeys(names, 0.0), dict.fromkeys(names, 0.0), 0.0, 0
    for f in range(args.first, args.frames + 1):
        acc = os.path.join(out_dir, "acc_%04d.exr" % f)
        e = np.mean((read_rgb(acc) - read_rgb(os.path.join(work, "ref", "frame_%04d.exr" % f))) ** 2, axis=2)
        young = read_channel(acc, LAYER + ".age") < args.young
        rest = np.ones_like(young)
        if args.split_ids:
            ids = np.rint(read_channel(os.path.join(inputs, "frame_%04d.exr" % f), "ViewLayer.IndexOB.X"))
            obj = (ids >= lo) & (ids <= hi)
            err[names[0]] += np.sum(e[obj]); cnt[names[0]] += np.sum(obj)
            young &= ~obj
            rest &= ~obj
        rest &= ~young
        err[names[-2]] += np.sum(e[young]); cnt[names[-2]] += np.sum(young)
        err[names[-1]] += np.sum(e[rest]); cnt[names[-1]] += np.sum(rest)
        total += np.sum(e)
        npx += e.size
    return {n: {"mse_share": err[n] / total, "pixels": cnt[n] / npx} for n in names}


def region_table(args, rows):
    names = list(rows[0]["regions"])
    L = ["", "Where the squared error lies (frames %d..%d; share of the MSE, share of the pixels):" % (args.first, args.frames), "",
         "| setting | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
    for d in rows:
        L.append("| %s | %s |" % (d["config"], " | ".join("%.0f%% of the MSE, %.1f%% px" % (100 * d["regions"][n]["mse_share"],
                                                                                         100 * d["regions"][n]["pixels"]) for n in names)))
    return L


def evaluate_clean(args, work, brute4):
    """--evaluate NAME --clean-input: rrc-accumulate on the reference renders, measured against them."""
    rows = []
    inputs = os.path.join(work, "ref_as_input")  # rrc-accumulate refuses a reference pattern equal to the input's
    if not os.path.lexists(inputs):
        os.symlink("ref", inputs)
    for i, spec in enumerate([None] + args.eval_signal):
        text = spec or "the preset's defaults"
        r = rrc_run(args, work, "clean%d" % i, inputs, spec)
        d = {"config": text, "rmse": r["output_rmse"], "ratio_to_4spp": r["output_rmse"] / brute4, "hit_ratio": r["hit_ratio"],
             "regions": region_split(args, work, r["dir"], os.path.join(work, "ref"))}
        rows.append(d)
        log("%s on the clean input: RMSE %.5f = %.3fx 4 spp (hit ratio %.1f%%)" % (text, d["rmse"], d["ratio_to_4spp"],
                                                                                100 * d["hit_ratio"]))
    L = ["Sequence %s (%s, %d frames, render_check_scene.py %s): the reference renders as the input, error over frames %d..%d" %
         (work, args.size, args.frames, args.scene_args or "(the check scene)", args.first, args.frames), "",
         "Command: " + " ".join(sys.argv), "",
         "rrc-accumulate --preset blender %s [--signal SPEC] on the reference; 4-spp RMSE %.5f" % (args.rrc_args, brute4), "",
         "| setting | RMSE | / 4-spp RMSE | MSE | hit ratio |", "|---|---|---|---|---|"]
    for d in rows:
        L.append("| %s | %.5f | %.3f | %.3e | %.1f%% |" % (d["config"], d["rmse"], d["ratio_to_4spp"], d["rmse"] ** 2,
                                                         100 * d["hit_ratio"]))
    L += region_table(args, rows)
    os.makedirs(os.path.join(work, "evaluate"), exist_ok=True)
    with open(os.path.join(work, "evaluate", args.evaluate + ".md"), "w") as fp:
        fp.write("\n".join(L) + "\n")
    log("\n".join(L))


def write_markdown(work, R):
    L = []
    L.append("Sequence: %s, %d frames, render_check_scene.py %s; reference %d spp%s" %
             (R["size"], R["frames"], R.get("scene_args") or "(the check scene)", R["ref_spp"],
              "; the 1- and 2-spp sequences and the centre-sampled image jittered through a %g-px Blackman-Harris filter"
              " (jitter=filter)" % R["jitter"] if R.get("jitter") else ""))
    L.append("")
    L.append("Per-frame times (medians over frames 2.. of the %s, the reference's own; seconds): total = path tracing + fixed" %
             ("timing renders" if R.get("timing_renders", True) else "sequences' own renders"))
    L.append("")
    L.append("| spp | total | path tracing | fixed | first frame | Blender start-up (per run) |")
    L.append("|---|---|---|---|---|---|")
    for k, t in sorted(R["times"].items(), key=lambda kv: int(kv[0]) if kv[0].isdigit() else 1 << 30):
        L.append("| %s | %.3f | %.3f | %.3f | %.3f | %.2f |" % (k, t["total"], t["path_tracing"], t["fixed"], t["first_frame"],
                                                               t["startup"]))
    L.append("")
    f = R["time_fit"]
    L.append("Least-squares fit over the timing renders: time = %.4f s + %.3f ms x spp" % (f["fixed_s"], 1e3 * f["per_spp_s"]))
    L.append("")
    c = R.get("centre_check")
    if c:
        L.append("Mean of %d independent 1-spp renders: RMSE %.4f to the reference, %.4f to the centre-sampled image"
                 " (noise floor %.4f)" % (c["renders"], c["mean_to_reference_rmse"], c["mean_to_centre_rmse"], c["noise_floor_rmse"]))
        L.append("")
    a = R.get("aliasing")
    if a:
        L.append("Centre sampling's aliasing (centre-sampled image against the reference, frames %d..): MSE %.3e; after a"
                 " 9-px box along x %.3e, along y %.3e; mean |Vector.X| %.2f px, |Vector.Y| %.2f px a frame where there is geometry" %
                 (R["from"], a["centre_mse"], a["after_box_x"], a["after_box_y"], a["mean_abs_vector_x"], a["mean_abs_vector_y"]))
        L.append("")
    L.append("Brute force (RMSE over frames %d..%d against %d spp):" % (R["from"], R["frames"], R["ref_spp"]))
    L.append("")
    L.append("| spp | RMSE | RMSE x sqrt(spp) | path tracing s/frame | total s/frame |")
    L.append("|---|---|---|---|---|")
    for k, b in sorted(R["brute"].items(), key=lambda kv: int(kv[0])):
        L.append("| %s | %.5f | %.4f | %.3f | %.3f |" % (k, b["rmse"], b["rmse"] * math.sqrt(int(k)), b["path_tracing"], b["total"]))
    L.append("")
    L.append("Sweep (rrc-accumulate --preset blender --signal ViewLayer.Combined:...):")
    L.append("")
    L.append("| spp | blend | λ / max_age | filter | RMSE | / 4-spp RMSE | rrc ms/frame (run / total) |")
    L.append("|---|---|---|---|---|---|---|")
    for s in R["sweep"]:
        L.append("| %d | %s | %g | %s | %.5f | %.3f | %.2f / %.1f |" % (s["spp"], s["blend"], s["value"], s["filter"], s["rmse"],
                                                                   s["ratio_to_4spp"], s["rrc_frame_run_ms"], s["rrc_total_ms"]))
    L.append("")
    p = R["preset_default"]
    L.append("This build's preset defaults at 1 spp: RMSE %.5f (%.3f x 4 spp); rrc-accumulate without --reference: %.1f ms a frame"
             " (%.2f ms of it rrc_frame_run)" % (p["rmse"], p["ratio_to_4spp"], p["rrc_total_ms"], p["rrc_frame_run_ms"]))
    L.append("")
    L.append("Decomposition (MSE over frames %d..%d; shares of the MSE):" % (R["from"], R["frames"]))
    L.append("")
    L.append("| spp | setting | RMSE | MSE | variance | blur and lag | centre sampling | seeds: variance | seeds: bias² | input: variance | input: centre sampling |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|")
    pc = lambda x, d: "%.2e (%.0f%%)" % (x, 100 * x / d["mse"])
    for d in R["decomposition"]:
        L.append("| %d | %s | %.5f | %.3e | %s | %s | %s | %s | %s | %.2e | %.2e |" %
                 (d["spp"], d["config"], d["rmse"], d["mse"], pc(d["variance"], d), pc(d["blur_lag"], d), pc(d["centre"], d),
                  "%.2e" % d["variance_seeds"] if "seeds" in d else "", "%.2e" % d["bias2_seeds"] if "seeds" in d else "",
                  d["input_variance"], d["input_centre"]))
    L.append("")
    L.append("Where the MSE is, by the pixel's age after the frame (share of the MSE; bias² share of the MSE; share of the pixels):")
    L.append("")
    L.append("| spp | setting | " + " | ".join(g[0] for g in AGE_GROUPS) + " |")
    L.append("|---|---|" + "---|" * len(AGE_GROUPS))
    for d in R["decomposition"]:
        cells = []
        for g in AGE_GROUPS:
            b = d["by_age"][g[0]]
            cells.append("%.0f%% (bias² %.0f%%), %.1f%% px" % (100 * b["mse"] / d["mse"], 100 * b["bias2"] / d["mse"], 100 * b["pixels"]))
        L.append("| %d | %s | %s |" % (d["spp"], d["config"], " | ".join(cells)))
    with open(os.path.join(work, "results.md"), "w") as fp:
        fp.write("\n".join(L) + "\n")
    log("\n".join(L))


def plot(work, R):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("no matplotlib: no figure")
        return
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), dpi=80)
    for ax, key, title in ((axes[0], "path_tracing", "path-tracing time per frame"), (axes[1], "total", "render time per frame (incl. fixed)")):
        bx = [R["brute"][k][key] for k in sorted(R["brute"], key=int)]
        by = [R["brute"][k]["rmse"] for k in sorted(R["brute"], key=int)]
        ax.plot(bx, by, "ko-", label="brute force")
        for k, x, y in zip(sorted(R["brute"], key=int), bx, by):
            ax.annotate(k, (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)
        marks = {"fixed": "s", "age_aware": "^", "running_mean": "v"}
        for spp, colour in ((1, "tab:blue"), (2, "tab:orange")):
            if not any(s["spp"] == spp for s in R["sweep"]):
                continue
            base = R["brute"][str(spp)][key]
            for blend in marks:
                rows = [s for s in R["sweep"] if s["spp"] == spp and s["blend"] == blend]
                cost = R["preset_default"]["rrc_total_ms"] / 1e3  # per frame, without --reference
                ax.plot([base + cost for s in rows], [s["rmse"] for s in rows], marks[blend], color=colour,
                        alpha=0.7, label="rrc %d spp %s" % (spp, blend) if ax is axes[0] else None)
            preset = [s for s in R["sweep"] if s["spp"] == spp and (s["blend"], s["value"], s["filter"]) == PRESET]
            ax.plot([base + R["preset_default"]["rrc_total_ms"] / 1e3 for s in preset], [s["rmse"] for s in preset], "*", ms=11,
                    color=colour, mec="k", label="rrc %d spp, the preset" % spp if ax is axes[0] else None)
        ax.axhline(0.85 * R["brute"]["4"]["rmse"], color="grey", ls="--", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel(title + " [s] (+ rrc's)")
        ax.set_ylabel("RMSE, frames %d.." % R["from"])
        ax.grid(True, which="both", lw=0.3)
    axes[0].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(work, "fronts.png"))
    log("figure:", os.path.join(work, "fronts.png"))


if __name__ == "__main__":
    main()
