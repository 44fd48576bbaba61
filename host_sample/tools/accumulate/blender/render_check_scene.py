# Renders a tiny Cycles scene whose geometry and cameras are known exactly,
# so the Depth and Vector passes Blender writes can be checked against them
# (docs/measurements/OFFLINE.md, "2. What Blender writes, measured").  Development aid: no test runs it.
#
#   blender -b --factory-startup --python render_check_scene.py -- OUT_DIR [SAMPLES [float|half [fixed|seed [FRAMES]]]] [KEY=VALUE...]
#
# Writes OUT_DIR/frame_0001.exr ... frame_NNNN.exr (FRAMES, default 3;
# OpenEXR multilayer with Combined, Depth, Vector, IndexOB; Combined in half
# with "half", Blender writes the data passes in float either way; "seed"
# animates Cycles' seed) and OUT_DIR/scene.json: per frame 0..FRAMES+1 the
# camera's world matrix and OpenGL projection, every object's world matrix
# and pass index, the render size.  Motion is linear in the frame number, so
# frame 1 has a previous and the last frame a next frame.
#
# KEY=VALUE options (error_study.py uses them; the defaults are the check's):
#   seed=N        Cycles' base seed (0)
#   size=WxH      the render size (64x48)
#   offset=frame  Cycles' sample offset (frame - 1) * SAMPLES, so that every
#                 frame takes the next samples of the sequence.  Without it
#                 (offset=0, the default) a 1-sample frame's one sample lies
#                 at the pixel centre whatever the seed (docs/measurements/OFFLINE.md,
#                 section 7): an animated seed does not jitter it.
#   filter=W      the pixel filter width in pixels (Cycles' 1.5); 0.01 gives
#                 a centre-sampled image
#   bounces=N     Cycles' max_bounces (Blender's 12): fewer bounces make the
#                 many-sample references of large frames affordable
# Variants of the scene for the error study (docs/measurements/OFFLINE.md, section 7,
# "Independent 320x180 sequences"); rrc-blender-check understands only the
# defaults (it intersects the ground, the cube and the sphere analytically):
#   camera=check|strafe   check (default): the camera translates, rises and
#                 pans; strafe: it slides along x at a constant height and
#                 tilt, panning by pan= degrees a frame
#   cam_x0=X, cam_speed=V, pan=DEG   the strafe's x at frame 0, its x per
#                 frame (signed) and its yaw per frame, zero at the middle
#                 frame (defaults -1.8, 0.15, 0)
#   mover=sphere|cube     the moving object (sphere); the cube is 0.9 wide
#                 and spins about z by spin= degrees a frame (0)
#   mover_vel=X,Y,Z       the moving object's velocity per frame
#                 (0.25,0,0.15 for the sphere: right and up)
#   pillars=N     N static upright cylinders between the camera and the
#                 scene (0): under a strafe they uncover what lies behind them
#   jitter=none|filter   filter: the camera is shifted by a sub-pixel offset
#                 each frame, Halton (2, 3) drawn through a Blackman-Harris
#                 filter of jitter_width= px (1: jitter_camera.py's default,
#                 2/3 of the reference's 1.5), so that a frame's first sample, which
#                 Cycles puts at the (shifted) pixel centre, sweeps the
#                 filter over the frames; scene.json gives each frame's
#                 "jitter" in pixels, x right, y down.  Cycles' Vector pass
#                 leaves the shift out (unjittered vectors)
# The fence sequence (docs/measurements/OFFLINE.md, section 7, "A fence of thin poles"; every
# option off by default, so the sequences above are unchanged):
#   fence=N       N thin upright poles (pass indices 10..) in a row at y =
#                 fence_y= (-4), evenly over x in [-fence_span/2,
#                 fence_span/2] (fence_span= 11), 3.2 high, their diameters
#                 cycling through fence_d= (0.021,0.038,0.052,0.065: 1.2-4
#                 px at 320x180 seen from the strafe, 5.3 away)
#   bricks=1      a brick wall behind the scene (pass index 8): a vertical
#                 plane at y = wall_y= (2), 24 wide, 4 high, with Cycles'
#                 procedural brick texture, bricks 0.25 x 0.125 and mortar
#                 0.01 (a third of a pixel at 320x180)
#   mover=ball    the moving object is a glossy striped ball of radius
#                 ball_r= (0.45) that rolls on the ground at mover_vel=
#                 (its z is ignored): it turns by its distance / radius
#   light=area    an area light (a 1.5-wide square, 400 W, facing down from
#                 z = 5) instead of the sun, moving by light_vel= (0.12,0,0)
#                 a frame from light_x0= (-1.5), so that the shadows move
#   threads=N     Cycles' threads (Blender's default: every core)
import bpy
import json
import math
import os
import sys

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
keys = dict(a.split("=", 1) for a in argv if "=" in a)
argv = [a for a in argv if "=" not in a]
keys_given = dict(keys)
unknown = set(keys) - {"seed", "size", "offset", "filter", "bounces", "camera", "cam_x0", "cam_speed", "pan", "mover",
                       "mover_vel", "spin", "pillars", "jitter", "jitter_width", "fence", "fence_y", "fence_span",
                       "fence_d", "bricks", "wall_y", "ball_r", "light", "light_vel", "light_x0", "threads"}
