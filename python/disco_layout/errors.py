"""The exceptions of disco_layout, one per way a `disco` command fails.

Each carries ``exit_code``, the code the ``disco`` command exits with for the same failure, and
the fields of the failure (the file, the field and the reason of a refused input; the model of a
model server that could not be used; the layout a degraded run still produced).
"""

from typing import Any, Dict, List, Optional

__all__ = [
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


class DiscoError(Exception):
    """Base of every disco_layout error. ``exit_code`` is what ``disco`` exits with."""

    exit_code: int = 1

    def __init__(self, message: str, **fields: Any) -> None:
        super().__init__(message)
        for name, value in fields.items():
            setattr(self, name, value)


class ValidationError(DiscoError, ValueError):
    """An input was refused (exit 1): ``path`` (the file, or ``<scene>``, ``<layout>``,
    ``<config>`` for a dict), ``field`` (a JSON path such as ``assets[2].size``, or a line and
    column) and ``reason``."""

    path: str = ""
    field: str = ""
    reason: str = ""


class FileError(DiscoError, OSError):
    """A file could not be read or written (exit 1): ``path``. Nothing is left half-written."""

    path: str = ""


class SceneError(DiscoError):
    """A scene could not be finished (exit 1): ``scene_id`` and ``reason``."""

    scene_id: str = ""
    reason: str = ""


class ModelError(DiscoError):
    """A model server could not be used (exit 3): ``model`` and ``reason``. When fallbacks still
    finished the room, ``layout`` holds it (and any files asked for were written)."""

    exit_code = 3
    model: Optional[str] = None
    reason: str = ""
    layout: Optional[Dict[str, Any]] = None


class RenderError(DiscoError):
    """A picture or a 3D file could not be made (exit 1): ``reason``."""

    reason: str = ""


class ScenesFailedError(DiscoError):
    """Some scenes of a batch failed (exit 4); the others were written. ``reports`` holds every
    scene's report, the failed ones with ``status == "failed"`` and their ``reason``."""

    exit_code = 4
    reports: List[Dict[str, Any]] = []


class DeadlineError(DiscoError):
    """The scene missed ``run.scene_deadline_s`` (exit 5): what was left was finished by
    fallbacks and the final PRT; ``layout`` holds the complete layout (and any files asked for
    were written)."""

    exit_code = 5
    layout: Optional[Dict[str, Any]] = None


class RoleTimeout(TimeoutError):
    """Raised inside a Python role when the supervisor gave up on its call (``deadline_s``):
    the runtime has moved on (retry or fallback), and the role's answer would be thrown away."""


class SceneWarning(UserWarning):
    """A problem that does not stop a run: an asset too big for the room (it will be dropped),
    a layout that lists only some of the scene's assets."""
