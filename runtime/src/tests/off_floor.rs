//! Objects off the floor on the external wire: a `process` designer that stands lamps on the
//! nightstands and hangs a painting above the bed gets them into the final layout with
//! `elevation`, `on` and `wall` intact, and the trace shows them; one that names a support the
//! scene lacks, or a wall the room lacks, is refused by the reply's acceptance and replaced by
//! its fallback.

use std::sync::Arc;

use disco_core::layout::{Layout, PlacedObject};
use disco_core::metrics::measure;
use disco_core::scene::{Asset, Room, SceneSpec};

use crate::Runtime;
use crate::config::GraphConfig;
use crate::registry::Registry;
use crate::trace::{Trace, TraceEvent, TraceKind};

/// A designer that poses every object of its group from one fixed table: the bed's head on
/// wall 0 (the bottom wall), a nightstand each side, a lamp on each nightstand and the painting
/// on wall 0 centred above the bed, 20 cm over its top. `bad-on` stands lamp-0 on an object the
/// scene does not have; `bad-wall` hangs the painting on wall 7 of a four-walled room.
const MOUNTING_DESIGNER: &str = r#"
import json, sys
mode = sys.argv[1]
poses = {
    "bed-0": {"position": [200, 105], "rotation": 0},
    "nightstand-0": {"position": [90, 20], "rotation": 0},
    "nightstand-1": {"position": [310, 20], "rotation": 0},
    "lamp-0": {"position": [90, 20], "rotation": 0, "elevation": 55, "on": "nightstand-0"},
    "lamp-1": {"position": [310, 20], "rotation": 0, "elevation": 55, "on": "nightstand-1"},
    "painting-0": {"position": [200, 2.1], "rotation": 0, "elevation": 120, "wall": 0},
}
if mode == "bad-on":
    poses["lamp-0"]["on"] = "ghost-9"
if mode == "bad-wall":
    poses["painting-0"]["wall"] = 7
for line in sys.stdin:
    req = json.loads(line)
    group = req["request"]["group"]
    reply = {"objects": [dict(poses[n], name=n) for n in group]}
    print(json.dumps({"protocol": 1, "id": req["id"], "reply": reply}), flush=True)
"#;

/// A 400 x 350 cm bedroom with a bed, two nightstands, two table lamps and a painting.
fn bedroom_with_lamps() -> SceneSpec {
    SceneSpec {
        id: "lamps".into(),
        prompt: "a bedroom with a lamp on each nightstand and a painting above the bed".into(),
        room_type: "bedroom".into(),
        room: Room::rect(400.0, 350.0),
        assets: vec![
            Asset::new("bed-0", "bed", [160.0, 210.0, 100.0]),
            Asset::new("nightstand-0", "nightstand", [50.0, 40.0, 55.0]),
            Asset::new("nightstand-1", "nightstand", [50.0, 40.0, 55.0]),
            Asset::new("lamp-0", "table lamp", [30.0, 30.0, 50.0]),
            Asset::new("lamp-1", "table lamp", [30.0, 30.0, 50.0]),
            Asset::new("painting-0", "framed painting", [100.0, 4.0, 70.0]),
        ],
    }
}

/// Runs the scene with the designer script in `mode` (no retries, the rules as its fallback).
async fn run_with(mode: &str) -> (Layout, Vec<TraceEvent>) {
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("mounting_designer.py");
    std::fs::write(&script, MOUNTING_DESIGNER).unwrap();
    let command = format!(
        "agents.designer.command=[\"python3\", {:?}, \"{mode}\"]",
        script.to_string_lossy()
    );
    let sets: Vec<String> = [
        "agents.designer.impl=process",
        &command,
        "agents.designer.retries=0",
        "agents.designer.fallback=rules",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let graph = GraphConfig::load(None, &sets).unwrap();
    let rt = Runtime::new(graph, Registry::builtin()).unwrap();
    let trace = Arc::new(Trace::default());
    let layout = rt
        .generate(bedroom_with_lamps(), Arc::clone(&trace))
        .await
        .unwrap();
    (layout, trace.events())
}

fn object<'l>(layout: &'l Layout, name: &str) -> &'l PlacedObject {
    layout
        .object(name)
        .unwrap_or_else(|| panic!("{name} not placed: {:?}", layout.dropped))
}

