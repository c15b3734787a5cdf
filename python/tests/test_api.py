"""Round trips through dicts and files, and errors as exceptions that mirror the exit codes."""

import json
import os
import threading
import time
import _thread
import tomllib

import pytest

import disco_layout as dl
from disco_layout import errors

from conftest import REPO, SCENES


def test_a_scene_as_a_dict_gives_the_layout_of_its_file(bedroom, bedroom_dict):
    from_file = dl.generate(bedroom)
    from_dict = dl.generate(bedroom_dict)
    for layout in (from_file, from_dict):
        layout["stats"].pop("wall_ms")
    assert from_dict == from_file
    names = sorted(a["name"] for a in bedroom_dict["assets"])
    placed = [o["name"] for o in from_dict["objects"]] + [d["name"] for d in from_dict["dropped"]]
    assert sorted(placed) == names, "every asset exactly once"


def test_a_scene_dict_without_id_is_called_scene(bedroom_dict):
    del bedroom_dict["id"]
    assert dl.validate(bedroom_dict)["id"] == "scene"
    assert dl.generate(bedroom_dict)["id"] == "scene"


def test_layouts_round_trip_through_every_function(bedroom, tmp_path):
    layout = dl.generate(bedroom, output=tmp_path / "room.json")
    assert json.loads((tmp_path / "room.json").read_text()) == layout
    # The returned dict is accepted wherever a layout file is.
    assert dl.metrics(bedroom, layout) == dl.metrics(bedroom, tmp_path / "room.json")
    assert dl.render_png(layout) == dl.render_png(tmp_path / "room.json")
    assert dl.export_glb(layout) == dl.export_glb(tmp_path / "room.json")
    refined = dl.refine(bedroom, layout)
    assert refined["objects"] == layout["objects"], "a valid layout stays where it is"
    assert refined["stats"]["prt"]["moved"] == 0


def test_a_trace_records_the_run_and_feeds_the_report(bedroom, tmp_path):
    trace = dl.Trace()
    layout = dl.generate(bedroom, trace=trace)
    events = trace.events()
    assert len(trace) == len(events) > 0
    assert {"request", "reply", "stage", "snapshot"} <= {e["kind"] for e in events}
    html = dl.report_html(bedroom, layout, trace)
    assert html.startswith("<!doctype html>") and html.count("data:image/png;base64") > 2
    trace.write_jsonl(tmp_path / "t.jsonl")
    assert len((tmp_path / "t.jsonl").read_text().splitlines()) == len(events)
    dl.generate(bedroom, trace=tmp_path / "file.jsonl")
    lines = (tmp_path / "file.jsonl").read_text().splitlines()
    assert lines and all(json.loads(line)["scene"] == "bedroom-01" for line in lines)
    assert "snapshot" not in {json.loads(line)["kind"] for line in lines}, "as --trace alone"


def test_configs_by_name_path_and_dict(bedroom):
    names = [name for name, _ in dl.presets()]
    assert "default" in names and "local-llm" in names
    graph_file = REPO / "config" / "default.toml"
    as_dict = tomllib.loads(graph_file.read_text())
    runs = {
        "name": dl.generate(bedroom, "default"),
        "path": dl.generate(bedroom, graph_file),
        "dict": dl.generate(bedroom, as_dict),
    }
    as_dict["agents"]["designer"]["impl"] = "noisy"
    runs["noisy dict"] = dl.generate(bedroom, as_dict)
    runs["noisy set"] = dl.generate(bedroom, sets=["agents.designer.impl=noisy"])
    for layout in runs.values():
        layout["stats"].pop("wall_ms")
    assert runs["name"] == runs["path"] == runs["dict"]
    assert runs["noisy dict"] == runs["noisy set"]
    assert runs["noisy set"]["objects"] != runs["name"]["objects"], "the noise moved things"
    as_dict["agents"]["designer"]["impl"] = "rulez"
    with pytest.raises(dl.ValidationError) as e:
        dl.generate(bedroom, as_dict)
    assert e.value.path == "<config>" and e.value.field == "agents.designer.impl"