if unknown:
    sys.exit("render_check_scene.py: unknown option(s) " + ", ".join(sorted(unknown)))
out_dir = os.path.abspath(argv[0] if argv else "blender_check")
samples = int(argv[1]) if len(argv) > 1 else 16
half = len(argv) > 2 and argv[2] == "half"
animated_seed = len(argv) > 3 and argv[3] == "seed"
frames = int(argv[4]) if len(argv) > 4 else 3
base_seed = int(keys.get("seed", "0"))
size = keys.get("size", "64x48").split("x")
offset_per_frame = keys.get("offset", "0") == "frame"
filter_width = float(keys.get("filter", "1.5"))
bounces = int(keys["bounces"]) if "bounces" in keys else None
camera_path = keys.get("camera", "check")
cam_x0, cam_speed, pan = float(keys.get("cam_x0", "-1.8")), float(keys.get("cam_speed", "0.15")), float(keys.get("pan", "0"))
mover_kind = keys.get("mover", "sphere")
mover_vel = [float(v) for v in keys.get("mover_vel", "0.25,0,0.15").split(",")]
fence = int(keys.get("fence", "0"))
fence_y, fence_span = float(keys.get("fence_y", "-4")), float(keys.get("fence_span", "11"))
fence_d = [float(v) for v in keys.get("fence_d", "0.021,0.038,0.052,0.065").split(",")]
bricks = keys.get("bricks", "0") == "1"
wall_y = float(keys.get("wall_y", "2"))
ball_r = float(keys.get("ball_r", "0.45"))
light_kind = keys.get("light", "sun")
light_vel = [float(v) for v in keys.get("light_vel", "0.12,0,0").split(",")]
light_x0 = float(keys.get("light_x0", "-1.5"))
threads = int(keys["threads"]) if "threads" in keys else None
spin = float(keys.get("spin", "0"))
pillars = int(keys.get("pillars", "0"))
jitter_kind = keys.get("jitter", "none")
jitter_width = float(keys.get("jitter_width", "1"))  # jitter_camera.py's default for the reference's 1.5 px, whatever filter= is
if camera_path not in ("check", "strafe") or mover_kind not in ("sphere", "cube", "ball") or len(mover_vel) != 3 \
        or jitter_kind not in ("none", "filter") or light_kind not in ("sun", "area") or len(light_vel) != 3:
    sys.exit("render_check_scene.py: camera=check|strafe, mover=sphere|cube|ball, mover_vel=X,Y,Z, jitter=none|filter, "
             "light=sun|area, light_vel=X,Y,Z")
os.makedirs(out_dir, exist_ok=True)

