"""disco_layout: furnished 3D rooms from a sentence and an asset list, from Python.

The same library as the ``disco`` command, so every function gives what the command of the
same name gives (the tests compare them byte for byte). Scenes, layouts and agent graphs go in
as paths or as dicts holding the same JSON as the files; layouts, metrics and reports come out
as dicts of that JSON. Units are centimetres and degrees (see docs/formats.md).

Long calls release the GIL and run on the library's own tokio runtime, so threads run rooms in
parallel, and Ctrl-C interrupts them. Failures raise the exceptions of
:mod:`disco_layout.errors`, which mirror the command's exit codes.

    >>> import disco_layout as dl
    >>> layout = dl.generate("examples/scenes/bedroom.json")
    >>> dl.metrics("examples/scenes/bedroom.json", layout)["collision_pct"]
    0.0
"""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _disco
from ._disco import Trace
from .errors import (
    DeadlineError,
    DiscoError,
    FileError,
    ModelError,
    RenderError,
    RoleTimeout,
    SceneError,
    ScenesFailedError,
    SceneWarning,
    ValidationError,
)

__version__: str = _disco.__version__

PathLike = Union[str, "os.PathLike[str]"]
"""A file name."""
Json = Dict[str, Any]
"""A JSON object as Python reads it: a dict of str, numbers, lists, dicts, bools and None."""
SceneLike = Union[PathLike, Mapping[str, Any]]
"""A scene: its file, or the dict of its JSON (an ``id`` defaults to ``"scene"``)."""
LayoutLike = Union[PathLike, Mapping[str, Any]]
"""A layout: its file, or the dict of its JSON (as ``generate`` returns it)."""
ConfigLike = Union[PathLike, Mapping[str, Any], None]
"""An agent graph: ``None`` for the built-in default, a TOML file, a built-in graph's name
(``"default"``, ``"local-llm"``, ... see :func:`presets`), or a dict of the TOML's tables."""
Role = Callable[[Json], Any]
"""A Python role: gets a request of the JSON protocol (docs/protocol), returns its reply."""

__all__ = [
    "Trace",
    "generate",
    "batch",
    "refine",
    "metrics",
    "validate",
    "render_png",
    "export_glb",
    "report_html",
    "register_role",
    "unregister_role",
    "registered_roles",
    "presets",
    "DiscoError",
    "ValidationError",
    "FileError",
    "SceneError",
    "ModelError",
    "RenderError",
    "ScenesFailedError",
    "DeadlineError",
    "RoleTimeout",
    "SceneWarning",
]


def generate(
    scene: SceneLike,
    config: ConfigLike = None,
    sets: Sequence[str] = (),
    *,
    cache: Optional[PathLike] = None,
    output: Optional[PathLike] = None,
    renders: Optional[PathLike] = None,
    glb: Optional[PathLike] = None,
    report: Optional[PathLike] = None,
    trace: Union[PathLike, Trace, None] = None,
    wall_height_cm: float = 250.0,
    strict: bool = True,
) -> Json:
    """Furnishes one room, as ``disco generate``: plan, then design, evaluate and refine group
    by group, then the final PRT. Returns the layout.

    ``sets`` are ``--set`` overrides (``"agents.designer.impl=noisy"``), ``cache`` is
    ``--cache`` (record and replay model answers). ``output``, ``renders``, ``glb``,
    ``report`` and ``trace`` write the files the flags of the same names write, byte for byte
    as the command does; ``trace`` may also be a :class:`Trace` to record the events into.

    Raises :class:`ValidationError` for a refused scene or graph, :class:`ModelError` for a model
    server that cannot be used, :class:`SceneError` for a scene that could not be finished.
    With ``strict`` (the default), a room the command would write but exit 3 or 5 for raises
    :class:`ModelError` or :class:`DeadlineError` after writing, with the layout in ``.layout``;
    with ``strict=False`` it is returned (``stats.model_failures``, ``stats.deadline_missed``).
    """
    return _disco.generate(
        scene,
        config,
        list(sets),
        cache=cache,
        output=output,
        renders=renders,
        glb=glb,
        report=report,
        trace=trace,
        wall_height_cm=wall_height_cm,
        strict=strict,
    )


def batch(
    scenes: Sequence[PathLike],
    out: PathLike,
    *,
    jobs: int = 4,
    config: ConfigLike = None,
    sets: Sequence[str] = (),
    cache: Optional[PathLike] = None,
    shard: Optional[str] = None,
    trace: Optional[PathLike] = None,
    on_progress: Optional[Callable[[int, int, Json], None]] = None,
    strict: bool = True,
) -> List[Json]:
    """Furnishes many rooms at once, as ``disco batch``: ``scenes`` are files or folders of
    them, at most ``jobs`` in flight; each layout is written atomically as ``out/<id>.json``
    and a rerun skips scenes already done. Returns one report per scene (``input``, ``id``,
    ``status``: ``done``, ``skipped`` or ``failed`` with its ``reason``, ``metrics``,
    ``wall_ms``), sorted by input.

    ``on_progress(done, total, report)`` is called in the calling thread as each scene
    finishes; an exception from it stops the batch. ``shard="I/N"`` runs only shard I of N.
    With ``strict``, failed scenes raise :class:`ScenesFailedError` (exit 4) at the end, the
    reports in ``.reports``; the other scenes are written either way.
    """
    return _disco.batch(
        list(scenes),
        out,
        jobs=jobs,
        config=config,
        sets=list(sets),
        cache=cache,
        shard=shard,
        trace=trace,
        on_progress=on_progress,
        strict=strict,
    )


