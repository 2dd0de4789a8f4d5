# thaw's run in Blender, in one step: every surface of the melt (ice | outside, water | ice, the
# puddle, ...) as one object whose mesh follows the frame (a frame-change handler swaps it), glass
# materials with thaw's indices of refraction and absorption, thaw's camera, lights and
# environment, the film's frame range and rate. `thaw run` writes this file into DIR/handoff/
# with the run's description in THAW below; its source is src/pipeline/blender_scene.py and
# docs/handoff.md says what each part becomes and what does not carry over.
#
#   blender --background --python DIR/handoff/blender_scene.py -- --frame N --render out.png
#   blender --python DIR/handoff/blender_scene.py      (Blender's UI: play or scrub the timeline)
#
# Options after "--":
#   --frame N            thaw's frame N (frames/frame_NNNNNN.png); default: the first
#   --render PATH        render that frame with Cycles (CPU) and write it as a PNG
#   --samples N          Cycles samples per pixel (default 64)
#   --mask PATH          instead of the picture, the frame's ice silhouette as a PNG: alpha 1 where
#                        the first surface on the ray through the pixel centre is the ice
#   --camera-check PATH  JSON: where Blender's camera puts the world points that thaw's camera
#                        sees at the image corners (handoff/camera.json), in thaw's pixels
#   --save PATH          also save the scene as a .blend file
#
# Frames are numbered as thaw's (the first is 0). Coordinates: thaw's world is y up, Blender's z
# up; a thaw point (x, y, z) [m] is Blender's (x, -z, y) [m] (a quarter turn about x).
import json
import math
import os
import sys

MIN_BLENDER = (3, 0, 0)
USAGE = ("blender --background --python blender_scene.py -- --frame N --render out.png")
THAW = {}  # @THAW_SCENE@ (thaw run puts the run's description here)

try:
    import bpy
    from mathutils import Matrix, Vector
    from bpy.app.handlers import persistent
except ImportError:
    print("thaw hand-off: this script needs Blender %d.%d or newer; run it as: %s"
          % (MIN_BLENDER[0], MIN_BLENDER[1], USAGE), file=sys.stderr)
    sys.exit(2)


def fail(message):
    """One line, then stop: exit status 2 in the background, an error in the UI."""
    line = "thaw hand-off: " + message
    if bpy.app.background:
        print(line, file=sys.stderr)
        sys.stdout.flush()
        sys.exit(2)
    raise RuntimeError(line)


if tuple(bpy.app.version) < MIN_BLENDER:
    fail("needs Blender %d.%d or newer (this is %s)"
         % (MIN_BLENDER[0], MIN_BLENDER[1], bpy.app.version_string))
if not THAW:
    fail("this is the template in thaw's source tree; run the copy that `thaw run` writes into "
         "DIR/handoff/")


def to_blender(v):
    """thaw (y up) to Blender (z up)."""
    return (v[0], -v[2], v[1])


# ---------------------------------------------------------------------------------------------
# Arguments and the run folder


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    opts = {"frame": None, "render": None, "samples": 64, "mask": None, "camera_check": None,
            "save": None}
    i = 0
    while i < len(argv):
        key = argv[i]
        name = key[2:].replace("-", "_") if key.startswith("--") else None
        if name not in opts or i + 1 >= len(argv):
            fail("unknown option or missing value '%s' (options: --frame N --render PATH "
                 "--samples N --mask PATH --camera-check PATH --save PATH)" % key)
        value = argv[i + 1]
        if name in ("frame", "samples"):
            try:
                value = int(value)
            except ValueError:
                fail("--%s must be an integer, not '%s'" % (name.replace("_", "-"), value))
        opts[name] = value
        i += 2
    count = len(THAW["frames"])
    if opts["frame"] is None:
        opts["frame"] = 0
    if not 0 <= opts["frame"] < count:
        fail("--frame %d is not a frame of this run (0 to %d)" % (opts["frame"], count - 1))
    if opts["samples"] < 1:
        fail("--samples must be at least 1")
    return opts


