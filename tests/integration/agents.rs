//! Agents outside the binary (`impl = "process"`) through `disco generate`: the Python examples of
//! `examples/agents/` in a graph, and scripted misbehaving agents that must not break a run (every
//! asset placed or reported, the right trace events, no process left behind).

use std::path::Path;

use serde_json::Value;

use crate::harness::{examples, stderr, trace_events, write};

/// Runs `disco generate` on the bedroom with graph `config`; returns the layout and the trace.
fn generate_with(dir: &Path, config: &str) -> (Value, Vec<Value>) {
    let out = dir.join("room.json");
    let trace = dir.join("trace.jsonl");
    let report = dir.join("report.html");
    let scene = examples().join("bedroom.json");
    let o = crate::harness::generate(
        &scene,
        &out,
        &[
            "--config",
            config,
            "--trace",
            trace.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let layout = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    (layout, trace_events(&trace))
}

/// Every asset of the bedroom is placed or dropped, once.
fn assert_complete(layout: &Value) {
    let mut names: Vec<&str> = ["objects", "dropped"]
        .iter()
        .flat_map(|k| layout[*k].as_array().unwrap())
        .map(|o| o["name"].as_str().unwrap())
        .collect();
    names.sort_unstable();
    assert_eq!(
        names,
        [
            "armchair-0",
            "bed-0",
            "floor lamp-0",
            "nightstand-0",
            "nightstand-1",
            "rug-0",
            "wardrobe-0"
        ]
    );
}

fn has(events: &[Value], role: &str, kind: &str, implementation: &str) -> bool {
    events
        .iter()
        .any(|e| e["role"] == role && e["kind"] == kind && e["implementation"] == implementation)
}

/// Processes whose command line mentions `marker`, still in the process table.
fn processes_mentioning(marker: &str) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| {
            let cmdline = std::fs::read(e.path().join("cmdline")).ok()?;
            let text = String::from_utf8_lossy(&cmdline).replace('\0', " ");
            text.contains(marker)
                .then(|| format!("{}: {text}", e.file_name().to_string_lossy()))
        })
        .collect()
}

#[test]
fn python_agents_design_and_patch_a_room_and_show_in_the_trace_and_report() {
    let dir = tempfile::tempdir().unwrap();
    let (layout, events) = generate_with(dir.path(), "config/experiments/python-agents.toml");
    assert_complete(&layout);
    assert!(has(&events, "designer", "reply", "process"));
    assert!(has(&events, "wall_hugger", "reply", "process"));
    assert!(
        layout["stats"]["fallbacks"].is_null(),
        "{}",
        layout["stats"]
    );
    let report = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(report.contains("wall_hugger"));
}

/// A graph whose designer is `misbehaving.py MODE` (copied into `dir`, so its path marks the
/// processes of this test), with the rules designer as its fallback.
fn misbehaving_graph(dir: &Path, mode: &str) -> (String, String) {
    let script = dir.join("misbehaving.py");
    let source =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/integration/agents/misbehaving.py");
    std::fs::copy(source, &script).unwrap();
    let script = script.to_string_lossy().into_owned();
    let graph = format!(
        "[run]\nbackoff_ms = 1\n\n[pipeline]\nround = [\"evaluate\", \"srt\", \"prt\"]\n\n\
         [agents.planner]\nimpl = \"rules\"\n\n\
         [agents.designer]\nimpl = \"process\"\ncommand = [\"python3\", {script:?}, \"{mode}\"]\n\
         deadline_s = 2\nretries = 1\nfallback = \"rules\"\n\n\
         [agents.evaluator]\nimpl = \"rules\"\n[agents.srt]\nimpl = \"rules\"\n[agents.prt]\nimpl = \"grid\"\n"
    );
    (write(dir, "graph.toml", &graph), script)
}

#[test]
fn a_misbehaving_agent_cannot_break_a_run() {
    let cases = [
        (
            "crash-on-start",
            "restart",
            "giving up before the first request",
        ),
        ("crash-mid-run", "restart", "crashing mid-run"),
        ("hang", "timeout", "deadline"),
        ("garbage", "error", "its reply is not JSON"),
        ("wrong-id", "error", "where request"),
    ];
    for (mode, kind, says) in cases {
        let dir = tempfile::tempdir().unwrap();
        let (config, script) = misbehaving_graph(dir.path(), mode);
        let (layout, events) = generate_with(dir.path(), &config);
        assert_complete(&layout);
        assert!(
            events
                .iter()
                .any(|e| e["role"] == "designer" && e["kind"] == kind),
            "{mode}: no {kind} event"
        );
        let said = events
            .iter()
            .filter(|e| e["role"] == "designer")
            .map(|e| e["detail"].to_string())
            .collect::<String>();
        assert!(said.contains(says), "{mode}: {said}");
        if mode != "crash-mid-run" {
            assert!(
                events
                    .iter()
                    .any(|e| e["role"] == "designer" && e["kind"] == "fallback"),
                "{mode}: no fallback"
            );
        }
        let left = processes_mentioning(&script);
        assert!(left.is_empty(), "{mode}: processes left behind: {left:?}");
    }
}
