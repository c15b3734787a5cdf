//! Kitchens by the default graph: the work pieces (counters, stove, sink, fridge, dishwasher)
//! form one run, and the dishwasher stands beside the sink on its wall.

use std::path::Path;

use disco_layout::Layout;
use disco_layout::layout::PlacedObject;

use crate::harness::{generate, stderr};

/// The layout the default graph makes of `bench/<scene>.json`.
fn furnish(scene: &str) -> Layout {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("layout.json");
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bench")
        .join(format!("{scene}.json"));
    let o = generate(&path, &out, &[]);
    assert!(o.status.success(), "{scene}: {}", stderr(&o));
    serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap()
}

/// The gap in cm between two placed objects' boxes (0 when they touch).
fn gap(a: &PlacedObject, b: &PlacedObject) -> f64 {
    a.footprint().aabb().gap(&b.footprint().aabb())
}

#[test]
fn a_kitchen_is_one_run_with_the_dishwasher_beside_the_sink() {
    for (scene, sink) in [
        ("scenes/kitchen-02", "kitchen sink-0"),
        ("patterns/workzone-triangle", "sink cabinet-0"),
    ] {
        let layout = furnish(scene);
        let get = |n: &str| layout.objects.iter().find(|o| o.name == n).unwrap();
        let (s, dw) = (get(sink), get("dishwasher-0"));
        assert_eq!(
            s.rotation, dw.rotation,
            "{scene}: sink and dishwasher face one way"
        );
        let g = gap(s, dw);
        assert!(
            g <= 5.0,
            "{scene}: the dishwasher stands {g:.0} cm from the sink"
        );
        // Every work piece within a metre of another one: one run, not islands.
        let work: Vec<&PlacedObject> = layout
            .objects
            .iter()
            .filter(|o| {
                [
                    "kitchen counter",
                    "stove",
                    "refrigerator",
                    "kitchen sink",
                    "sink cabinet",
                    "dishwasher",
                ]
                .contains(&o.category.as_str())
            })
            .collect();
        for a in &work {
            let near = work
                .iter()
                .filter(|b| b.name != a.name)
                .map(|b| gap(a, b))
                .fold(f64::INFINITY, f64::min);
            assert!(
                near <= 100.0,
                "{scene}: {} stands {near:.0} cm from the rest",
                a.name
            );
        }
    }
}
