"""Python roles in the same process, used from an agent graph under the runtime's supervision."""

import time

import pytest

import disco_layout as dl


@pytest.fixture
def role():
    """Registers Python roles for one test and removes them after it."""
    registered = []

    def register(kind, name, implementation):
        dl.register_role(kind, name, implementation)
        registered.append((kind, name))

    yield register
    for kind, name in registered:
        assert dl.unregister_role(kind, name)


def centre_poses(request):
    """A designer's reply: every object of the group at the room's centre (the PRT spreads
    them)."""
    body = request["request"]
    room = body["scene"]["room"]
    return {
        "objects": [
            {"name": n, "position": [room["width"] / 2, room["depth"] / 2], "rotation": 90}
            for n in body["group"]
        ]
    }


def test_a_python_designer_speaks_the_protocol_and_its_poses_are_used(bedroom, role):
    requests = []

    def designer(request):
        requests.append(request)
        return centre_poses(request)

    role("designer", "centre", designer)
    assert ("designer", "centre") in dl.registered_roles()
    layout = dl.generate(bedroom, sets=["agents.designer.impl=centre"])
    assert "fallbacks" not in layout["stats"]
    first = requests[0]
    assert (first["protocol"], first["role"], first["agent"], first["id"]) == (1, "designer", "designer", 1)
    assert {"scene", "plan", "group", "placed"} <= set(first["request"])
    assert [r["request"]["group"] for r in requests] == layout["plan"]["groups"]
    positions = {tuple(o["position"]) for o in layout["objects"]}
    assert len(positions) == len(layout["objects"]), "the PRT spread the piled-up objects"
    m = dl.metrics(bedroom, layout)
    assert (m["collision_pct"], m["oob_pct"]) == (0.0, 0.0)


def test_a_class_role_is_made_per_scene_with_the_agents_options(bedroom, role):
    made = []

    class Turned:
        def __init__(self, rotation):
            made.append(rotation)
            self.rotation = rotation

        def __call__(self, request):
            reply = centre_poses(request)
            for pose in reply["objects"]:
                pose["rotation"] = self.rotation
            return {"protocol": 1, "id": request["id"], "reply": reply, "notes": ["turned"]}

    role("designer", "turned", Turned)
    sets = ["agents.designer.impl=turned", "agents.designer.options.rotation=180"]
    layout = dl.generate(bedroom, sets=sets)
    assert made and set(made) == {180}
    assert "designer: turned" in layout["stats"]["notes"], "the reply's notes are kept"
    with pytest.raises(dl.ValidationError, match="unexpected keyword argument"):
        dl.generate(bedroom, sets=sets + ["agents.designer.options.colour=1"])


def test_a_python_role_past_its_deadline_is_cut_off_and_the_fallback_finishes(bedroom, role):
    calls, interrupted = [], []

    def stuck(request):
        calls.append(request["id"])
        try:
            while True:  # pure Python: the RoleTimeout gets in
                pass
        except dl.RoleTimeout:
            interrupted.append(request["id"])
            raise

    role("designer", "stuck", stuck)
    t0 = time.monotonic()
    layout = dl.generate(bedroom, sets=[
        "agents.designer.impl=stuck", "agents.designer.deadline_s=0.3",
        "agents.designer.retries=1", "agents.designer.fallback=rules",
    ])
    elapsed = time.monotonic() - t0
    assert any("stuck -> rules" in f for f in layout["stats"]["fallbacks"]), layout["stats"]
    assert len(calls) >= 2, "the first try and the retry"
    assert elapsed < 15, f"{elapsed:.1f} s: the deadline did not cut the calls off"
    for _ in range(40):
        if len(interrupted) == len(calls):
            break
        time.sleep(0.05)
    assert interrupted == calls, "every abandoned call was stopped inside Python"
    names = {o["name"] for o in layout["objects"]} | {d["name"] for d in layout["dropped"]}
    assert len(names) == 7 and dl.metrics(bedroom, layout)["collision_pct"] == 0.0


def test_a_sleeping_role_is_abandoned_and_a_raising_one_falls_back(bedroom, role):
    def sleepy(request):
        time.sleep(2)
        return centre_poses(request)

    def failing(request):
        raise RuntimeError("no idea where the bed goes")

    role("designer", "sleepy", sleepy)
    role("designer", "failing", failing)
    t0 = time.monotonic()
    trace = dl.Trace(snapshots=False)
    layout = dl.generate(bedroom, trace=trace, sets=[
        "agents.designer.impl=sleepy", "agents.designer.deadline_s=0.2",
        "agents.designer.retries=0", "agents.designer.fallback=rules",
    ])
    assert time.monotonic() - t0 < 2, "the run did not wait for the sleeping role"
    assert any("sleepy -> rules" in f for f in layout["stats"]["fallbacks"])
    assert "timeout" in {e["kind"] for e in trace.events()}

    trace = dl.Trace(snapshots=False)
    layout = dl.generate(bedroom, trace=trace, sets=[
        "agents.designer.impl=failing", "agents.designer.retries=1",
        "agents.designer.fallback=rules",
    ])
    assert any("failing -> rules" in f for f in layout["stats"]["fallbacks"])
    errors = [e for e in trace.events() if e["kind"] == "error"]
    assert any("RuntimeError: no idea where the bed goes" in str(e["detail"]) for e in errors)


def test_a_scene_past_its_deadline_raises_with_the_finished_layout(bedroom, role):
    def slow(request):
        time.sleep(0.6)
        return centre_poses(request)

    role("designer", "slow", slow)
    sets = ["agents.designer.impl=slow", "run.scene_deadline_s=1", "agents.designer.deadline_s=5"]
    with pytest.raises(dl.DeadlineError) as e:
        dl.generate(bedroom, sets=sets)
    assert e.value.exit_code == 5 and e.value.layout["stats"]["deadline_missed"] is True
    placed = len(e.value.layout["objects"]) + len(e.value.layout["dropped"])
    assert placed == 7, "the fallbacks finished the room"
    assert dl.generate(bedroom, sets=sets, strict=False)["stats"]["deadline_missed"]


def test_unknown_roles_and_empty_names_are_refused():
    with pytest.raises(ValueError, match="unknown role"):
        dl.register_role("decorator", "x", centre_poses)
    with pytest.raises(ValueError, match="must not be empty"):
        dl.register_role("designer", " ", centre_poses)
    assert dl.unregister_role("designer", "never-registered") is False


def test_a_lying_python_prt_is_refused_and_the_layout_stays_valid(bedroom, role):
    def liar(request):
        body = request["request"]
        poses = [{"name": o["name"], "position": [-500, -500], "rotation": 0}
                 for o in body["layout"]["objects"]]
        return {"objects": poses, "dropped": []}

    role("prt", "liar", liar)
    trace = dl.Trace(snapshots=False)
    layout = dl.generate(bedroom, trace=trace, sets=["agents.prt.impl=liar", "agents.prt.retries=0"])
    refused = [e for e in trace.events() if e["kind"] == "error" and "refused" in str(e["detail"])]
    assert refused, "the lie was refused by the reply checks"
    m = dl.metrics(bedroom, layout)
    assert (m["collision_pct"], m["oob_pct"]) == (0.0, 0.0)
    assert len(layout["objects"]) + len(layout["dropped"]) == 7