def find_run_dir():
    """The run folder: this script's folder's parent (the run folder holds no absolute path, so
    it can be moved or copied)."""
    candidates = []
    if "__file__" in globals():
        candidates.append(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    for text in bpy.data.texts:
        if text.filepath and os.path.basename(text.filepath) == "blender_scene.py":
            candidates.append(os.path.dirname(os.path.dirname(bpy.path.abspath(text.filepath))))
    for c in candidates:
        if os.path.isfile(os.path.join(c, "handoff", "camera.json")):
            return c
    fail("cannot find the run folder (looked in %s): keep this script in DIR/handoff/ and run "
         "it from there" % (", ".join(candidates) or "nowhere: no file name"))


def check_run(run_dir):
    """Names the first missing step's file, so an incomplete run says what to do."""
    for rel, step in THAW["required"]:
        if not os.path.exists(os.path.join(run_dir, rel)):
            fail("the run folder %s is incomplete: %s is missing (the %s stage has not finished: "
                 "run `thaw run` again)" % (run_dir, rel, step))


# ---------------------------------------------------------------------------------------------
# Meshes


def read_obj(path):
    """Vertices [m] and triangles of one of thaw's OBJ files (1-based `f a b c` or `f a//n`)."""
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                p = line.split()
                verts.append(to_blender((float(p[1]), float(p[2]), float(p[3]))))
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) - 1 for t in line.split()[1:]]
                for k in range(1, len(idx) - 1):
                    faces.append((idx[0], idx[k], idx[k + 1]))
    return verts, faces


def mesh_from_obj(name, path, material, scale=1.0):
    verts, faces = read_obj(path)
    if scale != 1.0:
        verts = [(v[0] * scale, v[1] * scale, v[2] * scale) for v in verts]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    for p in mesh.polygons:
        p.use_smooth = True
    if material is not None:
        mesh.materials.append(material)
    return mesh


def surface_mesh(run_dir, surface, frame):
    """The mesh datablock of `surface` at `frame`, read once and kept (an empty one if the
    surface does not exist then)."""
    entry = surface["frames"][frame]
    name = "thaw_%s_%06d" % (surface["object"], frame) if entry else "thaw_empty"
    mesh = bpy.data.meshes.get(name)
    if mesh is None:
        if entry is None:
            mesh = bpy.data.meshes.new(name)
        else:
            mesh = mesh_from_obj(name, os.path.join(run_dir, entry["file"]),
                                 bpy.data.materials.get(surface["material"]), entry["scale"])
    return mesh, entry


def thaw_show_frame(scene, *args):
    """frame_change_pre: every surface takes its mesh and placement of the current frame."""
    data = THAW
    run_dir = scene.get("thaw_run_dir", "")
    frame = min(max(scene.frame_current, 0), len(data["frames"]) - 1)
    for surface in data["surfaces"]:
        obj = bpy.data.objects.get("thaw_" + surface["object"])
        if obj is None:
            continue
        mesh, entry = surface_mesh(run_dir, surface, frame)
        if obj.data != mesh:
            obj.data = mesh
        if entry is not None:
            obj.location = to_blender(entry["translate_m"])


thaw_show_frame = persistent(thaw_show_frame)


def install_handler():
    handlers = bpy.app.handlers.frame_change_pre
    for h in list(handlers):
        if getattr(h, "__name__", "") == "thaw_show_frame":
            handlers.remove(h)
    handlers.append(thaw_show_frame)


# ---------------------------------------------------------------------------------------------
# Materials


def set_input(node, names, value):
    """Sets the first input of `node` that exists among `names` (Blender 3 and 4 names)."""
    for n in names:
        if n in node.inputs:
            node.inputs[n].default_value = value
            return


def new_material(name):
    old = bpy.data.materials.get(name)
    if old is not None:
        bpy.data.materials.remove(old)
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    bsdf = nt.nodes.new("ShaderNodeBsdfPrincipled")
    nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return mat, nt, bsdf, out


