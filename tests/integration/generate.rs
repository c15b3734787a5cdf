//! `disco generate` offline: a furnished room with its pictures and trace; bad agent graphs refused
//! with the file, the line and the key.

use serde_json::Value;

use crate::harness::{disco, examples, generate, stderr, stdout, write};

#[test]
fn generate_furnishes_a_room_offline_with_its_picture_and_trace() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("room.json");
    let trace = dir.path().join("trace.jsonl");
    let renders = dir.path().join("renders");
    let scene = examples().join("living-room.json");
    let o = generate(
        &scene,
        &out,
        &[
            "--renders",
            renders.to_str().unwrap(),
            "--trace",
            trace.to_str().unwrap(),
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let m: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(m["collision_pct"], 0.0);
    assert_eq!(m["oob_pct"], 0.0);
    assert_eq!(m["placed"], 10);
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(layout["objects"].as_array().unwrap().len(), 10);
    assert!(!layout["plan"]["groups"].as_array().unwrap().is_empty());
    assert!(renders.join("living-room-01.png").exists());
    // Every step drawn, and the sequence on one sheet.
    let steps: Vec<String> = std::fs::read_dir(renders.join("living-room-01"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        steps.iter().any(|s| s == "01-group1-design.png"),
        "{steps:?}"
    );
    assert!(
        steps.iter().any(|s| s.ends_with("-final-prt.png")),
        "{steps:?}"
    );
    let groups = layout["plan"]["groups"].as_array().unwrap().len();
    assert_eq!(
        steps.len(),
        groups + 1,
        "a design per group and the final PRT: {steps:?}"
    );
    assert!(renders.join("living-room-01-steps.png").exists());
    let lines: Vec<Value> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert!(
        lines
            .iter()
            .any(|e| e["role"] == "planner" && e["kind"] == "reply")
    );
    assert!(
        lines
            .iter()
            .any(|e| e["role"] == "designer" && e["kind"] == "request")
    );
}

#[test]
fn generate_refuses_a_bad_graph_with_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "graph.toml",
        "[pipeline]\nround = []\n\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rulez\"\n[agents.prt]\nimpl = \"grid\"\n",
    );
    let scene = examples().join("bedroom.json");
    let out = dir.path().join("x.json");
    let o = generate(&scene, &out, &["--config", &cfg]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains(
            "graph.toml: line 7, agents.designer.impl: unknown designer implementation \"rulez\"; known: grid-search, http, noisy, process, rules, vlm; did you mean rules?"
        ),
        "{}",
        stderr(&o)
    );
    let o = generate(&scene, &out, &["--set", "run.max_rounds=lots"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("run.max_rounds"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn a_mistake_in_a_set_is_reported_at_the_set_with_the_nearest_name() {
    let dir = tempfile::tempdir().unwrap();
    let scene = examples().join("bedroom.json");
    let out = dir.path().join("x.json");
    let run = |set: &str| {
        let o = generate(&scene, &out, &["--set", set]);
        assert_eq!(o.status.code(), Some(1), "{set}: {}", stderr(&o));
        stderr(&o)
    };
    let e = run("run.max_roundz=2");
    assert!(
        e.contains("error: --set run.max_roundz=2: run.max_roundz: unknown field"),
        "{e}"
    );
    assert!(e.contains("did you mean max_rounds?"), "{e}");
    assert!(!e.contains("default.toml"), "{e}");
    let e = run("agents.desinger.impl=noisy");
    assert!(e.contains("--set agents.desinger.impl=noisy: "), "{e}");
    assert!(e.contains("did you mean designer?"), "{e}");
    let e = run("agents.designer.options.bogus=1");
    assert!(
        e.contains("--set agents.designer.options.bogus=1: agents.designer.options.bogus: unknown option \"bogus\""),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn a_cache_with_a_graph_that_calls_no_model_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let scene = examples().join("bedroom.json");
    let out = dir.path().join("x.json");
    let cache = dir.path().join("cache");
    let o = generate(&scene, &out, &["--cache", cache.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(&format!(
            "warning: --cache {}: no agent of this graph calls a model",
            cache.display()
        )),
        "{}",
        stderr(&o)
    );
}

#[test]
fn generate_writes_into_a_folder_that_does_not_exist_yet() {
    let dir = tempfile::tempdir().unwrap();
    let scene = examples().join("bedroom.json");
    let out = dir.path().join("new/room.json");
    let glb = dir.path().join("other/room.glb");
    let o = generate(&scene, &out, &["--glb", glb.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.is_file() && glb.is_file());
}

#[test]
fn verbose_logs_the_stages_and_a_pipe_gets_no_progress_line() {
    let dir = tempfile::tempdir().unwrap();
    let scene = examples().join("bedroom.json");
    let out = dir.path().join("x.json");
    let args = [
        "generate",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    let o = disco(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "", "stderr is not a terminal: no progress line");
    let o = disco(&[&["-v"], &args[..]].concat());
    let log = stderr(&o);
    assert!(
        log.contains("INFO") && log.contains("stage {\"group\":"),
        "{log}"
    );
    assert!(log.contains("\"stage\":\"final prt\""), "{log}");
    assert!(!log.contains("DEBUG"), "{log}");
}

/// The README's example rooms are what a new user sees first: each one, furnished offline, meets
/// every constraint of its plan (facings included), leaves every object reachable and meets every
/// placement request its prompt states.
#[test]
fn the_example_rooms_meet_their_plan_their_prompt_and_reach() {
    let dir = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(examples()).unwrap() {
        let scene = entry.unwrap().path();
        let name = scene.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".layout.json") {
            continue;
        }
        let out = dir.path().join(&name);
        let o = generate(&scene, &out, &["--json"]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let m: Value = serde_json::from_str(&stdout(&o)).unwrap();
        assert_eq!(m["reach_pct"], 100.0, "{name}: reach in {m:#}");
        let unmet: Vec<&str> = m["unmet"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(Value::as_str)
            .collect();
        let known: Vec<&str> = KNOWN_MISSES
            .iter()
            .filter(|(scene, _)| *scene == name)
            .map(|(_, miss)| *miss)
            .collect();
        let new: Vec<&&str> = unmet.iter().filter(|u| !known.contains(u)).collect();
        assert!(new.is_empty(), "{name}: unmet {new:?} in {m:#}");
        let requests = m["prompt_requests"].as_array().unwrap();
        let missed: Vec<&Value> = requests
            .iter()
            .filter(|r| r["met"] != true)
            .filter(|r| {
                !known.iter().any(|k| {
                    r["request"]
                        .as_str()
                        .is_some_and(|q| k.contains(q) || q.contains(k))
                })
            })
            .collect();
        assert!(missed.is_empty(), "{name}: missed {missed:?}");
    }
}

/// What an example room is known to miss, and why, as `(file, unmet constraint)`: a miss not
/// listed here fails the test, and one listed here that comes back met should be taken off.
///
/// The L-shaped studio's bed now stands in the sleeping nook its prompt asks for; the nook is
/// then too short for the TV across from the sofa, and the designer does not yet turn the
/// living part round (the sofa on a side wall, the TV across) to make room.
const KNOWN_MISSES: [(&str, &str); 4] = [
    ("l-shaped-studio.json", "sofa-0 faces tv stand-0"),
    ("l-shaped-studio.json", "tv stand-0 is opposite sofa-0"),
    ("l-shaped-studio.json", "tv stand-0 faces sofa-0"),
    ("l-shaped-studio.json", "sofa-0 facing tv stand-0"),
];
