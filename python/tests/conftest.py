"""Shared fixtures: the repository's example scenes and the `disco` binary to compare with."""

import json
import os
import re
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENES = REPO / "examples" / "scenes"


@pytest.fixture(scope="session")
def disco():
    """Runs the `disco` command (``$DISCO_BIN``, as scripts/test-python builds it) and returns
    the finished process; ``check=False`` lets a test look at a failure."""
    binary = os.environ.get("DISCO_BIN") or str(REPO / "target" / "debug" / "disco")
    if not Path(binary).is_file():
        pytest.fail(f"no disco binary at {binary}: set DISCO_BIN (scripts/test-python does)")

    def run(*args, check=True):
        done = subprocess.run(
            [binary, *map(str, args)], capture_output=True, text=True, cwd=REPO
        )
        if check and done.returncode != 0:
            raise AssertionError(f"disco {args} exited {done.returncode}: {done.stderr}")
        return done

    return run


@pytest.fixture
def bedroom():
    return SCENES / "bedroom.json"


@pytest.fixture
def bedroom_dict(bedroom):
    return json.loads(bedroom.read_text())


def without_wall_ms(text: str) -> str:
    """A layout's JSON with its one time measurement blanked: everything else is deterministic."""
    masked, count = re.subn(r'"wall_ms": \d+', '"wall_ms": 0', text)
    assert count == 1, "a layout has exactly one wall_ms"
    return masked
