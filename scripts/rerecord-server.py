#!/usr/bin/env python3
"""Re-record a replay with the same answers: each request gets the recorded response of the most
similar old request (by its messages' text), each old answer used once. Used by scripts/rerecord-replays; usage: rerecord-server.py PORT OLD_CACHE_DIR"""
import json, os, sys, difflib, threading
from http.server import ThreadingHTTPServer, BaseHTTPRequestHandler
old = []
for f in sorted(os.listdir(sys.argv[2])):
    d = json.load(open(os.path.join(sys.argv[2], f)))
    req = d["request"]
    if isinstance(req, str):
        req = json.loads(req)
    old.append((f, req, d["response"]))
used = set(); lock = threading.Lock()
def text(req):
    out = []
    for m in req.get("messages", []):
        c = m.get("content")
        if isinstance(c, str): out.append(c)
        else: out.extend(p.get("text", "") for p in c or [] if p.get("type") == "text")
    return "\n".join(out)
class H(BaseHTTPRequestHandler):
    def log_message(self, *a): pass
    def do_GET(self):
        body = json.dumps({"object": "list", "data": [{"id": "manual", "object": "model"}]}).encode()
        self.send_response(200); self.send_header("content-type", "application/json"); self.send_header("content-length", str(len(body))); self.end_headers(); self.wfile.write(body)
    def do_POST(self):
        n = int(self.headers.get("content-length", 0)); req = json.loads(self.rfile.read(n)); t = text(req)
        with lock:
            best = max((i for i in range(len(old)) if i not in used), key=lambda i: difflib.SequenceMatcher(None, text(old[i][1]), t, autojunk=False).ratio())
            used.add(best)
        sys.stderr.write(f"request -> {old[best][0]}\n")
        resp = old[best][2]
        body = (resp if isinstance(resp, str) else json.dumps(resp)).encode()
        self.send_response(200); self.send_header("content-type", "application/json"); self.send_header("content-length", str(len(body))); self.end_headers(); self.wfile.write(body)
ThreadingHTTPServer(("127.0.0.1", int(sys.argv[1])), H).serve_forever()
