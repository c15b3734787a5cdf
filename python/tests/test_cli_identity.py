"""Every function gives what the `disco` command of the same name gives, byte for byte."""

import json
import re

import disco_layout as dl

from conftest import SCENES, without_wall_ms


def test_generate_writes_what_the_cli_writes(disco, bedroom, tmp_path):
    cli, py = tmp_path / "cli", tmp_path / "py"
    disco("generate", bedroom, "-o", cli / "room.json", "--glb", cli / "room.glb",
          "--renders", cli / "renders", "--report", cli / "room.html")
    layout = dl.generate(bedroom, output=py / "room.json", glb=py / "room.glb",
                         renders=py / "renders", report=py / "room.html")

    cli_json = (cli / "room.json").read_text()
    assert without_wall_ms((py / "room.json").read_text()) == without_wall_ms(cli_json)
    cli_layout = json.loads(cli_json)
    cli_layout["stats"]["wall_ms"] = layout["stats"]["wall_ms"]
    assert layout == cli_layout, "the returned dict is the file's JSON"
    assert (py / "room.glb").read_bytes() == (cli / "room.glb").read_bytes()
    cli_pngs = sorted(p.relative_to(cli) for p in (cli / "renders").rglob("*.png"))
    py_pngs = sorted(p.relative_to(py) for p in (py / "renders").rglob("*.png"))
    assert py_pngs == cli_pngs and len(cli_pngs) > 2, "the result, the steps and the sheet"
    for rel in cli_pngs:
        assert (py / rel).read_bytes() == (cli / rel).read_bytes(), rel
    assert timings_masked((py / "room.html").read_text()) == timings_masked(
        (cli / "room.html").read_text()
    )


def timings_masked(html: str) -> str:
    """A report with the run's clock readings (event times, call and run durations) blanked."""
    html = re.sub(r"<td class=\"num\">[\d.]+</td>", '<td class="num">T</td>', html)
    return re.sub(r"\d+(\.\d+)? ms", "T ms", html)


def test_refine_writes_what_the_cli_writes(disco, bedroom, tmp_path):
    broken = SCENES / "bedroom-broken.layout.json"
    disco("refine", bedroom, broken, "-o", tmp_path / "cli.json", "--render", tmp_path / "cli.png")
    refined = dl.refine(bedroom, broken, output=tmp_path / "py.json", render=tmp_path / "py.png")
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    assert refined == json.loads((tmp_path / "cli.json").read_text())
    # The draft as a dict gives the same.
    assert dl.refine(bedroom, json.loads(broken.read_text())) == refined


def test_metrics_validate_render_and_export_match_the_cli(disco, bedroom, tmp_path):
    layout_file = tmp_path / "room.json"
    disco("generate", bedroom, "-o", layout_file)
    layout = json.loads(layout_file.read_text())

    cli_metrics = json.loads(disco("metrics", bedroom, layout_file, "--json").stdout)
    assert dl.metrics(bedroom, layout_file) == cli_metrics
    assert dl.metrics(bedroom, layout) == cli_metrics
    assert "prompt_requests" in cli_metrics and cli_metrics["collision_pct"] == 0.0

    assert dl.validate(bedroom) == json.loads(disco("validate", bedroom, "--json").stdout)

    disco("render", layout_file, "-o", tmp_path / "cli.png", "--size", 300)
    png = dl.render_png(layout, size=300)
    assert png == (tmp_path / "cli.png").read_bytes() and png[:4] == b"\x89PNG"
    draft = SCENES / "bedroom-broken.layout.json"
    disco("render", draft, "--scene", bedroom, "-o", tmp_path / "draft.png")
    assert dl.render_png(draft, scene=bedroom) == (tmp_path / "draft.png").read_bytes()

    disco("export", layout_file, "--scene", bedroom, "-o", tmp_path / "cli.glb",
          "--wall-height", 240)
    glb = dl.export_glb(layout, bedroom, wall_height_cm=240)
    assert glb == (tmp_path / "cli.glb").read_bytes() and glb[:4] == b"glTF"


def test_batch_writes_what_the_cli_writes(disco, tmp_path):
    scenes = [SCENES / "bedroom.json", SCENES / "office.json", SCENES / "dining-room.json"]
    cli = json.loads(disco("batch", *scenes, "--out", tmp_path / "cli", "--json").stdout)
    seen = []
    reports = dl.batch(scenes, tmp_path / "py", jobs=2,
                       on_progress=lambda done, total, r: seen.append((done, total, r["id"])))
    assert [(d, t) for d, t, _ in seen] == [(1, 3), (2, 3), (3, 3)]
    assert sorted(i for _, _, i in seen) == sorted(r["id"] for r in reports)
    strip = lambda rs: [{k: v for k, v in r.items() if k != "wall_ms"} for r in rs]
    assert strip(reports) == strip(cli)
    for r in cli:
        name = f"{r['id']}.json"
        assert without_wall_ms((tmp_path / "py" / name).read_text()) == without_wall_ms(
            (tmp_path / "cli" / name).read_text()
        )
    again = dl.batch(scenes, tmp_path / "py")
    assert {r["status"] for r in again} == {"skipped"}, "a rerun skips finished scenes"
