# Keys a sub-pixel camera jitter into a Blender scene, so that a 1- or
# 2-sample Cycles sequence accumulated by rrc-accumulate converges to the
# pixel-filtered image instead of the pixel-centre one (docs/measurements/OFFLINE.md,
# section 1, step 4, and section 7, "Jittering the camera").
#
#   blender -b scene.blend --python jitter_camera.py -- [--width W] [--save] [--json FILE]
#
# Cycles puts a frame's first sample at the pixel centre whatever the seed, so
# an accumulated 1-sample sequence averages point samples of the image.  This
# shifts the scene camera each frame f of the scene's range by the Halton
# (2, 3) point f + 1, drawn through a Blackman-Harris filter of width W
# pixels (Cycles' pixel filter, narrowed): over the frames the first sample
# sweeps the pixel as a many-sample render's samples sweep the filter.  The
# default W is JITTER_SHARE (2/3) of the scene's filter width, 1 px for
# Cycles' 1.5: rrc's resampled history adds its own blur, and on the
# 320x180 sequences of docs/measurements/OFFLINE.md, section 7, 1 px beat the full 1.5.  The shift is keyed with constant interpolation on top of the
# camera's own (static) shift_x / shift_y; Cycles' Vector pass leaves the
# shift out, so the vectors stay unjittered.  Give rrc-accumulate no jitter
# (no --camera "jitter"): each jittered frame is a sample of the filtered
# pixel, which is what the history holds.
#
#   --width W     the jitter's Blackman-Harris width in pixels (default
#                 2/3 of the scene's filter width)
#   --save        save the .blend (otherwise only this Blender session has it)
#   --json FILE   write {"frame": [x, y], ...}: each frame's offset in pixels,
#                 x right, y down
import json
import math
import sys

# The jitter's width as a share of the pixel filter's (docs/measurements/OFFLINE.md, section 7, "The
# spatial fill and a jittered camera": 1 px against 1.5 px took strafe_b from 0.921x to
# 0.829x the 4-sample RMSE with the preset of then, strafe_a from 0.809x to 0.816x; with the
# rectified preset, "Rectification, and a sequence held out", from 0.913x to 0.813x and
# from 0.800x to 0.721x).
JITTER_SHARE = 2.0 / 3.0


def halton(i, base):
    """The radical inverse of i in base: the Halton sequence's i-th value."""
    f, r = 1.0, 0.0
    while i > 0:
        f /= base
        r += f * (i % base)
        i //= base
    return r


def filter_offset(u, width):
    """The offset, in pixels, at which Cycles' 1-D Blackman-Harris pixel filter of this width has
    cumulative weight u: sampling u uniformly draws offsets as Cycles draws each axis of its
    samples.  Cycles' filter_table() doubles a Blackman-Harris width: the window spans
    [-width, width] pixels."""
    n = 2048
    xs = [width * (2.0 * i / n - 1.0) for i in range(n + 1)]
    w = [0.35875 - 0.48829 * math.cos(t) + 0.14128 * math.cos(2 * t) - 0.01168 * math.cos(3 * t)
         for t in (2.0 * math.pi * (x / (2.0 * width) + 0.5) for x in xs)]
    cdf = [0.0]
    for i in range(n):
        cdf.append(cdf[-1] + 0.5 * (w[i] + w[i + 1]))
    u *= cdf[-1]
    for i in range(n):
        if cdf[i + 1] >= u:
            return xs[i] + (xs[i + 1] - xs[i]) * (u - cdf[i]) / max(cdf[i + 1] - cdf[i], 1e-30)
    return xs[-1]


def jitter(frame, width):
    """Frame f's offset from the pixel centre, pixels, x right and y down."""
    return filter_offset(halton(frame + 1, 2), width), filter_offset(halton(frame + 1, 3), width)


def key_jitter(camera_data, frames, width, image_width, image_height):
    """Keys camera_data.shift_x / shift_y at each frame of frames: its static shift plus the
    frame's jitter.  Blender's shift is in units of the image's larger side; +shift_x looks
    right, +shift_y up.  Returns {frame: (x, y)}."""
    ad = camera_data.animation_data
    if ad and ad.action and any(fc.data_path in ("shift_x", "shift_y") for fc in ad.action.fcurves):
        raise ValueError("the camera's shift is already animated; jitter_camera.py keys it itself")
    base_x, base_y = camera_data.shift_x, camera_data.shift_y
    side = float(max(image_width, image_height))
    out = {}
    for f in frames:
        jx, jy = jitter(f, width)
        out[f] = (jx, jy)
        camera_data.shift_x, camera_data.shift_y = base_x + jx / side, base_y - jy / side
        camera_data.keyframe_insert("shift_x", frame=f)
        camera_data.keyframe_insert("shift_y", frame=f)
    for fc in camera_data.animation_data.action.fcurves:
        if fc.data_path in ("shift_x", "shift_y"):
            for k in fc.keyframe_points:
                k.interpolation = 'CONSTANT'
    return out


def main(argv):
    import argparse
    import bpy
    ap = argparse.ArgumentParser(prog="jitter_camera.py", description="key a sub-pixel camera jitter (see the file's head)")
    ap.add_argument("--width", type=float, help="the jitter's Blackman-Harris width in pixels (default: 2/3 of the scene's filter)")
    ap.add_argument("--save", action="store_true", help="save the .blend")
    ap.add_argument("--json", help="write each frame's offset (pixels, x right, y down)")
    args = ap.parse_args(argv)
    scene = bpy.context.scene
    if scene.camera is None:
        sys.exit("jitter_camera.py: the scene has no camera")
    width = args.width if args.width is not None else JITTER_SHARE * scene.cycles.filter_width
    if not width > 0:
        sys.exit("jitter_camera.py: the filter width must be > 0 (got %g)" % width)
    if scene.cycles.pixel_filter_type != 'BLACKMAN_HARRIS':
        print("jitter_camera.py: the scene's pixel filter is %s; the jitter follows Blackman-Harris"
              % scene.cycles.pixel_filter_type)
    pct = scene.render.resolution_percentage / 100.0
    W, H = round(scene.render.resolution_x * pct), round(scene.render.resolution_y * pct)
    try:
        offsets = key_jitter(scene.camera.data, range(scene.frame_start, scene.frame_end + 1), width, W, H)
    except ValueError as e:
        sys.exit("jitter_camera.py: " + str(e))
    print("jitter_camera.py: keyed frames %d-%d of camera '%s' (%dx%d), offsets drawn through a %.3g-px Blackman-Harris filter"
          % (scene.frame_start, scene.frame_end, scene.camera.name, W, H, width))
    if args.json:
        with open(args.json, "w") as fp:
            json.dump({str(f): list(v) for f, v in offsets.items()}, fp, indent=1)
    if args.save:
        bpy.ops.wm.save_mainfile()


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
