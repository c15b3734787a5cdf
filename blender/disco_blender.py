"""A disco-layout layout as a Blender scene, and a headless render of it.

Three ways to use it:

- as a module, with Blender's ``bpy`` (Blender itself, or ``pip install bpy``)::

      import disco_blender
      disco_blender.build(layout, scene)          # dicts or paths of the JSON files
      disco_blender.render("room.png", size=(640, 480))

- from the command line, headless (``bpy`` from PyPI or Blender's own Python)::

      python blender/disco_blender.py room.json --scene scene.json --render room.png --blend room.blend
      blender -b -P blender/disco_blender.py -- room.json --render room.png

- as an add-on (Edit > Preferences > Add-ons > Install from disk: this file): File > Import >
  disco-layout (.json) builds the chosen layout in the open file.

What is built (units: Blender metres, Z up; the layout's x is X, its y is Y, so the top view
is the layout's render): the floor from the room's outline (``floor``), one wall per outline
edge standing outside the room (``wall-0``, ``wall-1``, ... as in the scene; a door is a hole
210 cm high, a window a hole from its sill to its top), one object per placed object, named as
in the layout, at its pose (rotation clockwise from above, so ``rotation_euler.z`` is minus
it) with its base at its ``elevation`` (an object on another stands on its top, a wall object
hangs at its height with its back on the wall): the asset's mesh when the scene names one (a
``.glb``, turned so its front faces the object's front and scaled to the asset's size), else a
box of the asset's size with its name written on top; a camera that frames the room and a sun.
Every object made carries a ``disco_kind`` custom property (``floor``, ``wall``, ``object``,
``label``, ``camera``, ``light``), and each layout object its ``category``, ``position_cm``,
``rotation_deg`` and ``size_cm``, plus ``elevation_cm``, ``on`` and ``wall`` when it is off the
floor.
"""

import argparse
import colorsys
import hashlib
import json
import math
import os
import sys

import bpy  # first: with bpy from PyPI, bmesh and mathutils come with it
import bmesh
from mathutils import Vector

bl_info = {
    "name": "disco-layout",
    "author": "disco-layout",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "File > Import > disco-layout (.json)",
    "description": "Builds a disco-layout layout as a room: floor, walls with doors and windows, objects",
    "category": "Import-Export",
}

CM = 0.01
"""Metres per centimetre."""
WALL_HEIGHT_CM = 250.0
WALL_THICKNESS_CM = 10.0
DOOR_HEIGHT_CM = 210.0
"""The walls, as ``disco export`` makes them."""
FLOOR_CM = 3.0
"""What stands at most this tall is a floor covering (a rug): drawn flat, under the rest."""


# ---------------------------------------------------------------------------------------------
# Reading the JSON


def _read(value):
    """A dict from a dict or from the path of a JSON file."""
    if value is None or isinstance(value, dict):
        return value
    with open(os.fspath(value), encoding="utf-8-sig") as f:
        return json.load(f)


def outline(room):
    """The room's floor outline as ``[(x, y), ...]`` in cm, counter-clockwise: its ``polygon``,
    or the rectangle ``width`` x ``depth``."""
    if "polygon" in room:
        return [tuple(map(float, p)) for p in room["polygon"]]
    w, d = float(room["width"]), float(room["depth"])
    return [(0.0, 0.0), (w, 0.0), (w, d), (0.0, d)]


def wall_names(room):
    """The walls' names, as ``disco export`` gives them: a plain rectangle's are ``wall-bottom``,
    ``wall-right``, ``wall-top``, ``wall-left``; any other room's ``wall-0``, ``wall-1``, ..."""
    points = outline(room)
    plain = "polygon" not in room and not room.get("doors") and not room.get("windows")
    if plain:
        return ["wall-bottom", "wall-right", "wall-top", "wall-left"]
    return [f"wall-{i}" for i in range(len(points))]


def openings(room, wall_height_cm=WALL_HEIGHT_CM, door_height_cm=DOOR_HEIGHT_CM):
    """Every door and window as ``(wall, start_cm, end_cm, bottom_cm, top_cm, kind)``: where
    along its wall (from the wall's start vertex) and how high the hole is."""
    holes = []
    for door in room.get("doors", []):
        at, width = float(door["at"]), float(door["width"])
        top = min(door_height_cm, wall_height_cm)
        holes.append((int(door["wall"]), at - width / 2, at + width / 2, 0.0, top, "door"))
    for window in room.get("windows", []):
        at, width = float(window["at"]), float(window["width"])
        bottom = float(window["sill"])
        top = min(bottom + float(window["height"]), wall_height_cm)
        holes.append((int(window["wall"]), at - width / 2, at + width / 2, bottom, top, "window"))
    return holes