def test_a_refused_scene_names_the_file_field_and_reason(disco, bedroom_dict, tmp_path):
    bedroom_dict["assets"][2]["size"] = [1.6, 2.0, 1.0]
    with pytest.raises(dl.ValidationError) as e:
        dl.validate(bedroom_dict)
    assert (e.value.path, e.value.field) == ("<scene>", "assets[2].size")
    assert "centimetres" in e.value.reason and e.value.exit_code == 1
    assert isinstance(e.value, ValueError) and isinstance(e.value, dl.DiscoError)

    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(bedroom_dict))
    with pytest.raises(dl.ValidationError) as from_file:
        dl.generate(bad)
    cli = disco("validate", bad, check=False)
    assert cli.returncode == from_file.value.exit_code == 1
    assert cli.stderr.strip() == f"error: {from_file.value}"


def test_missing_files_bad_configs_and_foreign_layouts_raise(bedroom, tmp_path):
    with pytest.raises(dl.FileError) as e:
        dl.generate(tmp_path / "nowhere.json")
    assert isinstance(e.value, OSError) and e.value.path.endswith("nowhere.json")
    with pytest.raises(dl.ValidationError, match="did you mean `default`"):
        dl.generate(bedroom, "defualt")
    with pytest.raises(dl.ValidationError, match=r"agents\.designer\.impl"):
        dl.generate(bedroom, sets=["agents.designer.impl=rulez"])
    office = dl.generate(SCENES / "office.json")
    with pytest.raises(dl.ValidationError, match="is not an asset of scene"):
        dl.metrics(bedroom, office)
    with pytest.raises(TypeError, match="a path or a dict"):
        dl.validate(42)
    with pytest.raises(dl.ValidationError, match="would replace|same file|refus"):
        dl.generate(bedroom, output=bedroom)


def test_an_unreachable_model_server_is_a_model_error(bedroom, monkeypatch):
    monkeypatch.setenv("DISCO_LOCAL_LLM_URL", "http://127.0.0.1:9/v1")
    with pytest.raises(dl.ModelError) as e:
        dl.generate(bedroom, "local-llm")
    assert e.value.exit_code == 3 and e.value.model


def test_failed_scenes_of_a_batch_raise_with_every_report(bedroom, bedroom_dict, tmp_path):
    bad = tmp_path / "in" / "bad.json"
    bad.parent.mkdir()
    bedroom_dict["assets"] = []
    bad.write_text(json.dumps(bedroom_dict))
    with pytest.raises(dl.ScenesFailedError) as e:
        dl.batch([bedroom, bad], tmp_path / "out")
    assert e.value.exit_code == 4
    status = {r["id"]: r["status"] for r in e.value.reports}
    assert status == {"bedroom-01": "done", "bad": "failed"}, status
    assert (tmp_path / "out" / "bedroom-01.json").is_file()
    reports = dl.batch([bedroom, bad], tmp_path / "out", strict=False)
    assert {r["id"]: r["status"] for r in reports} == {"bedroom-01": "skipped", "bad": "failed"}


def test_ctrl_c_interrupts_a_long_call(bedroom):
    started, release = threading.Event(), threading.Event()

    def slow_designer(request):
        started.set()
        release.wait(20)
        return {"objects": []}

    dl.register_role("designer", "slow", slow_designer)
    try:
        timer = threading.Timer(0.5, _thread.interrupt_main)
        timer.start()
        t0 = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            dl.generate(bedroom, sets=["agents.designer.impl=slow", "agents.designer.deadline_s=60"])
        assert started.is_set()
        assert time.monotonic() - t0 < 5, "Ctrl-C did not wait for the role"
    finally:
        release.set()
        dl.unregister_role("designer", "slow")
