//! Reading and writing the support fields of placed objects.

use std::path::Path;

use super::*;

const FLOOR_ONLY: &str = r#"{
  "id": "s",
  "room": {
    "width": 400.0,
    "depth": 300.0
  },
  "objects": [
    {
      "name": "nightstand-0",
      "category": "nightstand",
      "size": [
        45.0,
        40.0,
        55.0
      ],
      "position": [
        30.0,
        20.0
      ],
      "rotation": 0.0
    }
  ],
  "dropped": [],
  "plan": {
    "constraints": {},
    "groups": []
  },
  "stats": {
    "llm_calls": 0,
    "prompt_tokens": 0,
    "completion_tokens": 0,
    "wall_ms": 0
  }
}"#;

fn parse(text: &str) -> Result<Layout> {
    let layout: Layout = io::parse_json(Path::new("l.json"), text)?;
    layout.validate(Path::new("l.json"))?;
    Ok(layout)
}

/// The floor-only layout with a lamp added, whose fields are `extra`.
fn with_lamp(extra: &str) -> String {
    let lamp = format!(
        r#"{{"name": "lamp-0", "category": "table lamp", "size": [25, 25, 45],
             "position": [30, 20], "rotation": 0 {extra}}}"#
    );
    FLOOR_ONLY.replacen(
        "\"rotation\": 0.0\n    }",
        &format!("\"rotation\": 0.0\n    }},\n    {lamp}"),
        1,
    )
}

#[test]
fn a_floor_only_layout_is_written_back_byte_for_byte() {
    let layout = parse(FLOOR_ONLY).unwrap();
    assert_eq!(layout.objects[0].elevation, 0.0);
    assert!(layout.objects[0].on_floor());
    assert_eq!(serde_json::to_string_pretty(&layout).unwrap(), FLOOR_ONLY);
}

#[test]
fn elevation_on_and_wall_are_read_and_written() {
    let layout = parse(&with_lamp(r#", "elevation": 55, "on": "nightstand-0""#)).unwrap();
    let lamp = layout.object("lamp-0").unwrap();
    assert_eq!(
        (lamp.elevation, lamp.on.as_deref()),
        (55.0, Some("nightstand-0"))
    );
    assert_eq!(lamp.top(), 100.0);
    assert!(!lamp.on_floor());
    let back = serde_json::to_string(&layout).unwrap();
    assert!(
        back.contains(r#""elevation":55.0,"on":"nightstand-0""#),
        "{back}"
    );
    assert!(!back.contains("\"wall\""), "{back}");
    let layout = parse(&with_lamp(r#", "elevation": 150, "wall": 3"#)).unwrap();
    assert_eq!(layout.object("lamp-0").unwrap().wall, Some(3));
}

#[test]
fn bad_supports_are_refused_with_the_field() {
    for (extra, field, why) in [
        (r#", "elevation": -1"#, "objects[1].elevation", "from 0 to"),
        (r#", "elevation": 1e9"#, "objects[1].elevation", "from 0 to"),
        (
            r#", "on": "ghost-0""#,
            "objects[1].on",
            "not a placed object",
        ),
        (r#", "on": "lamp-0""#, "objects[1].on", "itself"),
        (r#", "wall": 4"#, "objects[1].wall", "walls 0 to 3"),
        (
            r#", "wall": 1, "on": "nightstand-0""#,
            "objects[1]",
            "not both",
        ),
    ] {
        let e = parse(&with_lamp(extra)).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains(why), "{extra}: {e}");
    }
}

#[test]
fn objects_standing_on_each_other_in_a_circle_are_refused() {
    let text = with_lamp(r#", "on": "nightstand-0""#).replacen(
        "\"rotation\": 0.0\n    }",
        "\"rotation\": 0.0, \"on\": \"lamp-0\"\n    }",
        1,
    );
    let e = parse(&text).unwrap_err().to_string();
    assert!(e.contains("through others, on itself"), "{e}");
}

#[test]
fn a_draft_carries_its_supports_and_names_scene_assets() {
    let scene = SceneSpec {
        id: "s".into(),
        prompt: String::new(),
        room_type: "bedroom".into(),
        room: Room::rect(400.0, 300.0),
        assets: vec![
            scene::Asset::new("nightstand-0", "nightstand", [45.0, 40.0, 55.0]),
            scene::Asset::new("lamp-0", "table lamp", [25.0, 25.0, 45.0]),
        ],
    };
    let draft: DraftLayout = serde_json::from_str(
        r#"{"objects": [{"name": "lamp-0", "position": [30, 20], "elevation": 55, "on": "nightstand-0"}]}"#,
    )
    .unwrap();
    let (layout, missing) = draft.resolve(Path::new("d.json"), &scene).unwrap();
    assert_eq!(missing, vec!["nightstand-0".to_string()]);
    assert_eq!(layout.objects[0].on.as_deref(), Some("nightstand-0"));
    assert_eq!(layout.objects[0].elevation, 55.0);
    let draft: DraftLayout = serde_json::from_str(
        r#"{"objects": [{"name": "lamp-0", "position": [30, 20], "on": "bed-0"}]}"#,
    )
    .unwrap();
    let e = draft.resolve(Path::new("d.json"), &scene).unwrap_err();
    assert!(e.to_string().contains("not an asset of the scene"), "{e}");
}
