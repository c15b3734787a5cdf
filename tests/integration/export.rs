//! What people open in other tools: glTF files checked by the Khronos validator and three.js,
//! asset meshes, and HTML reports opened in headless Chromium.

use serde_json::Value;

use crate::harness::chromium::open_in_chromium;
use crate::harness::glb::check_glb;
use crate::harness::{bench_scenes, disco, examples, generate, stderr, stdout, write};

#[test]
fn generate_writes_a_glb_and_a_report_people_can_open() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("room.json");
    let glb = dir.path().join("room.glb");
    let report = dir.path().join("report.html");
    let scene = examples().join("living-room.json");
    let o = generate(
        &scene,
        &out,
        &[
            "--glb",
            glb.to_str().unwrap(),
            "--wall-height",
            "300",
            "--report",
            report.to_str().unwrap(),
            "--set",
            "agents.designer.impl=noisy",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let objects = layout["objects"].as_array().unwrap();

    // The glb, parsed back: a root, floor, four walls, one node per object by name.
    let doc = gltf::Gltf::open(&glb).unwrap();
    assert_eq!(doc.nodes().count(), 1 + 1 + 4 + objects.len());
    for o in objects {
        let name = o["name"].as_str().unwrap();
        let node = doc.nodes().find(|n| n.name() == Some(name)).unwrap();
        let (t, _, s) = node.transform().decomposed();
        let x = o["position"][0].as_f64().unwrap() as f32 / 100.0;
        let y = o["position"][1].as_f64().unwrap() as f32 / 100.0;
        assert!((t[0] - x).abs() < 1e-4 && (t[2] + y).abs() < 1e-4, "{name}");
        let h = o["size"][2].as_f64().unwrap() as f32 / 100.0;
        assert!((s[1] - h).abs() < 1e-4, "{name}");
    }
    // What users' tools say: the Khronos validator finds nothing, three.js loads every mesh, and
    // the room stands 3 m high from the floor at y = 0.
    let checked = check_glb(&glb);
    assert_eq!(checked["errors"], 0, "{checked}");
    assert_eq!(checked["warnings"], 0, "{checked}");
    assert_eq!(
        checked["meshes"].as_array().unwrap().len(),
        1 + 4 + objects.len()
    );
    assert!(
        (checked["max"][1].as_f64().unwrap() - 3.0).abs() < 1e-6,
        "{checked}"
    );

    // The report opens in a browser with every picture shown.
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(
        html.contains("Is it true that"),
        "the evaluator's questions are there"
    );
    let (total, loaded) = open_in_chromium(&report);
    assert!(total > 2, "render, sheet and step pictures: {total}");
    assert_eq!(loaded, total);
}

#[test]
fn export_uses_asset_meshes_and_bench_writes_one_report() {
    let dir = tempfile::tempdir().unwrap();
    // A first room's glb serves as the mesh of a second room's plant.
    let first = dir.path().join("first.json");
    let first_glb = dir.path().join("first.glb");
    let scene = examples().join("living-room.json");
    let o = generate(
        &scene,
        &first,
        &["--glb", first_glb.to_str().unwrap(), "-q"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let mut spec: Value = serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    for a in spec["assets"].as_array_mut().unwrap() {
        if a["name"] == "plant-0" {
            a["mesh"] = Value::from("first.glb");
        }
    }
    let second_scene = write(dir.path(), "second.json", &spec.to_string());
    let o = disco(&[
        "export",
        first.to_str().unwrap(),
        "--scene",
        &second_scene,
        "-o",
        dir.path().join("second.glb").to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(summary["meshes"], 1);
    let checked = check_glb(&dir.path().join("second.glb"));
    assert_eq!(checked["errors"], 0, "{checked}");
    let doc = gltf::Gltf::open(dir.path().join("second.glb")).unwrap();
    let plant = doc.nodes().find(|n| n.name() == Some("plant-0")).unwrap();
    let triangles = plant
        .mesh()
        .unwrap()
        .primitives()
        .next()
        .unwrap()
        .indices()
        .unwrap()
        .count();
    assert!(
        triangles > 36,
        "the whole first room, not a box: {triangles} indices"
    );
    // A missing mesh file is one clear error and no output.
    std::fs::remove_file(&first_glb).unwrap();
    let target = dir.path().join("third.glb");
    let o = disco(&[
        "export",
        first.to_str().unwrap(),
        "--scene",
        &second_scene,
        "-o",
        target.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("first.glb"), "{}", stderr(&o));
    assert!(!target.exists());

    // One report over a benchmark's scenes.
    let scenes = bench_scenes(dir.path(), &["bathroom-01", "home-gym-01"]);
    let report = dir.path().join("bench.html");
    let o = disco(&[
        "bench",
        "--scenes",
        scenes.to_str().unwrap(),
        "--out",
        dir.path().join("bench").to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let html = std::fs::read_to_string(&report).unwrap();
    for part in ["bathroom-01", "home-gym-01", "| average", "average"] {
        if part.starts_with('|') {
            continue;
        }
        assert!(html.contains(part), "{part}");
    }
    let (total, loaded) = open_in_chromium(&report);
    assert_eq!((total, loaded), (2, 2), "one render per scene");
}

#[test]
fn a_polygon_room_with_openings_exports_and_reports_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("studio.json");
    let glb = dir.path().join("studio.glb");
    let report = dir.path().join("studio.html");
    let scene = examples().join("l-shaped-studio.json");
    let o = generate(
        &scene,
        &out,
        &[
            "--glb",
            glb.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let objects = layout["objects"].as_array().unwrap().len();

    // One wall node per edge of the six-cornered outline, the door and windows cut into them.
    let doc = gltf::Gltf::open(&glb).unwrap();
    assert_eq!(doc.nodes().count(), 1 + 1 + 6 + objects);
    for i in 0..6 {
        let name = format!("wall-{i}");
        assert!(
            doc.nodes().any(|n| n.name() == Some(name.as_str())),
            "{name}"
        );
    }
    let checked = check_glb(&glb);
    assert_eq!(checked["errors"], 0, "{checked}");
    assert_eq!(checked["warnings"], 0, "{checked}");
    assert_eq!(
        checked["meshes"].as_array().unwrap().len(),
        1 + 6 + objects,
        "{checked}"
    );
    // three.js sees the L's extent: 6.2 m along X, 4.8 m along -Z (walls 10 cm thick outside).
    let (min, max) = (&checked["min"], &checked["max"]);
    let span = |i: usize| max[i].as_f64().unwrap() - min[i].as_f64().unwrap();
    assert!((span(0) - 6.4).abs() < 1e-4, "{checked}");
    assert!((span(2) - 5.0).abs() < 1e-4, "{checked}");

    // The report names the openings and shows every picture.
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(
        html.contains("door on wall 0 at 500 cm, 90 cm wide, swings in"),
        "the door is listed"
    );
    assert!(html.contains("window on wall 5"), "the window is listed");
    let (total, loaded) = open_in_chromium(&report);
    assert!(total >= 1, "{total}");
    assert_eq!(loaded, total);
}

/// A room with pieces on tops and on walls: three.js (and the validator) load every piece at its
/// height, the lamp's bottom on its nightstand's top, the painting's where the layout hangs it.
#[test]
fn three_js_loads_every_piece_off_the_floor_at_its_height() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("room.json");
    let glb = dir.path().join("room.glb");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bench/whole/w01-master-bedroom.json");
    let o = generate(&scene, &out, &["--glb", glb.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let report = check_glb(&glb);
    assert_eq!(report["errors"], 0, "{report}");
    let mut off = 0;
    for o in layout["objects"].as_array().unwrap() {
        let name = o["name"].as_str().unwrap();
        let elevation = o["elevation"].as_f64().unwrap_or(0.0);
        let height = o["size"][2].as_f64().unwrap();
        let [low, high] = [0, 1].map(|k| report["heights"][name][k].as_f64().unwrap());
        assert!((low - elevation / 100.0).abs() < 1e-3, "{name}: {low} m");
        assert!(
            (high - (elevation + height) / 100.0).abs() < 1e-3,
            "{name}: {high} m"
        );
        off += usize::from(elevation > 0.0);
    }
    assert!(
        off >= 6,
        "the bedroom's lamps, TV, vase, painting, mirror and clock: {off}"
    );
}
