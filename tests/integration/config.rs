//! `disco config`: the built-in agent graphs, listed, written out, and run by name.

use crate::harness::{disco, examples, stderr, stdout};

#[test]
fn the_built_in_graphs_are_listed_and_written_out() {
    let o = disco(&["config", "list"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let list = stdout(&o);
    for name in ["default", "local-llm", "ollama", "openai", "vllm"] {
        assert!(
            list.lines()
                .any(|l| l.starts_with(name) && l.len() > name.len() + 20),
            "{name}: {list}"
        );
    }
    let o = disco(&["config", "show", "local-llm"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let shipped = include_str!("../../config/local-llm.toml");
    assert_eq!(stdout(&o), shipped);
    let o = disco(&["config", "show", "olama"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("did you mean ollama?"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_built_in_graph_runs_by_name_from_any_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("room.json");
    let scene = examples().join("bedroom.json");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_disco"))
        .current_dir(dir.path())
        .args([
            "generate",
            scene.to_str().unwrap(),
            "-o",
            "room.json",
            "--config",
            "default",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.is_file());
}
