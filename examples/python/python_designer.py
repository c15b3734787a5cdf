"""A designer written in Python, plugged into the default agent graph.

The designer is a class registered by name; the graph's designer agent names it
(``impl = "shelf-first"``) and keeps the default graph's supervision: a deadline per call,
retries, and the rule designer as the fallback when it fails. It gets each request of the JSON
protocol (docs/protocol) as a dict and answers poses; the evaluator, the refiners and the
final PRT of the default graph do the rest.

This one lines the objects the plan puts against a wall along the walls, largest first, and
stands the others in a row across the middle of the room.

    python examples/python/python_designer.py [SCENE.json]
"""

import sys
from pathlib import Path

import disco_layout as dl

SCENE = Path(__file__).resolve().parent.parent / "scenes" / "bedroom.json"


class ShelfFirst:
    """Made once per scene; ``options`` of the agent's table arrive as keyword arguments."""

    def __init__(self, gap_cm=10):
        self.gap = float(gap_cm)
        self.calls = 0

    def __call__(self, request):
        self.calls += 1
        body = request["request"]
        room = body["scene"]["room"]
        width = room.get("width") or max(p[0] for p in room["polygon"])
        depth = room.get("depth") or max(p[1] for p in room["polygon"])
        assets = {a["name"]: a for a in body["scene"]["assets"]}
        constraints = body["plan"]["constraints"]
        group = sorted(body["group"], key=lambda n: -assets[n]["size"][0])
        taken = sum(o["size"][0] + self.gap for o in body["placed"]
                    if constraints.get(o["name"], {}).get("against_wall"))
        poses, middle = [], self.gap
        for name in group:
            w, d, _ = assets[name]["size"]
            if constraints.get(name, {}).get("against_wall") and taken + w <= width:
                # Back on the top wall, facing into the room (rotation 180 faces -y).
                poses.append({"name": name, "position": [taken + w / 2, depth - d / 2], "rotation": 180})
                taken += w + self.gap
            else:
                poses.append({"name": name, "position": [middle + w / 2, depth / 2], "rotation": 0})
                middle += w + self.gap
        return {"objects": poses}


def main():
    scene = Path(sys.argv[1]) if len(sys.argv) > 1 else SCENE
    dl.register_role("designer", "shelf-first", ShelfFirst)
    layout = dl.generate(scene, "default", sets=[
        "agents.designer.impl=shelf-first",
        "agents.designer.options.gap_cm=15",
        "agents.designer.fallback=rules",
    ])
    m = dl.metrics(scene, layout)
    print(f"{layout['id']}: {len(layout['objects'])} placed, {len(layout['dropped'])} dropped")
    print(f"collisions {m['collision_pct']:.1f}%, out of bounds {m['oob_pct']:.1f}%, "
          f"constraints met {m['constraint_pct']:.1f}%, reachable {m['reach_pct']:.1f}%")
    for note in layout["stats"].get("fallbacks", []) + layout["stats"].get("notes", []):
        print(f"note: {note}")


if __name__ == "__main__":
    main()
