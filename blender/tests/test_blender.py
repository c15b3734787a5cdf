"""A layout built as a Blender scene (bpy from PyPI) and rendered headless."""

import json
import math
import struct
import subprocess
import sys
from pathlib import Path

import pytest

import bpy  # noqa: E402  (bpy first: bmesh and mathutils come with it)
from mathutils import Vector

import disco_layout as dl

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "blender"))
import disco_blender  # noqa: E402

STUDIO = REPO / "examples" / "scenes" / "l-shaped-studio.json"


@pytest.fixture(scope="module")
def studio():
    """The L-shaped studio (a polygon with a door and two windows), furnished."""
    return json.loads(STUDIO.read_text()), dl.generate(STUDIO)


def glb_node_names(glb):
    """The node names of a binary glTF: its JSON chunk follows the 12-byte header."""
    length, kind = struct.unpack_from("<I4s", glb, 12)
    assert kind == b"JSON"
    return {n["name"] for n in json.loads(glb[20:20 + length])["nodes"]}


def made(kind):
    return {o.name: o for o in bpy.context.scene.objects if o.get("disco_kind") == kind}


def test_objects_are_the_layouts_by_name_and_pose(studio):
    scene, layout = studio
    disco_blender.build(layout, scene)
    objects = made("object")
    assert len(objects) == len(layout["objects"]) == 9
    assert set(objects) == {o["name"] for o in layout["objects"]}
    for o in layout["objects"]:
        obj = objects[o["name"]]
        x, y = o["position"]
        assert (obj.location - Vector((x / 100, y / 100, 0))).length < 1e-6, o["name"]
        turn = -math.radians(o["rotation"])
        assert abs(math.remainder(obj.rotation_euler.z - turn, 2 * math.pi)) < 1e-6, o["name"]
        assert obj.rotation_euler.x == obj.rotation_euler.y == 0.0
        w, d, h = (s / 100 for s in o["size"])
        dims = obj.dimensions
        assert abs(dims.x - w) < 1e-5 and abs(dims.y - d) < 1e-5, o["name"]
        assert abs(dims.z - max(h, 0.005)) < 1e-5, o["name"]
        assert obj["category"] == o["category"]
    # Each box's front (+Y before the turn) points where the layout's rotation says.
    bed = objects["bed-0"]
    front = bed.matrix_world.to_3x3() @ Vector((0, 1, 0))
    r = math.radians(next(o for o in layout["objects"] if o["name"] == "bed-0")["rotation"])
    assert (front - Vector((math.sin(r), math.cos(r), 0))).length < 1e-6
    labels = made("label")
    assert {l.parent.name for l in labels.values()} == set(objects), "every box is labelled"
    # The same names as the glTF export gives its nodes.
    names = set(made("floor")) | set(made("wall")) | set(objects)
    assert names == glb_node_names(dl.export_glb(layout)) - {layout["id"]}


def wall_hit(wall, point_cm, outward):
    """Whether a ray across `wall` at `point_cm` (x, y, z in cm, just inside the room),
    going out of the room, meets the wall."""
    origin = Vector(point_cm) / 100 - outward * 0.05
    hit, *_ = wall.ray_cast(origin, outward, distance=1.0)
    return hit


def test_walls_have_real_holes_for_doors_and_windows(studio):
    scene, layout = studio
    disco_blender.build(layout, scene)
    room = scene["room"]
    points = room["polygon"]
    walls = made("wall")
    assert set(walls) == {f"wall-{i}" for i in range(len(points))}
    assert "floor" in made("floor")
    openings = [(d, "door") for d in room["doors"]] + [(w, "window") for w in room["windows"]]
    assert len(openings) == 3
    for opening, kind in openings:
        i = opening["wall"]
        (ax, ay), (bx, by) = points[i], points[(i + 1) % len(points)]
        length = math.hypot(bx - ax, by - ay)
        ux, uy = (bx - ax) / length, (by - ay) / length
        outward = Vector((uy, -ux, 0))
        at = opening["at"]

        def point(along, z):
            return (ax + ux * along, ay + uy * along, z)

        wall = walls[f"wall-{i}"]
        if kind == "door":
            low, high = 5.0, 200.0
            assert wall_hit(wall, point(at, 230.0), outward), "wall above the door"
        else:
            low, high = opening["sill"] + 5, opening["sill"] + opening["height"] - 5
            assert wall_hit(wall, point(at, opening["sill"] / 2), outward), "wall under the sill"
        for z in (low, (low + high) / 2, high):
            assert not wall_hit(wall, point(at, z), outward), f"{kind} on wall {i} at {z} cm"
            beside = at + opening["width"] / 2 + 15
            assert wall_hit(wall, point(beside, z), outward), f"solid beside the {kind}"


