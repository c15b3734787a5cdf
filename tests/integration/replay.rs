//! A recorded model run replayed: `bench/replays/r02-home-office-L` holds the answers a capable
//! model (written by hand through the manual model server) gave on the L-shaped home office, so
//! the model path's protocol (what is asked, what is settled by geometry, what moved unasked) is
//! checked without a server. A change to a prompt or to what is asked misses the cache and shows
//! here as a changed call count.

use std::path::Path;

use crate::harness::generate;

#[test]
fn the_recorded_home_office_replays_in_five_calls_with_every_move_reported() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let replay = root.join("bench/replays/r02-home-office-L");
    let dir = tempfile::tempdir().unwrap();
    // The cache is copied, so a miss cannot write into the repository.
    let cache = dir.path().join("cache");
    std::fs::create_dir_all(&cache).unwrap();
    for entry in std::fs::read_dir(replay.join("cache")).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), cache.join(entry.file_name())).unwrap();
    }
    let out = dir.path().join("office.json");
    let run = generate(
        &root.join("bench/requests/r02-home-office-L.json"),
        &out,
        &[
            "--config",
            replay.join("graph.toml").to_str().unwrap(),
            "--cache",
            cache.to_str().unwrap(),
        ],
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let layout: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let stats = &layout["stats"];
    // Planner, one designer call per group, nothing else: every question was settled by geometry.
    assert_eq!(stats["llm_calls"], 5, "{stats}");
    assert!(
        stats["fallbacks"].as_array().is_none_or(Vec::is_empty),
        "{stats}"
    );
    let notes: Vec<&str> = stats["notes"]
        .as_array()
        .map(|n| n.iter().filter_map(|v| v.as_str()).collect())
        .unwrap_or_default();
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with("unasked move: floor-lamp moved from [85, 300]")),
        "{notes:?}"
    );
    // Each window's rule is stated once per request, with the room; a piece is told of the
    // windows only when it stands on a wall (the desk), not when it stands free (its chair).
    for entry in std::fs::read_dir(replay.join("cache")).unwrap() {
        let text = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        let cached: serde_json::Value = serde_json::from_str(&text).unwrap();
        let Some(user) = cached["request"]["messages"][1]["content"].as_str() else {
            continue;
        };
        for line in user.lines() {
            if line.starts_with("- office-chair:") {
                assert!(!line.contains("window"), "{line}");
            }
            if line.starts_with("- desk: desk, 140 x 70 cm") {
                assert!(
                    line.contains("; it may stand under windows 0, 1 (sills 85, 95 cm);"),
                    "{line}"
                );
            }
        }
        assert!(
            user.matches("sill 85 cm above the floor").count() <= 1,
            "{user}"
        );
    }
}
