//! `--shard I/N` and `disco bench merge`: shards cover every scene once, and their merge is the
//! table one process writes (equal but for wall times, which measure each shard's process).

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::harness::{bench_scenes, disco, stderr, stdout};

const SCENES: &[&str] = &[
    "bathroom-01",
    "bedroom-02",
    "classroom-03",
    "dining-room-01",
    "kitchen-04",
    "living-room-05",
];

fn run(args: &[&str]) -> std::process::Output {
    let o = disco(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o
}

fn bench(scenes: &Path, out: &Path, shard: Option<&str>) {
    let mut args = vec![
        "bench",
        "--scenes",
        scenes.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ];
    if let Some(s) = shard {
        args.extend(["--shard", s]);
    }
    run(&args);
}

/// A JSON file with its wall times (`wall_ms`, `seconds`) taken out.
fn timeless(path: &Path) -> Value {
    fn strip(v: Value) -> Value {
        match v {
            Value::Object(m) => Value::Object(
                m.into_iter()
                    .filter(|(k, _)| k != "wall_ms" && k != "seconds")
                    .map(|(k, v)| (k, strip(v)))
                    .collect(),
            ),
            Value::Array(a) => Value::Array(a.into_iter().map(strip).collect()),
            v => v,
        }
    }
    strip(serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap())
}

/// The Markdown table without its last column (`s / scene`).
fn timeless_md(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|line| {
            let cut = line.trim_end_matches('|').rfind('|').unwrap_or(line.len());
            line[..cut].to_string()
        })
        .collect()
}

fn layout_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir.join("layouts"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn three_shards_merge_into_the_single_process_table() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), SCENES);
    let single = dir.path().join("single");
    bench(&scenes, &single, None);
    let shards: Vec<PathBuf> = (0..3).map(|k| dir.path().join(format!("s{k}"))).collect();
    let mut sizes = Vec::new();
    for (k, out) in shards.iter().enumerate() {
        bench(&scenes, out, Some(&format!("{k}/3")));
        sizes.push(layout_names(out).len());
    }
    assert_eq!(sizes.iter().sum::<usize>(), SCENES.len(), "{sizes:?}");

    let merged = dir.path().join("merged");
    let mut args = vec!["bench", "merge", merged.to_str().unwrap()];
    args.extend(shards.iter().map(|p| p.to_str().unwrap()));
    let o = run(&args);
    assert_eq!(
        stdout(&o),
        std::fs::read_to_string(merged.join("table.md")).unwrap()
    );
    assert_eq!(
        timeless_md(&merged.join("table.md")),
        timeless_md(&single.join("table.md"))
    );
    for name in ["table.json", "results.json"] {
        assert_eq!(
            timeless(&merged.join(name)),
            timeless(&single.join(name)),
            "{name}"
        );
    }
    assert_eq!(layout_names(&merged), layout_names(&single));
    for name in layout_names(&single) {
        let path = |d: &Path| d.join("layouts").join(&name);
        assert_eq!(timeless(&path(&merged)), timeless(&path(&single)), "{name}");
    }

    // A shard run again skips its finished scenes: the same results, the same merged table.
    let before = std::fs::read(shards[1].join("results.json")).unwrap();
    let table = std::fs::read(merged.join("table.md")).unwrap();
    bench(&scenes, &shards[1], Some("1/3"));
    assert_eq!(
        std::fs::read(shards[1].join("results.json")).unwrap(),
        before
    );
    run(&args);
    assert_eq!(std::fs::read(merged.join("table.md")).unwrap(), table);
}

#[test]
fn a_merge_refuses_overlaps_and_names_missing_scenes() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), SCENES);
    let (s0, s1) = (dir.path().join("s0"), dir.path().join("s1"));
    bench(&scenes, &s0, Some("0/2"));
    let merged = dir.path().join("merged");
    let merge = |dirs: &[&Path]| {
        let mut args = vec!["bench", "merge", merged.to_str().unwrap()];
        args.extend(dirs.iter().map(|p| p.to_str().unwrap()));
        disco(&args)
    };

    // Shard 1 never ran: its scenes are named, and nothing is written.
    let o = merge(&[s0.as_path()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let missing: Vec<&&str> = SCENES
        .iter()
        .filter(|id| !s0.join(format!("layouts/{id}.json")).exists())
        .collect();
    assert!(!missing.is_empty(), "6 scenes all in shard 0 of 2?");
    for id in &missing {
        assert!(stderr(&o).contains(**id), "{id}: {}", stderr(&o));
    }
    assert!(stderr(&o).contains("shard 1/2"), "{}", stderr(&o));
    assert!(!merged.join("table.md").exists());

    // The same shard given twice: its scenes are in two folders.
    bench(&scenes, &s1, Some("1/2"));
    let copy = dir.path().join("s0-copy");
    std::fs::create_dir_all(copy.join("layouts")).unwrap();
    for f in ["shard.json", "results.json"] {
        std::fs::copy(s0.join(f), copy.join(f)).unwrap();
    }
    let o = merge(&[s0.as_path(), &s1, &copy]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("in more than one shard"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("s0-copy"), "{}", stderr(&o));

    // Both shards once: a table of all six.
    let o = merge(&[s1.as_path(), &s0]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("| average | 6 |"), "{}", stdout(&o));

    // A folder holds one shard: another shard into it is refused.
    let o = disco(&[
        "bench",
        "--scenes",
        scenes.to_str().unwrap(),
        "--out",
        s0.to_str().unwrap(),
        "--shard",
        "1/2",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("its own --out"), "{}", stderr(&o));
}

#[test]
fn batch_shards_share_one_folder_and_cover_every_scene_once() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), SCENES);
    let out = dir.path().join("out");
    let mut seen: Vec<String> = Vec::new();
    for k in 0..3 {
        let shard = format!("{k}/3");
        let o = run(&[
            "batch",
            scenes.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--shard",
            &shard,
            "--json",
        ]);
        let reports: Value = serde_json::from_str(&stdout(&o)).unwrap();
        for r in reports.as_array().unwrap() {
            assert_eq!(r["status"], "done", "{r}");
            seen.push(r["id"].as_str().unwrap().to_string());
        }
    }
    seen.sort();
    assert_eq!(seen, SCENES, "every scene in exactly one shard");
    // The same split on a rerun: everything is already done.
    let o = run(&[
        "batch",
        scenes.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--shard",
        "2/3",
    ]);
    assert!(stdout(&o).contains("0 done"), "{}", stdout(&o));
}

#[test]
fn bad_shard_values_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), &["bathroom-01"]);
    for (value, says) in [
        ("3/3", "numbered 0 to 2"),
        ("0/0", "at least 1"),
        ("1", "is not I/N"),
        ("-1/3", "is not I/N"),
    ] {
        for command in ["batch", "bench"] {
            let mut args = vec![command];
            if command == "bench" {
                args.push("--scenes");
            }
            let shard = format!("--shard={value}");
            args.extend([scenes.to_str().unwrap(), "--out", "unused", shard.as_str()]);
            let o = disco(&args);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
            assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
        }
    }
}
