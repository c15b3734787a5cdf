"""Refine the output of another layout generator and print the metrics before and after.

Another generator (LayoutGPT, Holodeck, your own) gives poses that overlap and poke through
walls; disco_layout's Physical Refinement Tool makes them physically valid with the fewest and
smallest moves. Here the "other generator" is a stand-in that scatters the assets at random.

    python examples/python/refine_foreign.py [SCENE.json]
"""

import json
import random
import sys
from pathlib import Path

import disco_layout as dl

HERE = Path(__file__).resolve().parent
SCENE = HERE.parent / "scenes" / "living-room.json"


def other_generator(scene, seed=7):
    """A careless generator: every asset somewhere in the room's bounding box, roughly turned.
    Its layout is complete (sizes and categories too), as most generators write them."""
    rng = random.Random(seed)
    room = scene["room"]
    xs = [p[0] for p in room["polygon"]] if "polygon" in room else [0, room["width"]]
    ys = [p[1] for p in room["polygon"]] if "polygon" in room else [0, room["depth"]]
    objects = [
        {"name": a["name"], "category": a["category"], "size": a["size"],
         "position": [rng.uniform(min(xs), max(xs)), rng.uniform(min(ys), max(ys))],
         "rotation": rng.choice([0, 90, 180, 270]) + rng.uniform(-15, 15)}
        for a in scene["assets"]
    ]
    return {"id": scene.get("id", "scene"), "room": room, "objects": objects, "dropped": []}


def main():
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else SCENE
    scene = json.loads(path.read_text())
    draft = other_generator(scene)
    before = dl.metrics(scene, draft)
    refined = dl.refine(scene, draft)
    after = dl.metrics(scene, refined)
    prt = refined["stats"]["prt"]
    print(f"{'':18}{'before':>10}{'after':>10}")
    for key, label in [("collision_pct", "collisions %"), ("oob_pct", "out of bounds %"),
                       ("reach_pct", "reachable %"), ("dropped_pct", "dropped %")]:
        print(f"{label:18}{before[key]:10.1f}{after[key]:10.1f}")
    print(f"moved {prt['moved']} objects, mean {prt['mean_displacement_cm']:.1f} cm, "
          f"max {prt['max_displacement_cm']:.1f} cm")
    assert after["collision_pct"] == 0.0 and after["oob_pct"] == 0.0


if __name__ == "__main__":
    main()
