"""A designer that misbehaves on purpose, for the supervision tests: `misbehaving.py MODE`.

MODE is one of
  crash-on-start  exits before reading anything
  crash-mid-run   answers the first request, then exits on the second
  hang            never answers
  garbage         answers a line that is not JSON
  wrong-id        answers for another request
  good            answers every request with no poses (the runtime parks the group for the PRT)
  not-utf8        answers a reply whose bytes are not UTF-8 (a Latin-1 note)
  ghost           answers a pose for an object the scene does not have
"""

import json
import sys
import time

mode = sys.argv[1]
if mode == "crash-on-start":
    print("misbehaving: giving up before the first request", file=sys.stderr, flush=True)
    sys.exit(3)

for n, line in enumerate(sys.stdin):
    request = json.loads(line)
    reply = {"protocol": 1, "id": request["id"], "reply": {"objects": []}}
    if mode == "crash-mid-run" and n >= 1:
        print("misbehaving: crashing mid-run", file=sys.stderr, flush=True)
        sys.exit(4)
    if mode == "hang":
        time.sleep(3600)
    if mode == "garbage":
        sys.stdout.write("this is not a reply\n")
        sys.stdout.flush()
        continue
    if mode == "ghost":
        reply["reply"]["objects"] = [{"name": "unicorn-9", "position": [100, 100], "rotation": 0}]
    if mode == "wrong-id":
        reply["id"] = request["id"] + 1000
    if mode == "not-utf8":
        reply["notes"] = ["caf\u00e9"]
        line = json.dumps(reply, ensure_ascii=False) + "\n"
        sys.stdout.buffer.write(line.encode("latin-1"))
        sys.stdout.flush()
        continue
    sys.stdout.write(json.dumps(reply) + "\n")
    sys.stdout.flush()
