//! Every input kept, every number bounded, every snag of a first hour gone: no flag that writes
//! may replace an input of its command (or another output), by path or through a link; absurd
//! numbers are refused where they are read; a closed pipe (stdout or stderr) is a quiet exit; a
//! mistyped `--config` or `--set` says what was meant; a draft layout can be drawn.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::harness::{GOOD, disco, examples, stderr, stdout, write};

/// A scene and its layout, made once, in a fresh folder.
struct Files {
    dir: tempfile::TempDir,
    scene: PathBuf,
    layout: PathBuf,
}

fn files() -> Files {
    let dir = tempfile::tempdir().unwrap();
    let scene = PathBuf::from(write(dir.path(), "scene.json", GOOD));
    let layout = dir.path().join("layout.json");
    let o = disco(&[
        "-q",
        "generate",
        scene.to_str().unwrap(),
        "-o",
        layout.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    Files { dir, scene, layout }
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Runs `args`, expects exit 1 naming `flag` and `other`, and `kept` unchanged.
fn refused(args: &[&str], flag: &str, other: &str, kept: &[&Path]) {
    let before: Vec<Vec<u8>> = kept.iter().map(|p| std::fs::read(p).unwrap()).collect();
    let o = disco(args);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
    assert!(
        e.contains(&format!("{flag}: is the same file as")) && e.contains(other),
        "{args:?}: {e}"
    );
    for (p, bytes) in kept.iter().zip(before) {
        assert_eq!(std::fs::read(p).unwrap(), bytes, "{} changed", p.display());
    }
}

#[test]
fn no_output_flag_replaces_an_input() {
    let f = files();
    let (scene, layout) = (f.scene.as_path(), f.layout.as_path());
    let out = f.dir.path().join("out.json");
    let kept = [scene, layout];
    refused(
        &["refine", s(scene), s(layout), "-o", s(scene)],
        "-o",
        "SCENE",
        &kept,
    );
    refused(
        &["refine", s(scene), s(layout), "-o", s(layout)],
        "-o",
        "LAYOUT",
        &kept,
    );
    refused(
        &[
            "refine",
            s(scene),
            s(layout),
            "-o",
            s(&out),
            "--render",
            s(scene),
        ],
        "--render",
        "SCENE",
        &kept,
    );
    refused(
        &[
            "refine",
            s(scene),
            s(layout),
            "-o",
            s(&out),
            "--render",
            s(&out),
        ],
        "--render",
        "-o",
        &kept,
    );
    refused(
        &["render", s(layout), "-o", s(layout)],
        "-o",
        "LAYOUT",
        &kept,
    );
    refused(
        &["export", s(layout), "-o", s(layout)],
        "-o",
        "LAYOUT",
        &kept,
    );
    refused(
        &["export", s(layout), "--scene", s(scene), "-o", s(scene)],
        "-o",
        "--scene",
        &kept,
    );
    for flag in ["--glb", "--trace", "--report"] {
        refused(
            &["generate", s(scene), "-o", s(&out), flag, s(scene)],
            flag,
            "SCENE",
            &kept,
        );
    }
    // Two outputs of one command on one file: the layout would be replaced by the GLB.
    refused(
        &["generate", s(scene), "-o", s(&out), "--glb", s(&out)],
        "--glb",
        "-o",
        &kept,
    );
    assert!(!out.exists(), "nothing is written before the refusal");
    let o = disco(&[
        "batch",
        s(scene),
        "--out",
        s(f.dir.path()),
        "--trace",
        s(scene),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--trace: is the same file as the input SCENES"));
}

#[cfg(unix)]
#[test]
fn an_input_reached_through_a_link_is_kept_too() {
    let f = files();
    let (scene, layout) = (f.scene.as_path(), f.layout.as_path());
    let d = f.dir.path();
    let symlink = d.join("symlink.json");
    std::os::unix::fs::symlink(scene, &symlink).unwrap();
    let hard = d.join("hard.json");
    std::fs::hard_link(layout, &hard).unwrap();
    std::fs::create_dir(d.join("sub")).unwrap();
    let dotted = d.join("sub/../scene.json");
    let kept = [scene, layout];
    refused(
        &["generate", s(scene), "-o", s(&symlink)],
        "-o",
        "SCENE",
        &kept,
    );
    refused(
        &["generate", s(scene), "-o", s(&dotted)],
        "-o",
        "SCENE",
        &kept,
    );
    refused(
        &["render", s(layout), "-o", s(&hard)],
        "-o",
        "LAYOUT",
        &kept,
    );
    refused(
        &["export", s(&hard), "-o", s(layout)],
        "-o",
        "LAYOUT",
        &kept,
    );
}

/// Runs `args` with stdout a pipe whose reader is gone before anything is printed.
fn into_closed_pipe(args: &[&str]) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_disco"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

#[test]
fn a_closed_pipe_is_a_quiet_exit() {
    let f = files();
    let out = f.dir.path().join("out");
    let runs: [Vec<&str>; 4] = [
        vec!["generate", s(&f.scene), "-o", s(&f.layout)],
        vec!["batch", s(&f.scene), "--out", s(&out)],
        vec!["metrics", s(&f.scene), s(&f.layout), "--json"],
        vec!["config", "show", "local-llm"],
    ];
    for args in runs {
        let o = into_closed_pipe(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {e}");
        assert!(!e.contains("panicked"), "{args:?}: {e}");
    }
    assert_eq!(
        std::fs::read_dir(&out).unwrap().count(),
        1,
        "batch wrote its layout"
    );
}

/// Runs `args` with stderr a pipe whose reader is gone before anything is written there.
fn with_stderr_closed(args: &[&str]) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_disco"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    child.wait_with_output().unwrap()
}

#[test]
fn a_closed_stderr_is_a_quiet_exit_with_the_commands_own_code() {
    let f = files();
    let d = f.dir.path();
    let bad = write(d, "bad.json", "{\"id\": 3}");
    let out = d.join("out.json");
    let answers = d.join("answers");
    let many = d.join("many");
    let runs: [(Vec<&str>, i32); 3] = [
        // The error message itself (exit 1).
        (vec!["validate", &bad], 1),
        // A warning (`--cache` with a graph that calls no model), then success.
        (
            vec![
                "generate",
                s(&f.scene),
                "-o",
                s(&out),
                "--cache",
                s(&answers),
            ],
            0,
        ),
        // A failed scene of a batch, told on stderr as it happens (exit 4).
        (vec!["batch", s(&f.scene), &bad, "--out", s(&many)], 4),
    ];
    for (args, code) in runs {
        let o = with_stderr_closed(&args);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stdout(&o));
    }
    assert!(out.is_file(), "generate wrote its layout");
}

#[test]
fn absurd_numbers_are_refused_not_a_panic() {
    let f = files();
    let out = f.dir.path().join("out.json");
    for set in [
        "agents.designer.deadline_s=1e300",
        "run.scene_deadline_s=1e300",
        "run.restart_window_s=-1",
    ] {
        let o = disco(&["generate", s(&f.scene), "-o", s(&out), "--set", set]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{set}: {e}");
        assert!(e.contains(&format!("--set {set}: ")), "{set}: {e}");
        assert!(e.contains("86400 seconds (1 day)"), "{set}: {e}");
        assert!(!e.contains("panicked"), "{set}: {e}");
    }
}

#[test]
fn a_mistyped_config_or_set_says_what_was_meant() {
    let f = files();
    let out = f.dir.path().join("out.json");
    let o = disco(&[
        "generate",
        s(&f.scene),
        "-o",
        s(&out),
        "--config",
        "defualt",
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("defualt: --config: no such file or preset; did you mean `default`? (see `disco config list`)"),
        "{e}"
    );
    let o = disco(&[
        "generate",
        s(&f.scene),
        "-o",
        s(&out),
        "--set",
        "run.max_rounds",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("expected KEY=VALUE"), "{}", stderr(&o));
}

#[test]
fn the_readme_broken_layout_is_drawn_before_it_is_refined() {
    let dir = tempfile::tempdir().unwrap();
    let before = dir.path().join("before.png");
    let broken = examples().join("bedroom-broken.layout.json");
    let scene = examples().join("bedroom.json");
    let o = disco(&["render", s(&broken), "--scene", s(&scene), "-o", s(&before)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(&std::fs::read(&before).unwrap()[1..4], b"PNG");
    // Without the scene the draft has no room: the error says to give it.
    let o = disco(&["render", s(&broken), "-o", s(&before)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("add --scene SCENE.json"),
        "{}",
        stderr(&o)
    );
    // A complete layout whose objects lack `category` takes it from their names.
    let layout = write(
        dir.path(),
        "no-category.json",
        r#"{"id": "x", "room": {"width": 400, "depth": 350}, "objects": [{"name": "floor lamp-0", "size": [35, 35, 160], "position": [100, 100], "rotation": 0}]}"#,
    );
    let png = dir.path().join("x.png");
    let o = disco(&["render", &layout, "-o", s(&png)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(png.is_file());
}

#[test]
fn scripts_test_says_what_it_installs_and_times_each_part() {
    let script =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/test"))
            .unwrap();
    let notice = script.find("system-wide").expect("an install notice");
    let first_install = script.find("scripts/local-llm install").unwrap();
    assert!(
        notice < first_install,
        "the notice comes before any install"
    );
    for apt in ["chromium", "slurm-wlm"] {
        assert!(script[..first_install].contains(apt), "{apt} is announced");
    }
    assert!(
        script.contains("$((SECONDS - part_start)) s"),
        "per-part times"
    );
    let parts = script.matches("\npart \"").count();
    assert!(parts >= 9, "{parts} parts");
    assert_eq!(
        script.matches("\necho \"== ").count(),
        1,
        "every part but the closing total goes through `part`, which times it"
    );
}