def test_an_asset_with_a_mesh_gets_it_at_its_size(studio, tmp_path):
    scene, layout = studio
    disco_blender.clear_scene()
    bpy.ops.mesh.primitive_cone_add(radius1=1.0, depth=3.0)
    cone = tmp_path / "cone.glb"
    bpy.ops.export_scene.gltf(filepath=str(cone), use_selection=True)
    scene = json.loads(json.dumps(scene))
    for a in scene["assets"]:
        if a["name"] == "wardrobe-0":
            a["mesh"] = "cone.glb"
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    disco_blender.build(layout, tmp_path / "scene.json")
    wardrobe = made("object")["wardrobe-0"]
    assert wardrobe.type == "EMPTY" and len(made("object")) == 9
    meshes = [o for o in wardrobe.children_recursive if o.type == "MESH"]
    assert meshes, "the cone was imported under the wardrobe"
    bpy.context.view_layer.update()
    corners = [m.matrix_world @ Vector(c) for m in meshes for c in m.bound_box]
    size = next(a["size"] for a in scene["assets"] if a["name"] == "wardrobe-0")
    pose = next(o for o in layout["objects"] if o["name"] == "wardrobe-0")
    turned = round(pose["rotation"]) % 180 == 90
    want_x, want_y = (size[1], size[0]) if turned else (size[0], size[1])
    extent = [max(c[k] for c in corners) - min(c[k] for c in corners) for k in range(3)]
    assert extent == pytest.approx([want_x / 100, want_y / 100, size[2] / 100], abs=1e-3)
    assert min(c.z for c in corners) == pytest.approx(0.0, abs=1e-6), "standing on the floor"
    centre_x = (max(c.x for c in corners) + min(c.x for c in corners)) / 2
    assert centre_x == pytest.approx(pose["position"][0] / 100, abs=1e-3)


