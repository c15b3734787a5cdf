"""A custom stage (`role = "patch"`) in plain Python: every object of the group that the plan puts
against a wall is pushed back onto its nearest wall, facing into the room.

Run by the runtime as `impl = "process"` (config/experiments/python-agents.toml). It answers the
poses of the objects it moved; the others stay where they are.
"""

from agent_loop import log, serve


def onto_nearest_wall(room, obj):
    """The pose with the object's back on the wall nearest its centre."""
    w, d = obj["size"][0], obj["size"][1]
    width, depth = room["width"], room["depth"]
    x = min(max(obj["position"][0], w / 2), width - w / 2)
    y = min(max(obj["position"][1], w / 2), depth - w / 2)
    cx, cy = obj["position"]
    choices = [
        (cy, [x, d / 2], 0.0),  # back on the wall y = 0, facing +y
        (depth - cy, [x, depth - d / 2], 180.0),
        (cx, [d / 2, y], 90.0),  # back on the wall x = 0, facing +x
        (width - cx, [width - d / 2, y], 270.0),
    ]
    _, position, rotation = min(choices, key=lambda c: c[0])
    return position, rotation


def patch(body, _envelope):
    room = body["scene"]["room"]
    constraints = body["plan"]["constraints"]
    moved = []
    for obj in body["layout"]["objects"]:
        name = obj["name"]
        if name not in body["group"] or not constraints.get(name, {}).get("against_wall"):
            continue
        position, rotation = onto_nearest_wall(room, obj)
        if position != obj["position"] or rotation != obj["rotation"]:
            moved.append({"name": name, "position": position, "rotation": rotation})
    log(f"pushed {len(moved)} objects back onto a wall")
    return {"objects": moved}


if __name__ == "__main__":
    serve(patch)
