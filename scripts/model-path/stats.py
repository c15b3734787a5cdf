#!/usr/bin/env python3
"""stats.py RUN_DIR [DISCO]: per room of a model-path run (folders RUN_DIR/m*, as run-room writes
them), what the protocol cost and what could surprise the model, as a Markdown table (and
RUN_DIR/stats.json):
- calls, prompt and completion tokens: the trace's model_call events;
- tool moves: poses a PRT reply lists (it lists what it moved, snaps of a few cm included);
  tools moves >= 5 cm or turned are counted apart, with how many of them the model was told of
  (`moved` trace events);
- model answers and answers settled by geometry (reasons starting "measured:");
- contradicted: the model's "yes" answers whose statement the final metric finds unmet;
- constraints met, Col, OOB, reach: `DISCO metrics` on the final layout."""
import json, math, subprocess, sys, os, glob
run = sys.argv[1]
repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = sys.argv[2] if len(sys.argv) > 2 else os.path.join(repo, "target/release/disco")
rows = []
for d in sorted(glob.glob(os.path.join(run, "m*"))):
    rid = os.path.basename(d)
    tr = [json.loads(l) for l in open(os.path.join(d, "trace.jsonl"))]
    calls = [e for e in tr if e["kind"] == "model_call"]
    by_purpose = {}
    for e in calls:
        p = e["detail"].get("purpose", "?").split(":")[0]
        by_purpose[p] = by_purpose.get(p, 0) + 1
    pt = sum(e["detail"].get("prompt_tokens", 0) for e in calls)
    ct = sum(e["detail"].get("completion_tokens", 0) for e in calls)
    # Tool moves: every pose a PRT reply lists (it lists only what it moved).
    prt_moves = sum(len(e["detail"].get("poses", [])) for e in tr if e["role"] == "prt" and e["kind"] == "reply")
    reported = sum(1 for e in tr if e["kind"] == "moved")
    # Moves of 5 cm or more, or turns, against each object's last pose from a reply.
    pose, big = {}, 0
    for e in tr:
        if e["kind"] != "reply":
            continue
        for p in e.get("detail", {}).get("poses") or []:
            n = p["name"]
            if e["role"] == "prt" and n in pose:
                x, y, r = pose[n]
                dist = math.hypot(p["position"][0] - x, p["position"][1] - y)
                turn = abs((p["rotation"] - r + 180) % 360 - 180)
                big += dist >= 5 or turn > 1
            pose[n] = (p["position"][0], p["position"][1], p["rotation"])
    m = json.loads(subprocess.run([BIN, "metrics", os.path.join(repo, "bench/model-path", f"{rid}.json"), os.path.join(d, "layout.json"), "--json"], capture_output=True, text=True).stdout)
    unmet = set(m["unmet"])
    # Model answers (not settled by the geometry): yes whose statement is unmet at the end.
    model_answers = 0; contradicted = []; settled = 0
    qtext = {}
    for e in tr:
        if e["role"] == "evaluator" and e["kind"] == "request":
            qtext = {q["id"]: q["text"] for q in e["detail"].get("questions", [])}
        if e["role"] == "evaluator" and e["kind"] == "reply":
            for a in e["detail"].get("answers", []):
                if a.get("reason", "").startswith("measured:"):
                    settled += 1; continue
                model_answers += 1
                t = qtext.get(a["id"], "")
                stmt = t.removeprefix("Is it true that ").removesuffix("?")
                if a["yes"] and stmt in unmet:
                    contradicted.append(stmt)
    notes = json.load(open(os.path.join(d, "layout.json")))["stats"].get("notes", [])
    rows.append(dict(room=rid, calls=len(calls), by_purpose=by_purpose, prompt_tokens=pt, completion_tokens=ct,
                     prt_moves=prt_moves, big_moves=big, reported=reported, model_answers=model_answers, settled=settled,
                     contradicted=contradicted, constraint_pct=round(m["constraint_pct"], 1), col=m["collision_pct"], oob=m["oob_pct"],
                     reach=m["reach_pct"], placed=m["placed"], assets=m["assets"], prompt_requests=m.get("prompt_requests"), unmet=sorted(unmet),
                     infeasible_notes=[n for n in notes if "infeasible" in n]))
json.dump(rows, open(os.path.join(run, "stats.json"), "w"), indent=1)
print("| room | calls | prompt tok | compl tok | tool moves | of them >= 5 cm or turned | reported | model answers | settled by geometry | contradicted | constraints met | Col | OOB | reach |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
tot = {k: 0 for k in ["calls", "prompt_tokens", "completion_tokens", "prt_moves", "big_moves", "reported", "model_answers", "settled"]}; tc = 0
for r in rows:
    for k in tot: tot[k] += r[k]
    tc += len(r["contradicted"])
    print(f"| {r['room']} | {r['calls']} | {r['prompt_tokens']} | {r['completion_tokens']} | {r['prt_moves']} | {r['big_moves']} | {r['reported']} | {r['model_answers']} | {r['settled']} | {len(r['contradicted'])} | {r['constraint_pct']}% | {r['col']} | {r['oob']} | {r['reach']} |")
print(f"| **total** | {tot['calls']} | {tot['prompt_tokens']} | {tot['completion_tokens']} | {tot['prt_moves']} | {tot['big_moves']} | {tot['reported']} | {tot['model_answers']} | {tot['settled']} | {tc} | | | | |")