# ---------------------------------------------------------------------------------------------
# Geometry


def _mesh_object(name, bm, collection, kind):
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    obj["disco_kind"] = kind
    collection.objects.link(obj)
    return obj


def _material(name, rgb, roughness=0.8):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = (*rgb, 1.0)
        bsdf.inputs["Roughness"].default_value = roughness
    mat.diffuse_color = (*rgb, 1.0)
    return mat


def category_colour(category):
    """A stable, distinct colour per category (linear RGB)."""
    digest = hashlib.sha1(category.encode("utf-8")).digest()
    hue = digest[0] / 255.0
    r, g, b = colorsys.hsv_to_rgb(hue, 0.55, 0.8)
    return (r ** 2.2, g ** 2.2, b ** 2.2)


def _prism(bm, corners, z0, z1):
    """A block: the quad ``corners`` (metres, any winding) from height ``z0`` to ``z1``."""
    area = sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(corners, corners[1:] + corners[:1]))
    if area < 0:
        corners = corners[::-1]
    low = [bm.verts.new((x, y, z0)) for x, y in corners]
    high = [bm.verts.new((x, y, z1)) for x, y in corners]
    bm.faces.new(low[::-1])
    bm.faces.new(high)
    n = len(corners)
    for i in range(n):
        j = (i + 1) % n
        bm.faces.new((low[i], low[j], high[j], high[i]))


def build_floor(room, collection, thickness_cm=WALL_THICKNESS_CM):
    """The floor: the outline's face at Z = 0, the wall thickness deep."""
    bm = bmesh.new()
    top = [bm.verts.new((x * CM, y * CM, 0.0)) for x, y in outline(room)]
    face = bm.faces.new(top)
    extruded = bmesh.ops.extrude_face_region(bm, geom=[face])
    down = [v for v in extruded["geom"] if isinstance(v, bmesh.types.BMVert)]
    bmesh.ops.translate(bm, verts=down, vec=(0.0, 0.0, -thickness_cm * CM))
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces[:])
    obj = _mesh_object("floor", bm, collection, "floor")
    obj.data.materials.append(_material("disco floor", (0.55, 0.45, 0.35)))
    return obj


def _outward(a, b):
    """The unit normal of edge a -> b pointing out of a counter-clockwise outline."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = math.hypot(dx, dy)
    return (dy / length, -dx / length)


def _outer_corners(points, thickness):
    """Each vertex moved out by the wall thickness along both its walls (a mitred corner)."""
    n = len(points)
    corners = []
    for i in range(n):
        before = _outward(points[i - 1], points[i])
        after = _outward(points[i], points[(i + 1) % n])
        along = 1.0 + before[0] * after[0] + before[1] * after[1]
        k = thickness / along
        corners.append((points[i][0] + (before[0] + after[0]) * k,
                        points[i][1] + (before[1] + after[1]) * k))
    return corners


def wall_blocks(room, index, wall_height_cm=WALL_HEIGHT_CM, thickness_cm=WALL_THICKNESS_CM,
                door_height_cm=DOOR_HEIGHT_CM):
    """Wall ``index`` as solid blocks ``(quad_cm, bottom_cm, top_cm)``, its openings left out:
    full-height pieces between openings, the wall above each door, below and above each
    window. The ends are mitred to meet the neighbouring walls outside the room."""
    points = outline(room)
    n = len(points)
    start, end = points[index], points[(index + 1) % n]
    outer = _outer_corners(points, thickness_cm)
    length = math.hypot(end[0] - start[0], end[1] - start[1])
    ux, uy = (end[0] - start[0]) / length, (end[1] - start[1]) / length
    ox, oy = _outward(start, end)

    def inner(u):
        return (start[0] + ux * u, start[1] + uy * u)

    def out(u):
        if u <= 0.0:
            return outer[index]
        if u >= length:
            return outer[(index + 1) % n]
        x, y = inner(u)
        return (x + ox * thickness_cm, y + oy * thickness_cm)

    def quad(u0, u1):
        return [inner(u0), inner(u1), out(u1), out(u0)]

    holes = sorted((h for h in openings(room, wall_height_cm, door_height_cm) if h[0] == index),
                   key=lambda h: h[1])
    blocks = []
    u = 0.0
    for _, u0, u1, bottom, top, _ in holes:
        if u0 > u:
            blocks.append((quad(u, u0), 0.0, wall_height_cm))
        if bottom > 0.0:
            blocks.append((quad(u0, u1), 0.0, bottom))
        if top < wall_height_cm:
            blocks.append((quad(u0, u1), top, wall_height_cm))
        u = max(u, u1)
    if u < length:
        blocks.append((quad(u, length), 0.0, wall_height_cm))
    return blocks


def build_walls(room, collection, wall_height_cm=WALL_HEIGHT_CM, thickness_cm=WALL_THICKNESS_CM):
    """One wall object per outline edge, standing outside the room, with real holes."""
    material = _material("disco wall", (0.85, 0.85, 0.82))
    walls = []
    for index, name in enumerate(wall_names(room)):
        bm = bmesh.new()
        for quad, bottom, top in wall_blocks(room, index, wall_height_cm, thickness_cm):
            _prism(bm, [(x * CM, y * CM) for x, y in quad], bottom * CM, top * CM)
        obj = _mesh_object(name, bm, collection, "wall")
        obj["wall"] = index
        obj.data.materials.append(material)
        walls.append(obj)
    return walls


def _box(name, size_cm, collection):
    w, d, h = (s * CM for s in size_cm)
    bm = bmesh.new()
    half = [(-w / 2, -d / 2), (w / 2, -d / 2), (w / 2, d / 2), (-w / 2, d / 2)]
    _prism(bm, half, 0.0, h)
    return _mesh_object(name, bm, collection, "object")


def _label(obj, text, size_cm, collection):
    """The object's name written on its top, readable from above, inside its footprint."""
    curve = bpy.data.curves.new(f"{text} label", "FONT")
    curve.body = text
    curve.align_x = "CENTER"
    curve.align_y = "CENTER"
    width_m = size_cm[0] * CM
    curve.size = max(0.04, min(0.25, 1.6 * width_m / max(len(text), 1)))
    label = bpy.data.objects.new(f"{text} label", curve)
    label["disco_kind"] = "label"
    label.parent = obj
    label.location = (0.0, 0.0, size_cm[2] * CM + 0.002)
    label.data.materials.append(_material("disco label", (0.02, 0.02, 0.02), 0.5))
    collection.objects.link(label)
    return label


