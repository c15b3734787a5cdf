//! `disco refine`: broken layouts repaired, layouts of another scene refused, nothing written on
//! error, any names and prompts carried through.

use std::path::Path;

use serde_json::Value;

use crate::harness::{GOOD, disco, examples, stderr, stdout, write};

#[test]
fn refine_repairs_a_broken_layout_that_metrics_and_render_then_accept() {
    let dir = tempfile::tempdir().unwrap();
    let scene = examples().join("bedroom.json");
    let broken = examples().join("bedroom-broken.layout.json");
    let out = dir.path().join("fixed.json");
    let png = dir.path().join("fixed.png");
    let o = disco(&[
        "refine",
        scene.to_str().unwrap(),
        broken.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--render",
        png.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("7 placed"), "{}", stdout(&o));

    let o = disco(&[
        "metrics",
        scene.to_str().unwrap(),
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let m: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(m["collision_pct"], 0.0);
    assert_eq!(m["oob_pct"], 0.0);
    assert_eq!(m["dropped_pct"], 0.0);
    assert_eq!(
        m["wall_pct"], 100.0,
        "every against-wall object ends on a wall: {m}"
    );
    assert_eq!(m["placed"], 7);

    // The broken layout itself measures as broken.
    let (_, before) = disco_layout::layout::DraftLayout::load(&broken)
        .unwrap()
        .resolve(&broken, &disco_layout::SceneSpec::load(&scene).unwrap())
        .map(|(l, missing)| (missing, l))
        .unwrap();
    let m0 = disco_layout::metrics::measure(&before);
    assert!(m0.collision_pct > 0.0 || m0.oob_pct > 0.0 || m0.wall_pct < 100.0);

    let png_bytes = std::fs::read(&png).unwrap();
    assert_eq!(&png_bytes[1..4], b"PNG");
    let again = dir.path().join("again.png");
    let o = disco(&[
        "render",
        out.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
        "--size",
        "512",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let header = std::fs::read(&again).unwrap();
    let width = u32::from_be_bytes(header[16..20].try_into().unwrap());
    assert_eq!(width, 512);
}

#[test]
fn refine_refuses_layouts_that_do_not_belong_to_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "scene.json", GOOD);
    let cases = [
        (
            r#"{"objects": [{"name": "sofa-0", "position": [1, 2]}]}"#,
            "layout.json: objects[0].name: \"sofa-0\" is not an asset of scene \"scene\"",
        ),
        (
            r#"{"objects": [{"name": "bed-0", "size": [1, 2, 3], "position": [1, 2]}]}"#,
            "objects[0].size: [1.0, 2.0, 3.0] differs from the scene's size [160.0, 210.0, 100.0]",
        ),
        (
            r#"{"objects": [{"name": "bed-0", "position": [1]}]}"#,
            "layout.json: objects[0].position: invalid length 1",
        ),
        (
            r#"{"room": {"width": 10, "depth": 10}, "objects": []}"#,
            "room: 10 x 10 cm differs from the scene's room 400 x 350 cm",
        ),
        (
            r#"{"objects": [{"name": "bed-0", "position": [1, 2]}, {"name": "bed-0", "position": [1, 2]}]}"#,
            "objects[1].name: duplicate name \"bed-0\"",
        ),
    ];
    for (text, expected) in cases {
        let layout = write(dir.path(), "layout.json", text);
        let out = dir.path().join("out.json");
        let o = disco(&["refine", &scene, &layout, "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{text}");
        assert!(
            stderr(&o).contains(expected),
            "expected {expected:?} in {:?}",
            stderr(&o)
        );
        assert!(!out.exists(), "nothing is written on error");
    }
}

#[test]
fn a_missing_output_folder_is_made_and_an_unwritable_output_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "scene.json", GOOD);
    let layout = write(dir.path(), "layout.json", r#"{"objects": []}"#);
    let out = dir.path().join("missing-dir/out.json");
    let o = disco(&["refine", &scene, &layout, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.is_file());
    // The output names a folder: nothing can be written there, and nothing is left behind.
    let taken = dir.path().join("taken");
    std::fs::create_dir(&taken).unwrap();
    let o = disco(&["refine", &scene, &layout, "-o", taken.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("taken: cannot write the file"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        4,
        "no temporary file left"
    );
}

#[test]
fn unicode_names_and_prompts_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let text = r#"{"id": "chambre-à-coucher", "prompt": "une chambre calme 🌙 avec un lit", "room_type": "chambre",
      "room": {"width": 300, "depth": 300},
      "assets": [{"name": "床-0", "category": "lit", "size": [140, 200, 50]},
                 {"name": "ночник-0", "category": "table de chevet", "size": [40, 40, 50]}]}"#;
    let scene = write(dir.path(), "scène.json", text);
    let layout = write(
        dir.path(),
        "layout.json",
        r#"{"objects": [{"name": "床-0", "position": [150, 150]}, {"name": "ночник-0", "position": [150, 150]}]}"#,
    );
    let out = dir.path().join("sortie.json");
    let o = disco(&["refine", &scene, &layout, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(v["id"], "chambre-à-coucher");
    let names: Vec<&str> = v["objects"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["床-0", "ночник-0"]);
    let png = dir.path().join("vue.png");
    assert!(
        disco(&["render", out.to_str().unwrap(), "-o", png.to_str().unwrap()])
            .status
            .success()
    );
    // The spec itself round-trips through the library unchanged.
    let spec = disco_layout::SceneSpec::load(Path::new(&scene)).unwrap();
    let back: disco_layout::SceneSpec =
        serde_json::from_str(&serde_json::to_string(&spec).unwrap()).unwrap();
    assert_eq!(back, spec);
}

#[test]
fn usage_errors_exit_2() {
    let o = disco(&["refine"]);
    assert_eq!(o.status.code(), Some(2));
}
