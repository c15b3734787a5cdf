//! `disco validate`: good scenes pass, bad ones are refused with the file, the field and the reason.

use serde_json::Value;

use crate::harness::{GOOD, disco, examples, stderr, stdout, write};

/// Runs `disco validate` on `text` and returns (exit code, stderr).
fn validate(text: &str) -> (i32, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "scene.json", text);
    let o = disco(&["validate", &path]);
    (o.status.code().unwrap(), stderr(&o))
}

#[test]
fn a_good_scene_validates() {
    let (code, err) = validate(GOOD);
    assert_eq!(code, 0, "{err}");
    let o = disco(&[
        "validate",
        examples().join("bedroom.json").to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert!(
        stdout(&o).contains("valid scene \"bedroom-01\": 7 assets"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn bad_scenes_are_refused_with_file_field_and_reason() {
    let cases: &[(&str, String, &str)] = &[
        (
            "unparsable",
            "{\"room_type\": \"bedroom\",, }".into(),
            "scene.json: line 1, column 25: invalid JSON",
        ),
        (
            "truncated",
            GOOD[..60].into(),
            "the JSON ends too early (is the file truncated?)",
        ),
        (
            "missing room",
            r#"{"room_type": "x", "assets": []}"#.into(),
            "scene.json: (document): missing field `room`",
        ),
        (
            "missing size",
            GOOD.replace(r#", "size": [50, 40, 55]"#, ""),
            "scene.json: assets[1]: missing field `size`",
        ),
        (
            "duplicate",
            GOOD.replace("nightstand-0", "bed-0"),
            "assets[1].name: duplicate name \"bed-0\" (also assets[0])",
        ),
        (
            "zero size",
            GOOD.replace("[50, 40, 55]", "[50, 0, 55]"),
            "assets[1].size: depth must be a finite positive number of cm, got 0",
        ),
        (
            "negative size",
            GOOD.replace("[50, 40, 55]", "[-50, 40, 55]"),
            "assets[1].size: width must be a finite positive number",
        ),
        (
            "infinite size",
            GOOD.replace("[50, 40, 55]", "[1e999, 40, 55]"),
            "scene.json: assets[1].size",
        ),
        (
            "zero room",
            GOOD.replace(r#""width": 400"#, r#""width": 0"#),
            "room.width: must be positive, got 0 cm",
        ),
        (
            "absurd room",
            GOOD.replace(r#""depth": 350"#, r#""depth": 35000"#),
            "room.depth: 35000 cm is over the 10000 cm (100 m) limit",
        ),
        (
            "no assets",
            r#"{"room_type": "x", "room": {"width": 100, "depth": 100}, "assets": []}"#.into(),
            "assets: the scene has no assets to place",
        ),
        (
            "typo",
            GOOD.replace("\"assets\"", "\"assests\""),
            "unknown field `assests`",
        ),
        (
            "empty name",
            GOOD.replace("\"nightstand-0\"", "\"  \""),
            "assets[1].name: must not be empty",
        ),
        (
            "wrong type",
            GOOD.replace("[50, 40, 55]", "\"big\""),
            "assets[1].size: invalid type: string \"big\"",
        ),
    ];
    for (what, text, expected) in cases {
        let (code, err) = validate(text);
        assert_eq!(code, 1, "{what}: {err}");
        assert!(
            err.contains(expected),
            "{what}: expected {expected:?} in {err:?}"
        );
        assert!(
            err.contains("scene.json"),
            "{what}: the file is named: {err}"
        );
        assert!(!err.contains("panicked"), "{what}: {err}");
    }
}

#[test]
fn a_missing_file_is_named() {
    let o = disco(&["validate", "/nonexistent/scene.json"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("/nonexistent/scene.json: cannot read the file"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn an_asset_too_big_for_the_room_is_a_warning_and_ends_in_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let text = GOOD.replace("[160, 210, 100]", "[500, 400, 100]");
    let scene = write(dir.path(), "scene.json", &text);
    let o = disco(&["validate", &scene]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("warning: ") && stderr(&o).contains("\"bed-0\" will be dropped"),
        "{}",
        stderr(&o)
    );

    let layout = write(dir.path(), "layout.json", r#"{"objects": []}"#);
    let out = dir.path().join("out.json");
    let o = disco(&["refine", &scene, &layout, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(v["objects"].as_array().unwrap().len(), 1);
    assert_eq!(v["dropped"][0]["name"], "bed-0");
    assert!(
        v["dropped"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("does not fit the 400 x 350 cm room")
    );
}

#[test]
fn every_example_scene_validates() {
    let mut n = 0;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".json") && !name.contains(".layout.") {
            let o = disco(&["validate", path.to_str().unwrap()]);
            assert!(o.status.success(), "{name}: {}", stderr(&o));
            n += 1;
        }
    }
    assert!(n >= 5, "only {n} example scenes");
}

#[test]
fn one_asset_is_counted_in_the_singular() {
    let dir = tempfile::tempdir().unwrap();
    let one = GOOD.replace(
        r#",
             {"name": "nightstand-0", "category": "nightstand", "size": [50, 40, 55]}"#,
        "",
    );
    assert_ne!(one, GOOD);
    let path = write(dir.path(), "scene.json", &one);
    let o = disco(&["validate", &path]);
    assert!(
        stdout(&o).contains(": 1 asset in a 400 x 350 cm"),
        "{}",
        stdout(&o)
    );
}