def _import_mesh(name, path, size_cm, collection):
    """The asset's ``.glb`` under an empty named ``name``: turned so its front (glTF +Z, which
    Blender's importer makes -Y) faces +Y, scaled to the asset's size, standing on Z = 0."""
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=os.fspath(path))
    imported = [o for o in bpy.data.objects if o not in before]
    meshes = [o for o in imported if o.type == "MESH"]
    if not meshes:
        raise ValueError(f"{path}: the file holds no mesh")
    bpy.context.view_layer.update()
    corners = [o.matrix_world @ Vector(c) for o in meshes for c in o.bound_box]
    lo = Vector((min(c.x for c in corners), min(c.y for c in corners), min(c.z for c in corners)))
    hi = Vector((max(c.x for c in corners), max(c.y for c in corners), max(c.z for c in corners)))
    extent = hi - lo
    root = bpy.data.objects.new(name, None)
    root["disco_kind"] = "object"
    root.empty_display_size = 0.1
    collection.objects.link(root)
    # The model, centred on its footprint, on the floor, front to +Y, at the asset's size.
    fit = bpy.data.objects.new(f"{name} model", None)
    fit["disco_kind"] = "mesh"
    collection.objects.link(fit)
    fit.parent = root
    fit.rotation_euler = (0.0, 0.0, math.pi)
    w, d, h = (s * CM for s in size_cm)
    fit.scale = (w / max(extent.x, 1e-9), d / max(extent.y, 1e-9), h / max(extent.z, 1e-9))
    pivot = bpy.data.objects.new(f"{name} pivot", None)
    pivot["disco_kind"] = "mesh"
    collection.objects.link(pivot)
    pivot.parent = fit
    pivot.location = (-(lo.x + hi.x) / 2, -(lo.y + hi.y) / 2, -lo.z)
    for o in imported:
        for c in o.users_collection:
            c.objects.unlink(o)
        collection.objects.link(o)
        o["disco_kind"] = "mesh"
        if o.parent is None:
            o.parent = pivot
    return root


def meshes_of(scene, scene_path=None):
    """The assets' mesh files by name, relative ones resolved against the scene file's folder
    (as ``disco export --scene`` resolves them)."""
    if not scene:
        return {}
    base = os.path.dirname(os.fspath(scene_path)) if scene_path else ""
    return {a["name"]: os.path.join(base, a["mesh"]) for a in scene["assets"] if a.get("mesh")}