W, H = int(size[0]), int(size[1])
scene = bpy.context.scene
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)

scene.render.engine = 'CYCLES'
scene.cycles.device = 'CPU'
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.cycles.use_adaptive_sampling = False
scene.cycles.seed = base_seed
scene.cycles.use_animated_seed = animated_seed
scene.cycles.filter_width = filter_width
scene.cycles.sample_offset = 0
if bounces is not None:
    scene.cycles.max_bounces = bounces
if threads is not None:
    scene.render.threads_mode = 'FIXED'
    scene.render.threads = threads
if offset_per_frame:
    def set_sample_offset(sc, *_):
        sc.cycles.sample_offset = max(sc.frame_current - 1, 0) * samples
    bpy.app.handlers.frame_change_pre.append(set_sample_offset)
scene.render.use_motion_blur = False  # the Vector pass needs it off
scene.render.resolution_x = W
scene.render.resolution_y = H
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.render.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
scene.render.image_settings.color_depth = '16' if half else '32'
scene.render.image_settings.exr_codec = 'ZIP'
scene.render.filepath = os.path.join(out_dir, "frame_####")
scene.frame_start, scene.frame_end = 1, frames

layer = scene.view_layers[0]
layer.use_pass_combined = True
layer.use_pass_z = True
layer.use_pass_vector = True
layer.use_pass_object_index = True

world = scene.world or bpy.data.worlds.new("World")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs[0].default_value = (0.3, 0.5, 0.8, 1.0)
world.node_tree.nodes["Background"].inputs[1].default_value = 0.4


def material(name, colour, checker=False):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = colour
    if checker:  # structure on the ground, so blur and lag show
        tex = m.node_tree.nodes.new("ShaderNodeTexChecker")
        tex.inputs["Scale"].default_value = 40.0
        tex.inputs["Color1"].default_value = colour
        tex.inputs["Color2"].default_value = (0.1, 0.1, 0.1, 1.0)
        m.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    return m


def keyed(obj, frames_locs, rotations=None):
    for f, loc in frames_locs.items():
        obj.location = loc
        obj.keyframe_insert("location", frame=f)
        if rotations:
            obj.rotation_euler = rotations[f]
            obj.keyframe_insert("rotation_euler", frame=f)
    for fc in obj.animation_data.action.fcurves:
        for k in fc.keyframe_points:
            k.interpolation = 'LINEAR'


# Ground plane z = 0 (index 1), a static cube (index 2), a moving sphere (index 3).
bpy.ops.mesh.primitive_plane_add(size=40, location=(0, 0, 0))
plane = bpy.context.active_object
plane.name = "Ground"
plane.pass_index = 1
plane.data.materials.append(material("Ground", (0.6, 0.6, 0.6, 1.0), checker=True))
bpy.ops.mesh.primitive_cube_add(size=1.5, location=(-1.5, 1.0, 0.75))
cube = bpy.context.active_object
cube.name = "Cube"
cube.pass_index = 2
cube.data.materials.append(material("Cube", (0.2, 0.5, 0.2, 1.0)))
if mover_kind == "sphere":
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, location=(1.0, -0.5, 1.2), segments=48, ring_count=24)
    sphere = bpy.context.active_object
    sphere.name = "Sphere"
    sphere.data.materials.append(material("Sphere", (0.7, 0.2, 0.1, 1.0)))
    bpy.ops.object.shade_smooth()
    start = (1.0, -0.5, 1.2)
elif mover_kind == "ball":  # glossy, with stripes so that its rolling shows
    start = (1.0, -0.5, ball_r)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=ball_r, location=start, segments=48, ring_count=24)
    sphere = bpy.context.active_object
    sphere.name = "Ball"
    m = material("Ball", (0.7, 0.2, 0.1, 1.0))
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 0.08
    bsdf.inputs["Specular"].default_value = 0.9
    stripes = m.node_tree.nodes.new("ShaderNodeTexChecker")
    stripes.inputs["Scale"].default_value = 3.0
    stripes.inputs["Color1"].default_value = (0.7, 0.2, 0.1, 1.0)
    stripes.inputs["Color2"].default_value = (0.9, 0.85, 0.2, 1.0)
    m.node_tree.links.new(stripes.outputs["Color"], bsdf.inputs["Base Color"])
    sphere.data.materials.append(m)
    bpy.ops.object.shade_smooth()
    mover_vel[2] = 0.0
