//! Crash safety: a batch killed mid-run leaves no torn output, and a rerun finishes every scene
//! exactly once, cleaning what the killed run left behind.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime};

use disco_layout::{Layout, SceneSpec};

use crate::harness::layouts_in;

#[test]
fn a_batch_killed_mid_run_loses_nothing_and_tears_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    // 96 scenes: the benchmark's, twice under different ids.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("bench/scenes");
    let mut total = 0;
    for entry in std::fs::read_dir(&root).unwrap().flatten() {
        let mut scene = SceneSpec::load(&entry.path()).unwrap();
        for copy in 0..2 {
            let id = format!("{}-{copy}", scene.id);
            scene.id = id.clone();
            let text = serde_json::to_string(&scene).unwrap();
            std::fs::write(scenes.join(format!("{id}.json")), text).unwrap();
            total += 1;
        }
    }
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_disco"))
        .args([
            "batch",
            scenes.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--jobs", "4", "-q"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Kill it as soon as a few layouts are out.
    let t0 = Instant::now();
    while layouts_in(&out).len() < 3 && t0.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let written = layouts_in(&out);
    assert!(written.len() < total, "the batch ended before the kill");
    // Nothing torn: every file there is a whole layout.
    for p in &written {
        Layout::load(p).unwrap_or_else(|e| panic!("torn output {}: {e}", p.display()));
    }
    // Temporary files the kill left behind are cleaned by the next run once they are stale.
    for entry in std::fs::read_dir(&out).unwrap().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with(".disco-") {
            let old = SystemTime::now() - Duration::from_secs(3600);
            let f = std::fs::File::options()
                .write(true)
                .open(entry.path())
                .unwrap();
            f.set_modified(old).unwrap();
        }
    }
    let rerun = Command::new(env!("CARGO_BIN_EXE_disco"))
        .args([
            "batch",
            scenes.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "-q",
        ])
        .output()
        .unwrap();
    assert!(
        rerun.status.success(),
        "{}",
        String::from_utf8_lossy(&rerun.stderr)
    );
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.ends_with(".tmp")), "{names:?}");
    assert_eq!(layouts_in(&out).len(), total);
    for p in layouts_in(&out) {
        let layout = Layout::load(&p).unwrap();
        let scene = SceneSpec::load(&scenes.join(p.file_name().unwrap())).unwrap();
        assert_eq!(
            layout.objects.len() + layout.dropped.len(),
            scene.assets.len(),
            "{}",
            p.display()
        );
    }
}