/// Every asset once, nothing colliding in 3D, nothing outside the room.
fn assert_valid(layout: &Layout) {
    let mut names: Vec<&str> = layout
        .objects
        .iter()
        .map(|o| o.name.as_str())
        .chain(layout.dropped.iter().map(|d| d.name.as_str()))
        .collect();
    names.sort_unstable();
    let mut expected: Vec<String> = bedroom_with_lamps()
        .assets
        .iter()
        .map(|a| a.name.clone())
        .collect();
    expected.sort_unstable();
    assert_eq!(names, expected, "every asset exactly once");
    let m = measure(layout);
    assert_eq!(m.collision_pct, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.oob_pct, 0.0);
}

#[tokio::test]
async fn an_external_designer_puts_lamps_on_nightstands_and_a_painting_on_a_wall() {
    let (layout, events) = run_with("good").await;
    assert_valid(&layout);
    assert!(
        layout.stats.fallbacks.is_empty(),
        "{:?}",
        layout.stats.fallbacks
    );
    for (lamp, stand) in [("lamp-0", "nightstand-0"), ("lamp-1", "nightstand-1")] {
        let l = object(&layout, lamp);
        let s = object(&layout, stand);
        assert_eq!(l.on.as_deref(), Some(stand), "{l:?}");
        assert_eq!(l.elevation, s.top(), "{l:?} stands on {s:?}");
        assert_eq!(l.position, s.position, "{l:?} in the middle of {s:?}");
        assert_eq!(l.wall, None);
    }
    let p = object(&layout, "painting-0");
    assert_eq!(p.wall, Some(0), "{p:?}");
    assert_eq!(p.elevation, 120.0, "{p:?}");
    assert_eq!(p.position, [200.0, 2.1], "{p:?}");
    assert_eq!(p.on, None);
    // The trace's designer replies show what holds each piece, as the agent said it.
    let said: String = events
        .iter()
        .filter(|e| e.role == "designer" && e.kind == TraceKind::Reply)
        .map(|e| e.detail.to_string())
        .collect();
    assert!(
        said.contains(r#"{"elevation":55.0,"name":"lamp-0","on":"nightstand-0","position":[90.0,20.0],"rotation":0.0}"#),
        "{said}"
    );
    assert!(
        said.contains(r#""name":"painting-0","position":[200.0,2.1],"rotation":0.0,"wall":0}"#),
        "{said}"
    );
    // A floor piece shows as it always did.
    assert!(
        said.contains(r#"{"name":"bed-0","position":[200.0,105.0],"rotation":0.0}"#),
        "{said}"
    );
}

#[tokio::test]
async fn an_unknown_support_or_a_wall_the_room_lacks_is_refused() {
    for (mode, why) in [
        (
            "bad-on",
            r#""lamp-0" stands on "ghost-9", which is not another object of the scene"#,
        ),
        (
            "bad-wall",
            r#""painting-0" hangs on wall 7; the room has 4"#,
        ),
    ] {
        let (layout, events) = run_with(mode).await;
        assert_valid(&layout);
        let refused: Vec<String> = events
            .iter()
            .filter(|e| e.role == "designer" && e.kind == TraceKind::Error)
            .map(|e| e.detail.to_string())
            .collect();
        assert!(
            refused
                .iter()
                .any(|d| d.contains(&why.replace('"', "\\\""))),
            "{mode}: {refused:?}"
        );
        assert!(
            layout
                .stats
                .fallbacks
                .iter()
                .any(|f| f.starts_with("designer: process -> rules") && f.contains(why)),
            "{mode}: {:?}",
            layout.stats.fallbacks
        );
        // Nothing of the refused reply stands: no object rests on the ghost or on wall 7.
        assert!(
            layout
                .objects
                .iter()
                .all(|o| o.on.as_deref() != Some("ghost-9") && o.wall != Some(7)),
            "{mode}: {:?}",
            layout.objects
        );
    }
}