def test_the_command_renders_a_picture_that_is_not_blank(studio, tmp_path):
    scene, layout = studio
    (tmp_path / "layout.json").write_text(json.dumps(layout))
    done = subprocess.run(
        [sys.executable, str(REPO / "blender" / "disco_blender.py"), str(tmp_path / "layout.json"),
         "--scene", str(STUDIO), "--render", str(tmp_path / "room.png"), "--blend",
         str(tmp_path / "room.blend"), "--size", "200", "150", "--samples", "4"],
        capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert "9 objects built" in done.stdout
    png = tmp_path / "room.png"
    assert png.read_bytes()[:4] == b"\x89PNG" and (tmp_path / "room.blend").is_file()
    image = bpy.data.images.load(str(png))
    assert tuple(image.size) == (200, 150)
    pixels = image.pixels[:]
    lum = [0.2126 * pixels[i] + 0.7152 * pixels[i + 1] + 0.0722 * pixels[i + 2]
           for i in range(0, len(pixels), 4)]
    mean = sum(lum) / len(lum)
    spread = math.sqrt(sum((v - mean) ** 2 for v in lum) / len(lum))
    colours = {tuple(round(pixels[i + k] * 15) for k in range(3)) for i in range(0, len(pixels), 4)}
    assert 0.05 < mean < 0.95 and spread > 0.05, (mean, spread)
    assert len(colours) > 40, f"only {len(colours)} colours: the picture is not of a room"


# ---------------------------------------------------------------------------------------------
# Objects off the floor: a lamp on a nightstand, a painting and a clock on walls.

RAISED = {
    "id": "raised",
    "room": {"width": 400, "depth": 300,
             "windows": [{"wall": 1, "at": 240, "width": 80, "sill": 90, "height": 120}]},
    "objects": [
        {"name": "bed-0", "category": "bed", "size": [160, 200, 50], "position": [200, 200],
         "rotation": 180},
        {"name": "nightstand-0", "category": "nightstand", "size": [50, 40, 55],
         "position": [90, 280], "rotation": 180},
        {"name": "lamp-0", "category": "table lamp", "size": [30, 30, 45], "position": [90, 280],
         "rotation": 180, "elevation": 55, "on": "nightstand-0"},
        {"name": "painting-0", "category": "painting", "size": [80, 4, 60], "position": [398, 150],
         "rotation": 270, "elevation": 130, "wall": 1},
        {"name": "clock-0", "category": "wall clock", "size": [30, 5, 30], "position": [100, 2.5],
         "rotation": 0, "elevation": 190, "wall": 0},
    ],
}
"""Elevations by name (cm): what the boxes' lowest points must be at."""
HEIGHTS = {o["name"]: float(o.get("elevation", 0)) for o in RAISED["objects"]}


def world_corners(objects):
    """The world-space corners of the bounding boxes of every mesh among `objects`."""
    bpy.context.view_layer.update()
    return [o.matrix_world @ Vector(c) for o in objects if o.type == "MESH" for c in o.bound_box]


def test_objects_off_the_floor_are_built_at_their_elevation_and_walls():
    disco_blender.build(RAISED)
    objects = made("object")
    assert set(objects) == set(HEIGHTS)
    for name, elevation in HEIGHTS.items():
        corners = world_corners([objects[name]])
        lowest = min(c.z for c in corners)
        assert lowest == pytest.approx(elevation / 100, abs=1e-3), name
    assert objects["lamp-0"]["on"] == "nightstand-0"
    assert objects["painting-0"]["wall"] == 1 and objects["painting-0"]["elevation_cm"] == 130
    assert "elevation_cm" not in objects["bed-0"] and "on" not in objects["bed-0"]
    # The lamp stands on the nightstand's top, within its footprint.
    top = max(c.z for c in world_corners([objects["nightstand-0"]]))
    assert min(c.z for c in world_corners([objects["lamp-0"]])) == pytest.approx(top, abs=1e-3)
    # Wall objects have their backs on their walls: the painting's on wall 1 (x = 4 m), the
    # clock's on wall 0 (y = 0), their fronts into the room.
    painting = world_corners([objects["painting-0"]])
    assert max(c.x for c in painting) == pytest.approx(4.0, abs=1e-3)
    assert min(c.x for c in painting) == pytest.approx(3.96, abs=1e-3)
    clock = world_corners([objects["clock-0"]])
    assert min(c.y for c in clock) == pytest.approx(0.0, abs=1e-3)
    front = objects["painting-0"].matrix_world.to_3x3() @ Vector((0, 1, 0))
    assert (front - Vector((-1, 0, 0))).length < 1e-6
    # The names ride on the tops of the boxes, so they rise with them.
    label = next(l for l in made("label").values() if l.parent.name == "lamp-0")
    assert label.matrix_world.translation.z == pytest.approx(1.0 + 0.002, abs=1e-3)


def test_the_glb_export_puts_every_object_at_its_elevation_in_blenders_importer(tmp_path):
    glb = tmp_path / "raised.glb"
    glb.write_bytes(dl.export_glb(RAISED))
    disco_blender.clear_scene()
    bpy.ops.import_scene.gltf(filepath=str(glb))
    imported = {o.name: o for o in bpy.context.scene.objects}
    for name, elevation in HEIGHTS.items():
        assert name in imported, f"{name} not among {sorted(imported)}"
        corners = world_corners([imported[name]])
        assert corners, f"{name} has no mesh"
        lowest = min(c.z for c in corners)
        assert lowest == pytest.approx(elevation / 100, abs=1e-3), name
        size = next(o["size"] for o in RAISED["objects"] if o["name"] == name)
        highest = max(c.z for c in corners)
        assert highest - lowest == pytest.approx(size[2] / 100, abs=1e-3), name
    # glTF's -Z is our +y; Blender's importer turns glTF Y-up back to Z-up with our y as +Y.
    painting = world_corners([imported["painting-0"]])
    assert max(c.x for c in painting) == pytest.approx(4.0, abs=1e-3)
    clock = world_corners([imported["clock-0"]])
    assert min(c.y for c in clock) == pytest.approx(0.0, abs=1e-3)
    lamp = imported["lamp-0"]
    assert lamp.get("on") == "nightstand-0" and lamp.get("elevation_cm") == 55