else:  # a spinning cube: its vectors vary across its faces
    bpy.ops.mesh.primitive_cube_add(size=0.9, location=(1.0, -0.5, 0.45))
    sphere = bpy.context.active_object
    sphere.name = "Mover"
    sphere.data.materials.append(material("Mover", (0.7, 0.2, 0.1, 1.0), checker=True))
    start = (1.0, -0.5, 0.45)
sphere.pass_index = 3
# By default the sphere moves right and up: both signs of the vector show.
keys = (0, frames + 1)  # linear between, so every frame moves alike
if mover_kind == "ball":  # rolling without slipping: the turn is the distance over the radius, about (-vy, vx, 0)
    speed = math.hypot(mover_vel[0], mover_vel[1])
    heading = math.atan2(mover_vel[1], mover_vel[0])
    roll = {f: (0.0, speed * f / ball_r, heading) for f in keys}  # Euler XYZ: Rz(heading) Ry(roll), the roll about the path's normal
    keyed(sphere, {f: tuple(start[i] + mover_vel[i] * f for i in range(3)) for f in keys}, roll)
else:
    keyed(sphere, {f: tuple(start[i] + mover_vel[i] * f for i in range(3)) for f in keys},
          {f: (0.0, 0.0, math.radians(spin * f)) for f in keys} if spin else None)
statics = [plane, cube]
for i in range(pillars):  # evenly spread across the view, 5.5 in front of the scene's centre
    bpy.ops.mesh.primitive_cylinder_add(radius=0.18, depth=3.0, location=(-3.0 + 6.0 * (i + 0.5) / pillars, -4.5, 1.5))
    pillar = bpy.context.active_object
    pillar.name = "Pillar%d" % i
    pillar.pass_index = 4 + i
    pillar.data.materials.append(material("Pillar%d" % i, (0.8, 0.75, 0.6, 1.0)))
    statics.append(pillar)
for i in range(fence):  # thin poles, 1-4 px wide, evenly over the strafe's whole view
    d = fence_d[i % len(fence_d)]
    x = -fence_span / 2 + fence_span * (i + 0.5) / fence
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, radius=d / 2, depth=3.2, location=(x, fence_y, 1.6))
    pole = bpy.context.active_object
    pole.name = "Pole%d" % i
    pole.pass_index = 10 + i
    pole.data.materials.append(material("Pole%d" % i, (0.85, 0.85, 0.8, 1.0)))
    statics.append(pole)
