//! `disco config`: the built-in agent graphs, listed, written out, and run by name.

use crate::harness::{disco, examples, generate, stderr, stdout, write};

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

/// A model section whose key variable is unset is an input error (exit 1, as the README's table
/// says), for `judge` as for `generate`, naming the graph file and the model section.
#[test]
fn a_missing_api_key_is_an_input_error_for_judge_and_generate() {
    let dir = tempfile::tempdir().unwrap();
    let scene = examples().join("bedroom.json");
    let layout = dir.path().join("bedroom.layout.json");
    let o = generate(&scene, &layout, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let preset = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("config/openai.toml");
    let text = std::fs::read_to_string(preset).unwrap();
    let text = text.replace("OPENAI_API_KEY", "DISCO_TEST_KEY_NOBODY_SETS_7F3");
    let graph = write(
        dir.path(),
        "keyed.toml",
        &format!("{text}\n[judge]\nmodel = \"main\"\n"),
    );
    for args in [
        vec!["judge", scene.to_str().unwrap(), layout.to_str().unwrap()],
        vec![
            "generate",
            scene.to_str().unwrap(),
            "-o",
            layout.to_str().unwrap(),
        ],
    ] {
        let mut args = args;
        args.extend(["--config", graph.as_str()]);
        let o = disco(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("keyed.toml"), "{err}");
        assert!(err.contains("DISCO_TEST_KEY_NOBODY_SETS_7F3"), "{err}");
        assert_eq!(err.matches("models.main").count(), 1, "{err}");
    }
}
