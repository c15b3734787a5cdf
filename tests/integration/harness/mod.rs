//! What every end-to-end test shares: the `disco` binary runner, its output as text, scene
//! files written to temporary directories, and the paths of the example and benchmark scenes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub mod chromium;
pub mod glb;
pub mod local_model;

/// Runs the `disco` binary with `args` and waits for it.
pub fn disco(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_disco"))
        .args(args)
        .output()
        .expect("disco runs")
}

/// Runs `disco generate SCENE -o OUT` followed by the `extra` arguments.
pub fn generate(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "generate",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    disco(&args)
}

/// Runs the `disco` binary with `args` and the extra environment variables `env`.
pub fn disco_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_disco"));
    c.args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("disco runs")
}

/// What the command wrote on stderr, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// What the command wrote on stdout, as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The example scenes (`examples/scenes`).
/// The layouts (`*.json`) in `dir`; none when it does not exist yet.
pub fn layouts_in(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .map(|d| {
            d.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect()
        })
        .unwrap_or_default()
}

/// The events of a JSONL trace file, one JSON value a line.
pub fn trace_events(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes")
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

/// Copies the named benchmark scenes (`bench/scenes/NAME.json`) into `dir/scenes` and returns it.
pub fn bench_scenes(dir: &Path, names: &[&str]) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("bench/scenes");
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    for n in names {
        std::fs::copy(
            root.join(format!("{n}.json")),
            scenes.join(format!("{n}.json")),
        )
        .unwrap();
    }
    scenes
}

/// Runs the default graph's benchmark over the scene folder `bench/SET` and returns each scene
/// with its layout, in file-name order.
pub fn bench_layouts(set: &str) -> Vec<(disco_layout::SceneSpec, disco_layout::Layout)> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bench")
        .join(set);
    let o = disco(&[
        "bench",
        "--scenes",
        scenes.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&scenes)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|path| {
            let scene = disco_layout::SceneSpec::load(path).unwrap();
            let file = out.join("layouts").join(format!("{}.json", scene.id));
            let layout = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
            (scene, layout)
        })
        .collect()
}

/// A small valid bedroom (a bed and a nightstand) that the tests break in one place at a time.
pub const GOOD: &str = r#"{"room_type": "bedroom", "room": {"width": 400, "depth": 350},
  "assets": [{"name": "bed-0", "category": "bed", "size": [160, 210, 100]},
             {"name": "nightstand-0", "category": "nightstand", "size": [50, 40, 55]}]}"#;