def dielectric_material(spec):
    """A surface between two media: transmission with the relative index n_inside / n_outside
    (Cycles refracts by the material's IOR entering the front face and its inverse leaving it,
    and does not know the medium a ray is in), and the inside medium's absorption as a volume."""
    mat, nt, bsdf, out = new_material(spec["name"])
    set_input(bsdf, ["Base Color"], (1, 1, 1, 1))
    set_input(bsdf, ["Transmission", "Transmission Weight"], 1.0)
    set_input(bsdf, ["Roughness"], spec["roughness"])
    set_input(bsdf, ["Transmission Roughness"], spec["roughness"])
    set_input(bsdf, ["IOR"], spec["ior"])
    sigma = spec["absorption_per_m"]
    density = max(sigma)
    if density > 0:
        vol = nt.nodes.new("ShaderNodeVolumeAbsorption")
        # Cycles' absorption coefficient is density * (1 - colour) [1/m].
        vol.inputs["Color"].default_value = tuple(1 - s / density for s in sigma) + (1,)
        vol.inputs["Density"].default_value = density
        nt.links.new(vol.outputs["Volume"], out.inputs["Volume"])
    if spec["scattering_per_m"] > 0:
        sca = nt.nodes.new("ShaderNodeVolumeScatter")
        sca.inputs["Density"].default_value = spec["scattering_per_m"]
        sca.inputs["Anisotropy"].default_value = spec["scattering_g"]
        if out.inputs["Volume"].is_linked:
            add = nt.nodes.new("ShaderNodeAddShader")
            nt.links.new(out.inputs["Volume"].links[0].from_socket, add.inputs[0])
            nt.links.new(sca.outputs["Volume"], add.inputs[1])
            nt.links.new(add.outputs["Shader"], out.inputs["Volume"])
        else:
            nt.links.new(sca.outputs["Volume"], out.inputs["Volume"])
    return mat


def checker_node(nt, tex):
    """thaw's 3D checker: colour 0 where floor((x-o)/s) + floor((y-o)/s) + floor((z-o)/s) is even
    (render/material/texture.h), in thaw's axes (Blender's object coordinates turned back)."""
    coord = nt.nodes.new("ShaderNodeTexCoord")
    sep = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(coord.outputs["Object"], sep.inputs[0])
    o, s = tex["checker_offset_m"], tex["checker_size_m"]
    # thaw (x, y, z) = Blender (x, z, -y)
    axes = [(sep.outputs["X"], 1, o[0]), (sep.outputs["Z"], 1, o[1]), (sep.outputs["Y"], -1, o[2])]
    total = None
    for socket, sign, off in axes:
        lin = nt.nodes.new("ShaderNodeMath")
        lin.operation = "MULTIPLY_ADD"  # (sign v) / s - off / s
        nt.links.new(socket, lin.inputs[0])
        lin.inputs[1].default_value = sign / s
        lin.inputs[2].default_value = -off / s
        fl = nt.nodes.new("ShaderNodeMath")
        fl.operation = "FLOOR"
        nt.links.new(lin.outputs[0], fl.inputs[0])
        if total is None:
            total = fl.outputs[0]
        else:
            add = nt.nodes.new("ShaderNodeMath")
            add.operation = "ADD"
            nt.links.new(total, add.inputs[0])
            nt.links.new(fl.outputs[0], add.inputs[1])
            total = add.outputs[0]
    # parity = total - 2 floor(total / 2)
    half = nt.nodes.new("ShaderNodeMath")
    half.operation = "MULTIPLY"
    nt.links.new(total, half.inputs[0])
    half.inputs[1].default_value = 0.5
    fl = nt.nodes.new("ShaderNodeMath")
    fl.operation = "FLOOR"
    nt.links.new(half.outputs[0], fl.inputs[0])
    par = nt.nodes.new("ShaderNodeMath")
    par.operation = "MULTIPLY_ADD"
    nt.links.new(fl.outputs[0], par.inputs[0])
    par.inputs[1].default_value = -2.0
    nt.links.new(total, par.inputs[2])
    mix = nt.nodes.new("ShaderNodeMixRGB")
    nt.links.new(par.outputs[0], mix.inputs["Fac"])
    mix.inputs["Color1"].default_value = tuple(tex["checker_colors"][0]) + (1,)
    mix.inputs["Color2"].default_value = tuple(tex["checker_colors"][1]) + (1,)
    return mix.outputs["Color"]


def opaque_material(spec):
    """thaw's matte, phong, metal and emissive materials as Principled BSDFs."""
    mat, nt, bsdf, out = new_material(spec["name"])
    tex = spec["texture"]
    if tex["kind"] == "checker":
        nt.links.new(checker_node(nt, tex), bsdf.inputs["Base Color"])
    else:
        set_input(bsdf, ["Base Color"], tuple(tex["color"]) + (1,))
    kind = spec["kind"]
    set_input(bsdf, ["Roughness"], 1.0 if kind == "matte" else spec["roughness"])
    set_input(bsdf, ["Specular", "Specular IOR Level"], 0.0 if kind == "matte" else 0.5)
    if kind == "metal":
        set_input(bsdf, ["Metallic"], 1.0)
    if kind == "emissive":
        set_input(bsdf, ["Emission", "Emission Color"], tuple(spec["emission"]) + (1,))
        set_input(bsdf, ["Emission Strength"], 1.0)
    return mat


