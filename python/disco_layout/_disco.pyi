"""Type stubs of the native module ``disco_layout._disco`` (the Rust part of the package).

The documented API is :mod:`disco_layout`, which wraps these functions one for one.
"""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

_Path = Union[str, "os.PathLike[str]"]
_Json = Dict[str, Any]
_Input = Union[_Path, Mapping[str, Any]]

__version__: str
DEFAULT_SCENE_ID: str

class Trace:
    """A run's events; pass to ``generate(trace=...)`` to record them."""

    def __init__(self, snapshots: bool = True) -> None: ...
    def events(self) -> List[_Json]:
        """Every event so far, as the dicts of the JSON lines ``--trace`` writes."""
    def write_jsonl(self, path: _Path) -> None:
        """Writes the events as JSON lines, atomically."""
    def __len__(self) -> int: ...

def validate(scene: _Input) -> _Json: ...
def generate(
    scene: _Input,
    config: Optional[_Input] = None,
    sets: Sequence[str] = ...,
    *,
    cache: Optional[_Path] = None,
    output: Optional[_Path] = None,
    renders: Optional[_Path] = None,
    glb: Optional[_Path] = None,
    report: Optional[_Path] = None,
    trace: Union[_Path, Trace, None] = None,
    wall_height_cm: float = 250.0,
    strict: bool = True,
) -> _Json: ...
def batch(
    scenes: Sequence[_Path],
    out: _Path,
    *,
    jobs: int = 4,
    config: Optional[_Input] = None,
    sets: Sequence[str] = ...,
    cache: Optional[_Path] = None,
    shard: Optional[str] = None,
    trace: Optional[_Path] = None,
    on_progress: Optional[Callable[[int, int, _Json], None]] = None,
    strict: bool = True,
) -> List[_Json]: ...
def refine(
    scene: _Input,
    layout: _Input,
    *,
    grid_step_cm: float = 5.0,
    output: Optional[_Path] = None,
    render: Optional[_Path] = None,
) -> _Json: ...
def metrics(scene: _Input, layout: _Input) -> _Json: ...
def render_png(layout: _Input, *, scene: Optional[_Input] = None, size: int = 1024) -> bytes: ...
def export_glb(
    layout: _Input, scene: Optional[_Input] = None, *, wall_height_cm: float = 250.0
) -> bytes: ...
def report_html(scene: _Input, layout: _Input, trace: Optional[Trace] = None) -> str: ...
def register_role(role: str, name: str, implementation: Any) -> None: ...
def unregister_role(role: str, name: str) -> bool: ...
def registered_roles() -> List[Tuple[str, str]]: ...
def presets() -> List[Tuple[str, str]]: ...
