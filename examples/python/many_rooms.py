"""Generate 100 rooms in parallel with a progress bar.

Makes 100 variants of the example scenes (the same furniture in rooms of other sizes), writes
them to a folder, and furnishes them with ``disco_layout.batch``: as many rooms in flight as
there are cores, each layout written as OUT/<id>.json, a rerun skipping finished rooms. The
progress bar is drawn by ``on_progress``, called in this thread as each room finishes.

    python examples/python/many_rooms.py [OUT_DIR] [--count N]
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

import disco_layout as dl

SCENES = Path(__file__).resolve().parent.parent / "scenes"


def variants(count, folder):
    """``count`` scene files in ``folder``: the rectangular example scenes, each room stretched
    by up to 30% in width and depth."""
    bases = [json.loads(p.read_text()) for p in sorted(SCENES.glob("*.json"))
             if not p.name.endswith(".layout.json")]
    bases = [s for s in bases if "width" in s["room"]]
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for i in range(count):
        scene = json.loads(json.dumps(bases[i % len(bases)]))
        stretch = 1.0 + 0.3 * ((i * 37) % 11) / 10
        scene["room"]["width"] = round(scene["room"]["width"] * stretch)
        scene["room"]["depth"] = round(scene["room"]["depth"] * (2.3 - stretch))
        scene["id"] = f"{scene['id']}-{i:03d}"
        path = folder / f"{scene['id']}.json"
        path.write_text(json.dumps(scene))
        paths.append(path)
    return paths


def progress_bar(width=40):
    """An ``on_progress`` callback drawing a bar on stderr."""
    started = time.monotonic()

    def draw(done, total, report):
        filled = width * done // total
        rate = done / max(time.monotonic() - started, 1e-9)
        bar = "#" * filled + "." * (width - filled)
        sys.stderr.write(f"\r[{bar}] {done}/{total} rooms, {rate:.1f}/s, last {report['id']:<28}")
        if done == total:
            sys.stderr.write("\n")

    return draw


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", nargs="?", default="out/many-rooms")
    parser.add_argument("--count", type=int, default=100)
    args = parser.parse_args()
    out = Path(args.out)
    scenes = variants(args.count, out / "scenes")
    t0 = time.monotonic()
    reports = dl.batch([out / "scenes"], out / "layouts", jobs=os.cpu_count() or 2,
                       on_progress=progress_bar())
    seconds = time.monotonic() - t0
    done = [r for r in reports if r["status"] in ("done", "skipped")]
    mean = lambda key: sum(r["metrics"][key] for r in done) / max(len(done), 1)
    print(f"{len(done)} of {len(scenes)} rooms in {seconds:.1f} s: collisions {mean('collision_pct'):.1f}%, "
          f"constraints met {mean('constraint_pct'):.1f}%, reachable {mean('reach_pct'):.1f}%")
    print(f"layouts in {out / 'layouts'}")


if __name__ == "__main__":
    main()