def build_objects(layout, collection, meshes=None, labels=True):
    """One Blender object per placed object, named as in the layout, at its pose: its base at
    Z = ``elevation`` (cm, 0 when absent), so what stands on another object stands on its top
    and what hangs on a wall hangs at its height, its back on the wall."""
    meshes = meshes or {}
    made = []
    for o in layout["objects"]:
        name, size = o["name"], [float(s) for s in o["size"]]
        if name in meshes:
            obj = _import_mesh(name, meshes[name], size, collection)
        else:
            if size[2] <= FLOOR_CM:
                size = [size[0], size[1], max(size[2], 0.5)]
            obj = _box(name, size, collection)
            obj.data.materials.append(_material(f"disco {o['category']}", category_colour(o["category"])))
            if labels:
                _label(obj, name, size, collection)
        x, y = (float(v) for v in o["position"])
        elevation = float(o.get("elevation", 0.0))
        # The base at the object's elevation: on the floor, on its support's top or up its wall
        # (a wall object's pose already puts its back on the wall).
        obj.location = (x * CM, y * CM, elevation * CM)
        obj.rotation_euler = (0.0, 0.0, -math.radians(float(o["rotation"])))
        obj["category"] = o["category"]
        obj["position_cm"] = [x, y]
        obj["rotation_deg"] = float(o["rotation"])
        obj["size_cm"] = [float(s) for s in o["size"]]
        if elevation:
            obj["elevation_cm"] = elevation
        if o.get("on") is not None:
            obj["on"] = o["on"]
        if o.get("wall") is not None:
            obj["wall"] = int(o["wall"])
        made.append(obj)
    return made


