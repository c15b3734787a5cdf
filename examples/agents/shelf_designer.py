"""A designer in plain Python: poses each object of the group on a coarse grid of free spots,
walls first for the objects the plan puts against a wall.

Run by the runtime as `impl = "process"` (config/experiments/python-agents.toml). It answers
`{"objects": [{"name", "position", "rotation"}]}`; sizes and categories come from the scene.
"""

from agent_loop import log, serve

STEP_CM = 10.0


def footprint(size, rotation):
    """The axis-aligned extent (x, y) of an object turned by a multiple of 90 degrees."""
    w, d = size[0], size[1]
    return (d, w) if round(rotation / 90) % 2 else (w, d)


def overlaps(a, b):
    """Whether two boxes (cx, cy, ex, ey) overlap."""
    return abs(a[0] - b[0]) * 2 < a[2] + b[2] and abs(a[1] - b[1]) * 2 < a[3] + b[3]


def wall_spots(room, size):
    """Spots with the object's back on a wall, facing the room: (x, y, rotation)."""
    width, depth = room["width"], room["depth"]
    w, d = size[0], size[1]
    x = w / 2
    while x <= width - w / 2:
        yield x, d / 2, 0.0
        yield x, depth - d / 2, 180.0
        x += STEP_CM
    y = w / 2
    while y <= depth - w / 2:
        yield d / 2, y, 90.0
        yield width - d / 2, y, 270.0
        y += STEP_CM


def floor_spots(room, size):
    """Spots anywhere on the floor, centre first."""
    width, depth = room["width"], room["depth"]
    spots = []
    y = size[1] / 2
    while y <= depth - size[1] / 2:
        x = size[0] / 2
        while x <= width - size[0] / 2:
            spots.append((x, y, 0.0))
            x += STEP_CM
        y += STEP_CM
    spots.sort(key=lambda s: (s[0] - width / 2) ** 2 + (s[1] - depth / 2) ** 2)
    return spots


def design(body, _envelope):
    scene, plan = body["scene"], body["plan"]
    sizes = {a["name"]: a["size"] for a in scene["assets"]}
    taken = []
    for o in body["placed"]:
        if o["size"][2] > 3:  # rugs may lie under furniture
            ex, ey = footprint(o["size"], o["rotation"])
            taken.append((o["position"][0], o["position"][1], ex, ey))
    objects = []
    for name in body["group"]:
        size = sizes[name]
        wall = plan["constraints"].get(name, {}).get("against_wall", False)
        spots = list(wall_spots(scene["room"], size)) if wall else []
        spots += floor_spots(scene["room"], size)
        for x, y, rotation in spots:
            ex, ey = footprint(size, rotation)
            box = (x, y, ex, ey)
            if size[2] <= 3 or not any(overlaps(box, t) for t in taken):
                if size[2] > 3:
                    taken.append(box)
                objects.append({"name": name, "position": [x, y], "rotation": rotation})
                break
        else:
            log(f"no free spot for {name}; leaving it to the PRT")
    log(f"posed {len(objects)} of {len(body['group'])} objects")
    return {"objects": objects}


if __name__ == "__main__":
    serve(design)
