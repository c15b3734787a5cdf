"""The Python side of Python roles: making an implementation and one exchange of the protocol.

The native module calls these from the runtime's threads (see ``register_role``).
"""

import ctypes
import inspect
import json
import logging
import threading
from collections.abc import Mapping
from typing import Any, Callable, Dict, Optional

from . import _json
from .errors import RoleTimeout

PROTOCOL_VERSION = 1

log = logging.getLogger("disco_layout.roles")


def instantiate(implementation: Any, options: Dict[str, Any]) -> Callable[[Dict[str, Any]], Any]:
    """The callable that serves one agent: a class is instantiated with the agent's ``options``
    as keyword arguments (once per scene); a function is used as it is."""
    if inspect.isclass(implementation):
        instance = implementation(**options)
        if not callable(instance):
            raise TypeError(f"{implementation.__name__} instances must be callable (define __call__)")
        return instance
    if options:
        raise TypeError(
            f"options {sorted(options)} given to a function role: register a class to take them"
        )
    if not callable(implementation):
        raise TypeError(f"a role must be callable, got {type(implementation).__name__}")
    return implementation


def exchange(role: Callable[[Dict[str, Any]], Any], line: str) -> str:
    """One request (a line of the JSON protocol) through ``role``, and its reply line.

    ``role`` gets the request as a dict and returns the reply's body (``{"objects": [...]}``
    for a designer), or a whole reply (a dict with ``"protocol"``, which may carry ``notes`` or
    ``error``). An exception it raises becomes the reply's ``error``: the runtime retries the
    call, then swaps in the agent's fallback.
    """
    request = json.loads(line)
    try:
        result = role(request)
    except Exception as e:  # noqa: BLE001 - any failure of the role is its error reply
        log.debug("%s %s failed", request.get("role"), request.get("agent"), exc_info=True)
        error = {"protocol": PROTOCOL_VERSION, "id": request["id"], "error": f"{type(e).__name__}: {e}"}
        return json.dumps(error)
    if isinstance(result, Mapping) and "protocol" in result:
        return _json.dumps(result)
    return _json.dumps({"protocol": PROTOCOL_VERSION, "id": request["id"], "reply": result})


class Call:
    """One call of a role, shared by the thread running it and the supervisor waiting on it:
    which thread runs it, and whether the supervisor gave up on it. The lock keeps the two
    apart, so a ``RoleTimeout`` only ever reaches the call it was meant for."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.thread: Optional[int] = None
        self.abandoned = False


def run(call: Call, role: Callable[[Dict[str, Any]], Any], line: str) -> Optional[str]:
    """:func:`exchange` for ``call`` in this thread; ``None`` when the call was abandoned."""
    with call.lock:
        if call.abandoned:
            return None
        call.thread = threading.get_ident()
    reply: Optional[str] = None
    try:
        reply = exchange(role, line)
    finally:
        with call.lock:
            call.thread = None
            if call.abandoned:
                # A RoleTimeout raised too late must not reach this thread's next call.
                _set_async_exc(threading.get_ident(), None)
                reply = None
    return reply


def abandon(call: Call) -> None:
    """The supervisor gave up on ``call`` (its deadline passed): ``RoleTimeout`` is raised in
    the thread running it, if it still runs."""
    with call.lock:
        call.abandoned = True
        if call.thread is not None:
            _set_async_exc(call.thread, ctypes.py_object(RoleTimeout))


def _set_async_exc(thread: int, exc: Any) -> int:
    return ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread), exc)