# ---------------------------------------------------------------------------------------------
# The scene


def new_object(name, data, collection):
    old = bpy.data.objects.get(name)
    if old is not None:
        bpy.data.objects.remove(old)
    obj = bpy.data.objects.new(name, data)
    collection.objects.link(obj)
    return obj


def static_mesh(spec, material):
    """A scenario object (plane, sphere, box, OBJ file) as a Blender mesh in Blender axes."""
    import bmesh
    name = "thaw_" + spec["object"]
    shape = spec["shape"]
    if shape == "mesh":
        return mesh_from_obj(name, spec["file"], material, spec["scale"])
    bm = bmesh.new()
    if shape == "sphere":
        bmesh.ops.create_uvsphere(bm, u_segments=96, v_segments=48, radius=spec["radius_m"])
        bmesh.ops.translate(bm, verts=bm.verts, vec=to_blender(spec["center_m"]))
    elif shape == "box":
        lo, hi = spec["min_m"], spec["max_m"]
        bmesh.ops.create_cube(bm, size=1.0)
        size = [hi[i] - lo[i] for i in range(3)]
        centre = [(hi[i] + lo[i]) / 2 for i in range(3)]
        bmesh.ops.scale(bm, verts=bm.verts, vec=(size[0], size[2], size[1]))
        bmesh.ops.translate(bm, verts=bm.verts, vec=to_blender(centre))
    else:  # an endless plane: a square of half-size `extent_m` about its point
        n = Vector(to_blender(spec["normal"])).normalized()
        t1 = n.orthogonal().normalized()
        t2 = n.cross(t1)
        p = Vector(to_blender(spec["point_m"]))
        e = spec["extent_m"]
        vs = [bm.verts.new(p + e * (a * t1 + b * t2)) for a, b in ((-1, -1), (1, -1), (1, 1),
                                                                   (-1, 1))]
        face = bm.faces.new(vs)
        if face.normal.dot(n) < 0:
            face.normal_flip()
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    if shape == "sphere":
        for p in mesh.polygons:
            p.use_smooth = True
    if material is not None:
        mesh.materials.append(material)
    return mesh


