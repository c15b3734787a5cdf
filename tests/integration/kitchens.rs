//! Kitchens by the default graph: the work pieces (counters, stove, sink, fridge, dishwasher)
//! form one run, and the dishwasher stands beside the sink on its wall.

use std::path::Path;

use serde_json::Value;

use crate::harness::{generate, stderr};

/// The layout the default graph makes of `bench/<scene>.json`, as JSON objects by name.
fn furnish(scene: &str) -> Vec<Value> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("layout.json");
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bench")
        .join(format!("{scene}.json"));
    let o = generate(&path, &out, &[]);
    assert!(o.status.success(), "{scene}: {}", stderr(&o));
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    layout["objects"].as_array().unwrap().clone()
}

/// The axis-aligned box (min x, min y, max x, max y) of a placed object turned by a right angle.
fn bounds(o: &Value) -> [f64; 4] {
    let (x, y) = (
        o["position"][0].as_f64().unwrap(),
        o["position"][1].as_f64().unwrap(),
    );
    let (w, d) = (
        o["size"][0].as_f64().unwrap(),
        o["size"][1].as_f64().unwrap(),
    );
    let turned = (o["rotation"].as_f64().unwrap() / 90.0).round() as i64 % 2 != 0;
    let (hw, hd) = if turned {
        (d / 2.0, w / 2.0)
    } else {
        (w / 2.0, d / 2.0)
    };
    [x - hw, y - hd, x + hw, y + hd]
}

/// The gap in cm between two boxes (0 when they touch).
fn gap(a: [f64; 4], b: [f64; 4]) -> f64 {
    let dx = (a[0] - b[2]).max(b[0] - a[2]).max(0.0);
    let dy = (a[1] - b[3]).max(b[1] - a[3]).max(0.0);
    dx.hypot(dy)
}

#[test]
fn a_kitchen_is_one_run_with_the_dishwasher_beside_the_sink() {
    for (scene, sink) in [
        ("scenes/kitchen-02", "kitchen sink-0"),
        ("patterns/workzone-triangle", "sink cabinet-0"),
    ] {
        let objects = furnish(scene);
        let get = |n: &str| objects.iter().find(|o| o["name"] == n).unwrap();
        let (s, dw) = (get(sink), get("dishwasher-0"));
        assert_eq!(
            s["rotation"], dw["rotation"],
            "{scene}: sink and dishwasher face one way"
        );
        let g = gap(bounds(s), bounds(dw));
        assert!(
            g <= 5.0,
            "{scene}: the dishwasher stands {g:.0} cm from the sink"
        );
        // Every work piece within a metre of another one: one run, not islands.
        let work: Vec<&Value> = objects
            .iter()
            .filter(|o| {
                let c = o["category"].as_str().unwrap();
                [
                    "kitchen counter",
                    "stove",
                    "refrigerator",
                    "kitchen sink",
                    "sink cabinet",
                    "dishwasher",
                ]
                .contains(&c)
            })
            .collect();
        for a in &work {
            let near = work
                .iter()
                .filter(|b| b["name"] != a["name"])
                .map(|b| gap(bounds(a), bounds(b)))
                .fold(f64::INFINITY, f64::min);
            assert!(
                near <= 100.0,
                "{scene}: {} stands {near:.0} cm from the rest",
                a["name"]
            );
        }
    }
}
