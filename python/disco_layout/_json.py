"""Python objects to the JSON the library reads."""

import json
import os
from collections.abc import Mapping
from typing import Any


def is_path(obj: Any) -> bool:
    """Whether ``obj`` names a file (``str`` or ``os.PathLike``) rather than holding the JSON."""
    return isinstance(obj, (str, os.PathLike))


def _plain(value: Any) -> Any:
    # NumPy numbers and arrays (and anything else with ``tolist``) as plain lists and numbers.
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON: use dicts, lists, str and numbers")


def dumps(obj: Any) -> str:
    """A mapping (a scene, layout or agent graph as a dict) as JSON text."""
    if not isinstance(obj, Mapping):
        raise TypeError(f"expected a path or a dict, got {type(obj).__name__}")
    return json.dumps(obj, default=_plain, allow_nan=False)