def refine(
    scene: SceneLike,
    layout: LayoutLike,
    *,
    grid_step_cm: float = 5.0,
    output: Optional[PathLike] = None,
    render: Optional[PathLike] = None,
) -> Json:
    """Makes any layout physically valid with the Physical Refinement Tool, as ``disco refine``:
    no collisions, everything inside the room, with the fewest and smallest moves. ``layout``
    may be another tool's draft: objects need only ``name`` and ``position`` (``rotation``
    defaults to 0); assets it does not place start at the room's centre. Returns the refined
    layout; ``output`` and ``render`` also write it and its picture."""
    return _disco.refine(scene, layout, grid_step_cm=grid_step_cm, output=output, render=render)


def metrics(scene: SceneLike, layout: LayoutLike) -> Json:
    """Measures a layout against its scene, as ``disco metrics --json``: Col, OOB, constraint
    satisfaction (overall, per kind), reach, dropped, displacement, and ``prompt_requests``
    (the prompt's placements checked on the layout). A layout naming objects the scene does
    not have raises :class:`ValidationError`."""
    return _disco.metrics(scene, layout)


def validate(scene: SceneLike) -> Json:
    """Checks a scene, as ``disco validate --json``: its verdict (``valid``, ``id``,
    ``assets``, ``room``, ``room_type``, ``warnings``) when valid; raises
    :class:`ValidationError` with the file, the field and the reason when not."""
    return _disco.validate(scene)


def render_png(
    layout: LayoutLike, *, scene: Optional[SceneLike] = None, size: int = 1024
) -> bytes:
    """The layout drawn from above, as PNG bytes, as ``disco render``: ``size`` pixels on the
    long side. With ``scene``, a draft layout (names and poses) is drawn too."""
    return _disco.render_png(layout, scene=scene, size=size)


def export_glb(
    layout: LayoutLike, scene: Optional[SceneLike] = None, *, wall_height_cm: float = 250.0
) -> bytes:
    """The room as binary glTF bytes, as ``disco export``: floor, walls (with door and window
    holes), one node per object. With ``scene``, assets that name a ``mesh`` get it instead of
    a box. Y up, metres; see docs/formats.md for the axes."""
    return _disco.export_glb(layout, scene, wall_height_cm=wall_height_cm)


def report_html(scene: SceneLike, layout: LayoutLike, trace: Optional[Trace] = None) -> str:
    """The self-contained HTML report of a run, as ``disco generate --report`` writes it. Pass
    the :class:`Trace` given to :func:`generate` for the step pictures, the messages and the
    model calls; without one the report has the result, the metrics and the plan."""
    return _disco.report_html(scene, layout, trace)


def register_role(role: str, name: str, implementation: Union[Role, type]) -> None:
    """Registers a Python role: ``impl = "NAME"`` in an agent graph's ``[agents.X]`` of that
    ``role`` (``planner``, ``designer``, ``evaluator``, ``srt``, ``prt`` or ``patch``) then runs
    it, in this process, under the same supervision as any implementation (``deadline_s``,
    ``retries``, ``fallback``, restarts).

    ``implementation`` is a callable, or a class instantiated once per scene with the agent's
    ``options`` as keyword arguments (its instances are called). It gets each request of the
    JSON protocol of docs/protocol as a dict (``request["request"]`` is the task) and returns
    the reply's body, e.g. ``{"objects": [{"name": ..., "position": [x, y], "rotation": r}]}``
    for a designer, or a whole reply dict (with ``"protocol"``, for ``notes`` or ``error``). An
    exception is the reply's error: retried, then the fallback. A call past ``deadline_s`` gets
    :class:`RoleTimeout` raised inside it. One agent's calls come one at a time; scenes running
    at once call from several threads (a class gets an instance per scene).
    """
    _disco.register_role(role, name, implementation)


def unregister_role(role: str, name: str) -> bool:
    """Removes a Python role registered with :func:`register_role`; whether there was one."""
    return _disco.unregister_role(role, name)


def registered_roles() -> List[Tuple[str, str]]:
    """The Python roles registered, as ``(role, name)`` pairs."""
    return _disco.registered_roles()


def presets() -> List[Tuple[str, str]]:
    """The built-in agent graphs (``disco config list``) as ``(name, description)``; any of
    these names is a valid ``config``."""
    return _disco.presets()
