"""The three examples of examples/python run and print what they promise."""

import subprocess
import sys

from conftest import REPO

EXAMPLES = REPO / "examples" / "python"


def run(script, *args):
    done = subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)],
                          capture_output=True, text=True, cwd=REPO, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    return done


def test_refining_another_generators_layout_prints_the_metrics():
    out = run("refine_foreign.py").stdout
    before, after = (float(v) for v in out.split("collisions %")[1].split()[:2])
    assert before > 0.0 and after == 0.0, out
    assert "moved" in out


def test_a_hundred_rooms_in_parallel_with_a_progress_bar(tmp_path):
    done = run("many_rooms.py", tmp_path)
    assert "100 of 100 rooms" in done.stdout, done.stdout
    assert "100/100 rooms" in done.stderr, "the progress bar reached the end"
    assert len(list((tmp_path / "layouts").glob("*.json"))) == 100


def test_a_python_designer_in_the_default_graph():
    out = run("python_designer.py").stdout
    assert "7 placed, 0 dropped" in out and "collisions 0.0%" in out, out
    assert "shelf-first -> rules" not in out, "the Python designer did the work"