if bricks:  # sub-pixel mortar: aliasing that a 1-sample frame cannot resolve
    bpy.ops.mesh.primitive_plane_add(size=1, location=(0, wall_y, 2.0), rotation=(math.radians(90), 0, 0))
    wall = bpy.context.active_object
    wall.name = "Wall"
    wall.scale = (24.0, 4.0, 1.0)
    wall.pass_index = 8
    m = material("Wall", (0.55, 0.2, 0.12, 1.0))
    nt = m.node_tree
    coord = nt.nodes.new("ShaderNodeTexCoord")
    brick = nt.nodes.new("ShaderNodeTexBrick")
    brick.inputs["Scale"].default_value = 1.0  # world units: the plane's object coordinates times its scale
    brick.inputs["Color1"].default_value = (0.55, 0.2, 0.12, 1.0)
    brick.inputs["Color2"].default_value = (0.4, 0.15, 0.1, 1.0)
    brick.inputs["Mortar"].default_value = (0.85, 0.85, 0.8, 1.0)
    brick.inputs["Mortar Size"].default_value = 0.01
    brick.inputs["Brick Width"].default_value = 0.25
    brick.inputs["Row Height"].default_value = 0.125
    scale = nt.nodes.new("ShaderNodeVectorMath")
    scale.operation = 'MULTIPLY'
    scale.inputs[1].default_value = (24.0, 4.0, 1.0)
    nt.links.new(coord.outputs["Object"], scale.inputs[0])
    nt.links.new(scale.outputs["Vector"], brick.inputs["Vector"])
    nt.links.new(brick.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
    wall.data.materials.append(m)
    statics.append(wall)

cam_data = bpy.data.cameras.new("Camera")
cam_data.lens = 35.0
cam_data.sensor_fit = 'AUTO'
cam = bpy.data.objects.new("Camera", cam_data)
scene.collection.objects.link(cam)
scene.camera = cam
if camera_path == "check":
    # The camera moves sideways, rises and pans: translation and rotation.
    keyed(cam, {f: (0.4 * f, -9.0 + 0.2 * f, 3.0 + 0.12 * f) for f in keys},
          {f: (math.radians(73.0 - 0.8 * f), 0.0, math.radians(4.0 + 1.5 * f)) for f in keys})
else:
    # A strafe: sideways at a constant height and tilt, optionally panning,
    # centred on the scene at the middle frame.
    mid = (frames + 1) / 2.0
    keyed(cam, {f: (cam_x0 + cam_speed * f, -9.0, 3.0) for f in keys},
          {f: (math.radians(73.0), 0.0, math.radians(pan * (f - mid))) for f in keys})

# jitter=filter: the camera's sub-pixel offset of frame f is jitter_camera.py's (the Halton
# (2, 3) point f + 1 drawn through the pixel filter), so that Cycles' first sample, which lies
# at the pixel centre (docs/measurements/OFFLINE.md, section 7), sweeps the filter over the frames as a
# many-sample render's samples do.
jitters = {f: (0.0, 0.0) for f in range(0, frames + 2)}
if jitter_kind == "filter":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import jitter_camera
    jitters = jitter_camera.key_jitter(cam_data, range(0, frames + 2), jitter_width, W, H)

if light_kind == "sun":
    sun = bpy.data.lights.new("Sun", type='SUN')
    sun.energy = 1.5
    sun.angle = math.radians(15.0)  # soft shadows: noisy penumbrae at few samples
    light = bpy.data.objects.new("Sun", sun)
    light.rotation_euler = (math.radians(40), 0, math.radians(30))
    scene.collection.objects.link(light)
else:  # an area light sliding along: shadows that move over static surfaces
    area = bpy.data.lights.new("Area", type='AREA')
    area.energy = 400.0
    area.size = 1.5
    light = bpy.data.objects.new("Area", area)
    scene.collection.objects.link(light)
    lstart = (light_x0, -1.5, 5.0)
    keyed(light, {f: tuple(lstart[i] + light_vel[i] * f for i in range(3)) for f in keys})


def mat(m):
    return [[m[i][j] for j in range(4)] for i in range(4)]  # row-major


info = {"width": W, "height": H, "samples": samples, "half": half, "frame_count": frames, "frames": {},
        "options": keys_given}
depsgraph = bpy.context.evaluated_depsgraph_get()
for f in range(0, frames + 2):
    scene.frame_set(f)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    cam_eval = cam.evaluated_get(depsgraph)
    proj = cam_eval.calc_matrix_camera(depsgraph, x=W, y=H, scale_x=1.0, scale_y=1.0)
    info["frames"][str(f)] = {
        "camera_world": mat(cam_eval.matrix_world),
        "jitter": list(jitters[f]),
        "projection": mat(proj),
        "objects": {o.name: {"index": o.pass_index, "world": mat(o.evaluated_get(depsgraph).matrix_world)}
                    for o in statics + [sphere]},
    }
with open(os.path.join(out_dir, "scene.json"), "w") as fp:
    json.dump(info, fp, indent=1)

bpy.ops.render.render(animation=True)
