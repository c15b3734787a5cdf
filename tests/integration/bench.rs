//! `disco bench`: tables per category, resumed runs, counted failures, and suites of tables.

use std::path::Path;

use serde_json::Value;

use crate::harness::{bench_scenes, disco, stderr, stdout, write};

#[test]
fn bench_writes_a_table_per_category_resumes_and_counts_failures() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), &["bathroom-01", "bathroom-02", "kitchen-01"]);
    let out = dir.path().join("out");
    let args = |extra: &[&str]| {
        let mut a = vec![
            "bench",
            "--scenes",
            scenes.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        a.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        disco(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let o = run(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = stdout(&o);
    for row in [
        "| bathroom | 2 | 0.00 | 0.00 |",
        "| kitchen | 1 |",
        "| average | 3 |",
    ] {
        assert!(md.contains(row), "{row} in\n{md}");
    }
    assert_eq!(std::fs::read_to_string(out.join("table.md")).unwrap(), md);
    let table: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("table.json")).unwrap()).unwrap();
    assert_eq!(table["rows"].as_array().unwrap().len(), 3);
    let results: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(results.as_array().unwrap().len(), 3);
    let layout = out.join("layouts/bathroom-01.json");
    let written = std::fs::metadata(&layout).unwrap().modified().unwrap();

    // A rerun reuses the layouts and prints the same table; --fresh regenerates.
    let o = run(&["--json", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let again: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(again["table"], table);
    assert_eq!(
        std::fs::metadata(&layout).unwrap().modified().unwrap(),
        written
    );
    let o = run(&["--fresh", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(
        std::fs::metadata(&layout).unwrap().modified().unwrap(),
        written
    );

    // A broken scene fails alone: the table still comes out, with the failure counted.
    write(
        &scenes,
        "broken.json",
        "{\"room_type\": \"x\", \"room\": {\"width\": 0, \"depth\": 10}, \"assets\": []}",
    );
    let o = run(&[]);
    assert_eq!(
        o.status.code(),
        Some(4),
        "some scenes failed, the others written"
    );
    assert!(
        stderr(&o).contains("1 of 4 scenes failed"),
        "{}",
        stderr(&o)
    );
    assert!(
        stdout(&o).contains("| average | 3 (+1 failed) |"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn a_suite_writes_every_table_with_the_command_behind_it() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), &["dining-room-01", "bedroom-01"]);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let suite = format!(
        r#"scenes = [{scenes:?}]
jobs = 2
[[method]]
name = "rules"
[[method]]
name = "one shot"
config = {layoutgpt:?}
[[method]]
name = "grid search"
config = {holodeck:?}
[[method]]
name = "unused"
config = "does/not/exist.toml"
[[table]]
title = "By room"
by = "category"
methods = ["rules"]
[[table]]
title = "Against the baselines"
note = "Same scenes."
by = "method"
methods = ["rules", "one shot", "grid search"]
"#,
        scenes = scenes.to_str().unwrap(),
        layoutgpt = root
            .join("config/baselines/layoutgpt.toml")
            .to_str()
            .unwrap(),
        holodeck = root
            .join("config/baselines/holodeck.toml")
            .to_str()
            .unwrap(),
    );
    let path = write(dir.path(), "suite.toml", &suite);
    let out = dir.path().join("out");
    let o = disco(&[
        "bench",
        "--suite",
        &path,
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(out.join("RESULTS.md")).unwrap();
    for part in [
        "## By room",
        "| dining room | 1 |",
        "## Against the baselines",
        "Same scenes.",
        "| rules | 2 | 0.00 | 0.00 |",
        "| one shot | 2 |",
        "| grid search | 2 | 0.00 | 0.00 |",
        "disco bench --scenes",
        "holodeck.toml --jobs 2 --out",
    ] {
        assert!(md.contains(part), "{part:?} in\n{md}");
    }
    assert!(!md.contains("unused"), "a method no table shows is not run");
    for m in ["rules", "one-shot", "grid-search"] {
        assert!(out.join(m).join("table.md").exists(), "{m}");
    }
    assert!(!out.join("unused").exists());
}

#[test]
fn bench_refuses_an_out_folder_that_is_inside_or_holds_its_scenes() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = bench_scenes(dir.path(), &["bathroom-01"]);
    let before = std::fs::read_dir(&scenes).unwrap().count();
    let s = scenes.to_str().unwrap();
    let inside = scenes.join("results");
    let file = scenes.join("bathroom-01.json");
    let mut cases = vec![
        (s.to_string(), "is the input --scenes"),
        (
            inside.to_str().unwrap().to_string(),
            "lies inside the input folder --scenes",
        ),
        (
            dir.path().to_str().unwrap().to_string(),
            "would fill a folder holding the input --scenes",
        ),
    ];
    #[cfg(unix)]
    {
        let link = dir.path().join("linked");
        std::os::unix::fs::symlink(&scenes, &link).unwrap();
        cases.push((link.to_str().unwrap().to_string(), "is the input --scenes"));
    }
    for (out, why) in &cases {
        let o = disco(&["bench", "--scenes", s, "--out", out, "-q"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "--out {out}: {e}");
        assert!(
            e.contains(&format!("{out}: --out: {why}")),
            "--out {out}: {e}"
        );
        assert!(e.contains("choose another folder"), "{e}");
    }
    let o = disco(&[
        "bench",
        "--scenes",
        file.to_str().unwrap(),
        "--out",
        file.to_str().unwrap(),
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // Nothing was written into the scene folder, nor beside it.
    assert_eq!(std::fs::read_dir(&scenes).unwrap().count(), before);
    assert!(!inside.exists());
    assert!(!dir.path().join("table.md").exists());
    // A suite's scenes are kept the same way.
    let suite = write(
        dir.path(),
        "suite.toml",
        &format!(
            "scenes = [{s:?}]\n[[method]]\nname = \"rules\"\n[[table]]\ntitle = \"t\"\nby = \"category\"\nmethods = [\"rules\"]\n"
        ),
    );
    let o = disco(&["bench", "--suite", &suite, "--out", s, "-q"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--out: is the input --scenes"),
        "{}",
        stderr(&o)
    );
}
