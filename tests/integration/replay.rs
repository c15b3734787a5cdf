//! Recorded model runs replayed: `bench/replays/r02-home-office-L` holds the answers a capable
//! model (written by hand through the manual model server) gave on the L-shaped home office, and
//! `bench/replays/r03-whole-bedroom` those it gave on a bedroom whose lamps, TV, painting and clock
//! leave the floor, so the model path's protocol (what is asked, what is settled by geometry, what
//! moved unasked, what holds each piece) is checked without a server. A change to a prompt or to
//! what is asked misses the cache and shows here as a changed call count.

use std::path::Path;

use crate::harness::generate;

/// Runs `scene` with the replay folder `replay`'s graph and a copy of its cache (so a miss
/// cannot write into the repository); returns the layout.
fn replay(scene: &Path, replay: &Path) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    std::fs::create_dir_all(&cache).unwrap();
    for entry in std::fs::read_dir(replay.join("cache")).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), cache.join(entry.file_name())).unwrap();
    }
    let out = dir.path().join("layout.json");
    let run = generate(
        scene,
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
    serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap()
}

#[test]
fn the_recorded_whole_bedroom_replays_with_lamps_on_nightstands_and_pictures_on_walls() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let folder = root.join("bench/replays/r03-whole-bedroom");
    let layout = replay(&folder.join("scene.json"), &folder);
    let stats = &layout["stats"];
    // The planner and one designer call per group; every question settled by geometry.
    assert_eq!(stats["llm_calls"], 4, "{stats}");
    assert!(
        stats["fallbacks"].as_array().is_none_or(Vec::is_empty),
        "{stats}"
    );
    let objects = layout["objects"].as_array().unwrap();
    assert_eq!(objects.len(), 9, "nothing dropped: {}", layout["dropped"]);
    let object = |name: &str| {
        objects
            .iter()
            .find(|o| o["name"] == name)
            .unwrap_or_else(|| panic!("{name} not placed"))
    };
    for (lamp, stand) in [
        ("table-lamp-0", "nightstand-0"),
        ("table-lamp-1", "nightstand-1"),
        ("tv-0", "tv-stand-0"),
    ] {
        let l = object(lamp);
        let s = object(stand);
        assert_eq!(l["on"], stand, "{l}");
        assert_eq!(l["elevation"], s["size"][2], "{l} stands on the top of {s}");
        assert!(s.get("elevation").is_none(), "{s} stands on the floor");
    }
    // The painting hangs on the wall behind the bed's head (wall 2, the top one), centred over
    // the bed, 20 cm above its top; the clock on another wall, its centre at 190 cm.
    let bed = object("bed-0");
    let painting = object("painting-0");
    assert_eq!(painting["wall"], 2, "{painting}");
    assert_eq!(painting["position"][0], bed["position"][0], "{painting}");
    assert_eq!(painting["elevation"], 120.0, "{painting}");
    let clock = object("clock-0");
    assert!(clock["wall"].as_u64().is_some_and(|w| w != 2), "{clock}");
    assert_eq!(clock["elevation"], 190.0 - 17.5, "{clock}");
    for o in objects {
        let floor = o.get("on").is_none() && o.get("wall").is_none();
        assert_eq!(floor, o.get("elevation").is_none(), "{o}");
    }
}

#[test]
fn the_recorded_home_office_replays_in_five_calls_with_every_move_reported() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let replay_folder = root.join("bench/replays/r02-home-office-L");
    let layout = replay(
        &root.join("bench/requests/r02-home-office-L.json"),
        &replay_folder,
    );
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
    for entry in std::fs::read_dir(replay_folder.join("cache")).unwrap() {
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

/// The answers helpers playing a capable model gave on the seven fresh rooms of
/// `bench/model-path` (session 14, the final run), replayed: each room in the calls it took
/// then, nothing from a fallback, every asset placed, every unasked move noted with its reason,
/// and what the model called infeasible noted and not asked again. The plans name doors,
/// windows and walls as targets (`display-cabinet-0` beside `door-1`, the sliding door).
#[test]
fn the_seven_model_path_rooms_replay_in_their_recorded_calls() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let recorded = [
        ("m01-l-living-room", 6),
        ("m02-home-office-alcove", 6),
        ("m03-bedroom-angled-wall", 6),
        ("m04-dining-room-bay", 7),
        ("m05-clinic-waiting-room", 7),
        ("m06-meeting-room", 6),
        ("m07-studio-flat", 7),
    ];
    let mut infeasible = 0;
    for (room, calls) in recorded {
        let folder = root.join("bench/replays").join(room);
        let layout = replay(
            &root.join("bench/model-path").join(format!("{room}.json")),
            &folder,
        );
        let stats = &layout["stats"];
        assert_eq!(stats["llm_calls"], calls, "{room}: {stats}");
        assert!(
            stats["fallbacks"].as_array().is_none_or(Vec::is_empty),
            "{room}: {stats}"
        );
        let scene: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(folder.join("scene.json")).unwrap())
                .unwrap();
        assert_eq!(
            layout["objects"].as_array().unwrap().len(),
            scene["assets"].as_array().unwrap().len(),
            "{room}: nothing dropped: {}",
            layout["dropped"]
        );
        let notes: Vec<&str> = stats["notes"]
            .as_array()
            .map(|n| n.iter().filter_map(|v| v.as_str()).collect())
            .unwrap_or_default();
        for n in notes.iter().filter(|n| n.starts_with("unasked move:")) {
            assert!(
                n.contains(" moved from [") && n.contains("): "),
                "{room}: {n}"
            );
        }
        infeasible += notes
            .iter()
            .filter(|n| n.contains("cannot be met") && n.ends_with("it is not asked about again"))
            .count();
        if room == "m03-bedroom-angled-wall" {
            // The walkway repair moved the stool it had just placed, not a nightstand of the
            // bed's group to the bed's other side: one nightstand on each side.
            let x = |name: &str| {
                layout["objects"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|o| o["name"] == name)
                    .and_then(|o| o["position"][0].as_f64())
                    .unwrap()
            };
            let (a, bed, b) = (x("nightstand-0"), x("bed-0"), x("nightstand-1"));
            assert!(
                (a - bed) * (b - bed) < 0.0,
                "nightstands at {a} and {b}, the bed at {bed}"
            );
        }
        if room == "m04-dining-room-bay" {
            let cabinet = &layout["plan"]["constraints"]["display-cabinet-0"];
            assert!(
                cabinet["relations"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|r| r["relation"] == "side_of" && r["target"] == "door-1"),
                "{cabinet}"
            );
        }
    }
    assert_eq!(infeasible, 9, "the checks the models called infeasible");
}