def build_camera(scene, collection):
    c = THAW["camera"]
    data = bpy.data.cameras.get("thaw_camera") or bpy.data.cameras.new("thaw_camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(c["vertical_fov_deg"])
    data.shift_x = data.shift_y = 0.0
    data.clip_start = 1e-3
    data.clip_end = 1e4
    obj = new_object("thaw_camera", data, collection)
    # The renderer's basis (render/scene/camera.h): Blender's camera looks along its -z, y up.
    pos = Vector(c["position_m"])
    forward = (Vector(c["look_at_m"]) - pos).normalized()
    right = forward.cross(Vector(c["up"])).normalized()
    up = right.cross(forward)
    cols = [Vector(to_blender(v)) for v in (right, up, -forward)]
    m = Matrix.Identity(4)
    for i in range(3):
        for j in range(3):
            m[j][i] = cols[i][j]
    m.translation = Vector(to_blender(pos))
    obj.matrix_world = m
    scene.camera = obj
    return obj


def build_lights(collection):
    for i, spec in enumerate(THAW["lights"]):
        data = bpy.data.lights.new("thaw_light_%d" % i, "POINT")
        data.energy = spec["power_w"]
        data.color = spec["color"]
        data.shadow_soft_size = spec["radius_m"]
        obj = new_object("thaw_light_%d" % i, data, collection)
        obj.location = to_blender(spec["position_m"])


def build_world(scene, run_dir):
    env = THAW["environment"]
    world = bpy.data.worlds.get("thaw_world") or bpy.data.worlds.new("thaw_world")
    world.use_nodes = True
    nt = world.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputWorld")
    bg = nt.nodes.new("ShaderNodeBackground")
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    if env["kind"] == "map":
        tex = nt.nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(os.path.join(run_dir, env["file"]), check_existing=True)
        tex.projection = "EQUIRECTANGULAR"
        nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    else:
        bg.inputs["Color"].default_value = tuple(env["color"]) + (1,)
    bg.inputs["Strength"].default_value = 1.0
    scene.world = world


def build_scene(run_dir):
    scene = bpy.context.scene
    scene["thaw_run_dir"] = run_dir
    # A new file's default cube, light and camera make way; the user's own objects stay.
    if not bpy.data.filepath:
        for name in ("Cube", "Light", "Camera"):
            if name in bpy.data.objects:
                bpy.data.objects.remove(bpy.data.objects[name])
    collection = bpy.data.collections.get("thaw") or bpy.data.collections.new("thaw")
    if collection.name not in scene.collection.children:
        scene.collection.children.link(collection)
    img = THAW["image"]
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = img["width"], img["height"], 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    fps = THAW["fps"]
    r.fps = max(1, round(fps))
    r.fps_base = r.fps / fps
    scene.frame_start, scene.frame_end = 0, len(THAW["frames"]) - 1
    scene.cycles.device = "CPU"
    depth = img["max_depth"]
    scene.cycles.max_bounces = depth
    scene.cycles.transmission_bounces = depth
    scene.cycles.glossy_bounces = depth
    scene.cycles.transparent_max_bounces = depth
    scene.cycles.seed = 0
    # Debian's Blender is built without Open Image Denoise; turn it on where it exists.
    scene.cycles.use_denoising = False
    # thaw's PNGs: linear radiance times 2^exposure, sRGB-encoded.
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = img["exposure_stops"]
    scene.view_settings.gamma = 1.0
    build_camera(scene, collection)
    build_lights(collection)
    build_world(scene, run_dir)
    for spec in THAW["materials"]:
        opaque_material(spec)
    for spec in THAW["interfaces"]:
        dielectric_material(spec)
    for spec in THAW["objects"]:
        mesh = static_mesh(spec, bpy.data.materials.get(spec["material"]))
        new_object("thaw_" + spec["object"], mesh, collection)
    for surface in THAW["surfaces"]:
        new_object("thaw_" + surface["object"], bpy.data.meshes.new("thaw_empty_init"), collection)
    install_handler()
    return scene


# ---------------------------------------------------------------------------------------------
# Outputs


def render_mask(scene, path):
    """The ice silhouette: the ice's outer surface emits, every other object is a holdout (it
    hides what is behind it and leaves alpha 0), one sample at the pixel centre."""
    white, nt, bsdf, out = new_material("thaw_mask_ice")
    nt.nodes.remove(bsdf)
    em = nt.nodes.new("ShaderNodeEmission")
    nt.links.new(em.outputs["Emission"], out.inputs["Surface"])
    hold, nt, bsdf, out = new_material("thaw_mask_holdout")
    nt.nodes.remove(bsdf)
    h = nt.nodes.new("ShaderNodeHoldout")
    nt.links.new(h.outputs["Holdout"], out.inputs["Surface"])
    for obj in scene.objects:
        if obj.type != "MESH":
            continue
        mat = white if obj.name == "thaw_" + THAW["ice_surface"] else hold
        obj.data.materials.clear()
        obj.data.materials.append(mat)
    scene.render.film_transparent = True
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01  # the sample at the pixel centre, as thaw's AOV pass
    scene.cycles.max_bounces = 0
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def camera_check(scene, path):
    from bpy_extras.object_utils import world_to_camera_view
    cam = json.load(open(os.path.join(scene["thaw_run_dir"], "handoff", "camera.json")))
    w, h = THAW["image"]["width"], THAW["image"]["height"]
    rows = []
    for c in cam["corner_points"]:
        ndc = world_to_camera_view(scene, scene.camera, Vector(to_blender(c["world_m"])))
        got = (ndc.x * w, (1 - ndc.y) * h)
        rows.append({"thaw_px": c["pixel"], "blender_px": got,
                     "error_px": math.hypot(got[0] - c["pixel"][0], got[1] - c["pixel"][1])})
    with open(path, "w") as f:
        json.dump({"corners": rows, "max_error_px": max(r["error_px"] for r in rows)}, f, indent=2)


def main():
    opts = parse_args()
    run_dir = find_run_dir()
    check_run(run_dir)
    scene = build_scene(run_dir)
    scene.frame_set(opts["frame"])
    if opts["camera_check"]:
        camera_check(scene, opts["camera_check"])
    if opts["save"]:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(opts["save"]))
    if opts["render"]:
        scene.cycles.samples = opts["samples"]
        scene.render.image_settings.file_format = "PNG"
        scene.render.image_settings.color_mode = "RGB"
        scene.render.filepath = os.path.abspath(opts["render"])
        bpy.ops.render.render(write_still=True)
    if opts["mask"]:
        render_mask(scene, os.path.abspath(opts["mask"]))


main()