def frame_camera(room, collection, aspect=4 / 3, wall_height_cm=WALL_HEIGHT_CM):
    """A perspective camera looking down at the room from the side of wall 0 at 60 degrees,
    moved back until the whole room, walls included, is in the picture."""
    from bpy_extras.object_utils import world_to_camera_view

    points = outline(room)
    xs, ys = [p[0] * CM for p in points], [p[1] * CM for p in points]
    centre = Vector(((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2, 0.0))
    pad = WALL_THICKNESS_CM * CM
    corners = [Vector((x, y, z)) for x in (min(xs) - pad, max(xs) + pad)
               for y in (min(ys) - pad, max(ys) + pad) for z in (0.0, wall_height_cm * CM)]
    data = bpy.data.cameras.new("camera")
    data.lens = 35.0
    data.clip_end = 1000.0
    cam = bpy.data.objects.new("camera", data)
    cam["disco_kind"] = "camera"
    collection.objects.link(cam)
    elevation, azimuth = math.radians(60.0), math.radians(-20.0)
    direction = Vector((math.sin(azimuth) * math.cos(elevation),
                        -math.cos(azimuth) * math.cos(elevation), math.sin(elevation)))
    scene = bpy.context.scene
    scene.camera = cam
    distance = 0.5 * max(max(xs) - min(xs), max(ys) - min(ys), 1.0)
    for _ in range(100):
        cam.location = centre + direction * distance
        cam.rotation_euler = (-direction).to_track_quat("-Z", "Y").to_euler()
        bpy.context.view_layer.update()
        seen = [world_to_camera_view(scene, cam, c) for c in corners]
        if all(0.03 <= v.x <= 0.97 and 0.03 <= v.y <= 0.97 and v.z > 0 for v in seen):
            break
        distance *= 1.04
    return cam


def add_light(room, collection):
    """A sun from above and to the side, and a soft grey sky."""
    data = bpy.data.lights.new("sun", "SUN")
    data.energy = 3.0
    data.angle = math.radians(10.0)
    sun = bpy.data.objects.new("sun", data)
    sun["disco_kind"] = "light"
    sun.rotation_euler = (math.radians(35.0), math.radians(15.0), math.radians(30.0))
    collection.objects.link(sun)
    world = bpy.context.scene.world or bpy.data.worlds.new("disco world")
    bpy.context.scene.world = world
    world.use_nodes = True
    background = world.node_tree.nodes.get("Background")
    if background is not None:
        background.inputs["Color"].default_value = (0.6, 0.65, 0.7, 1.0)
        background.inputs["Strength"].default_value = 0.6
    return sun


def clear_scene():
    """Empties the current scene (objects, and the meshes, curves and materials left unused)."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for pool in (bpy.data.meshes, bpy.data.curves, bpy.data.materials, bpy.data.cameras,
                 bpy.data.lights):
        for block in list(pool):
            if block.users == 0:
                pool.remove(block)


def build(layout, scene=None, *, wall_height_cm=WALL_HEIGHT_CM, clear=True, labels=True,
          aspect=4 / 3):
    """Builds ``layout`` (a dict, or the path of a layout file) in the current Blender scene, in
    a collection named after it; with ``scene`` (dict or path), assets that name a ``mesh`` get
    it. Returns the collection. ``clear`` empties the scene first."""
    scene_path = None if isinstance(scene, dict) or scene is None else scene
    layout, scene = _read(layout), _read(scene)
    if clear:
        clear_scene()
    collection = bpy.data.collections.new(layout.get("id") or "layout")
    bpy.context.scene.collection.children.link(collection)
    room = layout["room"]
    build_floor(room, collection)
    if wall_height_cm > 0:
        build_walls(room, collection, wall_height_cm)
    build_objects(layout, collection, meshes_of(scene, scene_path), labels)
    frame_camera(room, collection, aspect, max(wall_height_cm, 1.0))
    add_light(room, collection)
    return collection


def render(path, size=(640, 480), engine="CYCLES", samples=16):
    """Renders the current scene's camera to the PNG ``path``, headless: Cycles on the CPU with
    ``samples`` samples (few are enough to see the room), or ``"BLENDER_EEVEE_NEXT"`` where
    a GPU context exists."""
    scene = bpy.context.scene
    scene.render.engine = engine
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = os.path.abspath(os.fspath(path))
    if engine == "CYCLES":
        scene.cycles.device = "CPU"
        scene.cycles.samples = samples
        scene.cycles.use_denoising = False
        scene.cycles.max_bounces = 4
    bpy.ops.render.render(write_still=True)
    return scene.render.filepath


# ---------------------------------------------------------------------------------------------
# The add-on: File > Import > disco-layout (.json)


class IMPORT_OT_disco_layout(bpy.types.Operator):
    """Build a disco-layout layout as a room"""

    bl_idname = "import_scene.disco_layout"
    bl_label = "Import disco-layout (.json)"
    bl_options = {"REGISTER", "UNDO"}

    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    filter_glob: bpy.props.StringProperty(default="*.json", options={"HIDDEN"})
    scene_path: bpy.props.StringProperty(name="Scene (for meshes)", subtype="FILE_PATH")
    wall_height_cm: bpy.props.FloatProperty(name="Wall height (cm)", default=WALL_HEIGHT_CM,
                                            min=0.0, max=10000.0)

    def execute(self, context):
        build(self.filepath, self.scene_path or None, wall_height_cm=self.wall_height_cm,
              clear=False)
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


def _menu(self, context):
    self.layout.operator(IMPORT_OT_disco_layout.bl_idname, text="disco-layout (.json)")


def register():
    """Adds File > Import > disco-layout (.json)."""
    bpy.utils.register_class(IMPORT_OT_disco_layout)
    bpy.types.TOPBAR_MT_file_import.append(_menu)


def unregister():
    """Removes what :func:`register` added."""
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    bpy.utils.unregister_class(IMPORT_OT_disco_layout)


# ---------------------------------------------------------------------------------------------
# The command line


def main(argv=None):
    """``disco_blender.py LAYOUT.json [--scene SCENE.json] [--render OUT.png] [--blend
    OUT.blend] [--size W H] [--samples N] [--engine CYCLES] [--wall-height CM]``."""
    if argv is None:
        argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    parser = argparse.ArgumentParser(prog="disco_blender.py", description=__doc__.split("\n")[0])
    parser.add_argument("layout", help="the layout (JSON)")
    parser.add_argument("--scene", help="its scene, for the assets' meshes")
    parser.add_argument("--render", help="write a perspective picture (PNG) here")
    parser.add_argument("--blend", help="save the Blender file here")
    parser.add_argument("--size", nargs=2, type=int, default=[640, 480], metavar=("W", "H"))
    parser.add_argument("--samples", type=int, default=16)
    parser.add_argument("--engine", default="CYCLES")
    parser.add_argument("--wall-height", type=float, default=WALL_HEIGHT_CM)
    args = parser.parse_args(argv)
    collection = build(args.layout, args.scene, wall_height_cm=args.wall_height,
                       aspect=args.size[0] / args.size[1])
    objects = [o for o in collection.objects if o.get("disco_kind") == "object"]
    print(f"{collection.name}: {len(objects)} objects built")
    if args.blend:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.blend))
        print(f"{args.blend}: saved")
    if args.render:
        render(args.render, tuple(args.size), args.engine, args.samples)
        print(f"{args.render}: rendered {args.size[0]} x {args.size[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
