//! The rule designer in real rooms: nothing but floor coverings in a door's zone, nothing above
//! a sill in a window's, everything on the polygon's floor.

use std::path::Path;

use super::RuleDesigner;
use crate::rules::planner::RulePlanner;
use disco_core::layout::PlacedObject;
use disco_core::scene::SceneSpec;

/// Every group of `scene` designed in plan order, as the scene loop would (without refinement).
fn design_all(scene: &SceneSpec) -> Vec<PlacedObject> {
    let plan = RulePlanner::new().make_plan(scene);
    let designer = RuleDesigner::new();
    let mut placed: Vec<PlacedObject> = Vec::new();
    for group in &plan.groups {
        let assets: Vec<_> = group.iter().filter_map(|n| scene.asset(n)).collect();
        let out = designer.design_group(scene, &plan, &assets, &placed);
        placed.extend(out);
    }
    placed
}

fn bench_room(name: &str) -> SceneSpec {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../bench/rooms")
        .join(format!("{name}.json"));
    SceneSpec::load(&path).unwrap()
}

#[test]
fn doors_and_windows_stay_clear_in_l_u_and_slanted_rooms() {
    for name in [
        "bedroom-l-01",
        "bedroom-slant-02",
        "living-room-u-02",
        "kitchen-l-03",
        "classroom-t-03",
    ] {
        let scene = bench_room(name);
        let placed = design_all(&scene);
        assert_eq!(placed.len(), scene.assets.len(), "{name}");
        let zones = scene.room.keep_clear();
        assert!(!zones.is_empty(), "{name}");
        for o in &placed {
            let fp = o.footprint();
            assert!(fp.inside(&scene.room), "{name}: {} off the floor", o.name);
            for z in &zones {
                assert!(
                    !fp.intrudes(z, o.size[2]),
                    "{name}: {} in the zone of {:?}",
                    o.name,
                    z.kind
                );
            }
        }
    }
}
