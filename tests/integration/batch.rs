//! `disco batch`: failures stay with their scene, reruns skip what is done, and the rule agents
//! meet the targets on the benchmark scenes.

use std::path::Path;

use serde_json::Value;

use crate::harness::{disco, examples, stderr, stdout, write};

#[test]
fn batch_finishes_the_good_scenes_reports_the_bad_one_and_skips_on_rerun() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    for name in ["bedroom.json", "office.json", "dining-room.json"] {
        std::fs::copy(examples().join(name), scenes.join(name)).unwrap();
    }
    write(
        &scenes,
        "broken.json",
        "{\"room_type\": \"x\", \"room\": {\"width\": 0, \"depth\": 10}, \"assets\": []}",
    );
    let out = dir.path().join("out");
    let o = disco(&[
        "batch",
        scenes.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "3",
    ]);
    assert_eq!(
        o.status.code(),
        Some(4),
        "one scene failed, the others written"
    );
    let table = stdout(&o);
    assert!(
        table.contains("4 scenes: 3 done, 0 skipped, 1 failed"),
        "{table}"
    );
    assert!(
        stderr(&o).contains("broken.json: room.width: must be positive"),
        "{}",
        stderr(&o)
    );
    for id in ["bedroom-01", "office-01", "dining-room-01"] {
        assert!(out.join(format!("{id}.json")).exists(), "{id}");
    }
    std::fs::remove_file(scenes.join("broken.json")).unwrap();
    let o = disco(&[
        "batch",
        scenes.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let reports: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!(
        reports
            .as_array()
            .unwrap()
            .iter()
            .all(|r| r["status"] == "skipped"),
        "{reports}"
    );
    // No temporary files are left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

/// The offline default over the 45 benchmark scenes and the unseen room types: physically sound
/// everywhere, and on average at the targets (>= 95% constraints, >= 95% reach).
#[test]
fn rule_agents_meet_the_targets_on_the_benchmark_scenes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = tempfile::tempdir().unwrap();
    let o = disco(&[
        "batch",
        &root.join("bench/scenes").to_string_lossy(),
        &root.join("bench/unseen").to_string_lossy(),
        "--out",
        &out.path().to_string_lossy(),
        "--json",
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let reports: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let reports = reports.as_array().unwrap();
    assert_eq!(reports.len(), 48);
    let (mut constraints, mut reach) = (0.0, 0.0);
    for r in reports {
        let m = &r["metrics"];
        let id = r["id"].as_str().unwrap();
        assert_eq!(m["collision_pct"], 0.0, "{id}");
        assert_eq!(m["oob_pct"], 0.0, "{id}");
        assert_eq!(m["dropped_pct"], 0.0, "{id}");
        constraints += m["constraint_pct"].as_f64().unwrap();
        reach += m["reach_pct"].as_f64().unwrap();
    }
    let n = reports.len() as f64;
    assert!(
        constraints / n >= 95.0,
        "mean constraints {}",
        constraints / n
    );
    assert!(reach / n >= 95.0, "mean reach {}", reach / n);
}
