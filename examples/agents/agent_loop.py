"""The loop every example agent shares: read one JSON request per line on stdin, answer with one
JSON reply per line on stdout, echoing the protocol version and the request's id.

Standard library only. Logs go to stderr (the runtime forwards them to its log); stdout carries
replies and nothing else. See docs/protocol/README.md for the messages of every role.
"""

import json
import sys

PROTOCOL = 1


def log(*words):
    """Writes a line to stderr, which the runtime forwards to its log."""
    print(*words, file=sys.stderr, flush=True)


def serve(handle):
    """Answers every request on stdin with `handle(request_body, envelope)`, until stdin closes.

    `handle` returns the reply body; an exception becomes an `error` reply, so the runtime retries
    and then swaps in the agent's fallback.
    """
    for line in sys.stdin:
        if not line.strip():
            continue
        envelope = json.loads(line)
        reply = {"protocol": PROTOCOL, "id": envelope["id"]}
        try:
            reply["reply"] = handle(envelope["request"], envelope)
        except Exception as e:  # the agent's own failure, reported in words
            reply["error"] = f"{type(e).__name__}: {e}"
        sys.stdout.write(json.dumps(reply) + "\n")
        sys.stdout.flush()
