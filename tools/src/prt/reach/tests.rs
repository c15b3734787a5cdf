//! The reach repair's tests: layouts that are valid as given but wall a piece in, in rooms with
//! a door, and what the repair moves to free it.

use super::*;
use crate::prt::tests::properties::check_valid;
use crate::prt::tests::{obj, walls};
use disco_core::metrics::{REACH_CELL_CM, unreachable_objects};
use disco_core::plan::{Relation, RelationSpec};
use disco_core::room::{Door, Window};

/// `plan` with `subject` asked to stand beside `target`.
fn beside(mut plan: Plan, subject: &str, target: &str) -> Plan {
    let c = plan.constraints.entry(subject.into()).or_default();
    c.relations.push(RelationSpec {
        relation: Relation::SideOf,
        target: target.into(),
    });
    plan
}

/// Where `name` stands in `objects`.
fn pose_of(objects: &[PlacedObject], name: &str) -> ([f64; 2], f64) {
    let o = objects.iter().find(|o| o.name == name).expect("placed");
    (o.position, o.rotation)
}

/// Refines `objects` and checks what every PRT result must keep (the shared validity check:
/// inside, nothing colliding, every asset once) and that nothing was dropped; returns the
/// refined objects.
fn refine_checked(room: &Room, objects: &[PlacedObject], plan: &Plan) -> Vec<PlacedObject> {
    let r = PhysicalRefiner::default().refine(room, objects, plan);
    check_valid(room, objects, &r).expect("a valid result");
    assert!(r.dropped.is_empty(), "{:?}", r.dropped);
    r.objects
}

/// A bed against the bottom wall of a narrow room, its nightstand on its left, and a desk
/// standing 20 cm off the bed's corner, sealing the nightstand's corner; the plan puts the bed
/// and the nightstand on walls, the nightstand beside the bed.
fn sealed_nightstand() -> ([PlacedObject; 3], Plan) {
    let objects = [
        obj("bed-0", [160.0, 200.0, 60.0], [200.0, 100.0], 0.0),
        obj("nightstand-0", [50.0, 40.0, 55.0], [85.0, 20.0], 0.0),
        obj("desk-0", [100.0, 60.0, 75.0], [50.0, 230.0], 0.0),
    ];
    let plan = beside(walls(&["bed-0", "nightstand-0"]), "nightstand-0", "bed-0");
    (objects, plan)
}

#[test]
fn a_piece_boxing_a_nightstand_in_moves_though_nothing_collided() {
    // Nothing collides and nothing is off its wall, so the placement moves nothing; the desk
    // is in the way.
    let mut room = Room::rect(300.0, 350.0);
    room.doors.push(Door::new(2, 150.0, 80.0));
    let (objects, plan) = sealed_nightstand();
    assert_eq!(
        unreachable_objects(&room, &objects, REACH_CELL_CM),
        vec!["nightstand-0".to_string()],
        "the layout as given walls the nightstand in"
    );

    let after = refine_checked(&room, &objects, &plan);

    assert!(
        unreachable_objects(&room, &after, REACH_CELL_CM).is_empty(),
        "{after:?}"
    );
    // The nightstand keeps its place by the bed (no other pose beside it is free); the desk,
    // which blocks the way and is asked nothing, is the one that moves.
    for name in ["bed-0", "nightstand-0"] {
        let given = objects.iter().find(|o| o.name == name).expect("given");
        assert_eq!(
            pose_of(&after, name),
            (given.position, given.rotation),
            "{name}"
        );
    }
    assert_ne!(pose_of(&after, "desk-0").0, [50.0, 230.0]);
}

#[test]
fn a_nightstand_boxed_in_behind_its_twin_leaves_the_wall_but_not_the_bed() {
    // The bed's right side holds both nightstands, one walled in behind the other; on its left
    // the walls are windows, so no pose against a wall beside the bed is left. The last resort
    // puts the nightstand beside the bed under the window (it is lower than the sill).
    let mut room = Room::rect(300.0, 300.0);
    room.doors.push(Door::new(2, 150.0, 80.0));
    let window = |wall, at, width| Window {
        wall,
        at,
        width,
        sill: 90.0,
        height: 120.0,
    };
    room.windows.push(window(0, 27.5, 55.0));
    room.windows.push(window(3, 200.0, 200.0));
    let objects = [
        obj("bed-0", [160.0, 200.0, 60.0], [140.0, 100.0], 0.0),
        obj("nightstand-0", [50.0, 40.0, 55.0], [280.0, 65.0], 270.0),
        obj("nightstand-1", [50.0, 40.0, 55.0], [245.0, 20.0], 0.0),
    ];
    let plan = walls(&["bed-0", "nightstand-0", "nightstand-1"]);
    let plan = beside(plan, "nightstand-0", "bed-0");
    let plan = beside(plan, "nightstand-1", "bed-0");
    assert_eq!(
        unreachable_objects(&room, &objects, REACH_CELL_CM),
        vec!["nightstand-1".to_string()],
        "the layout as given walls the second nightstand in"
    );

    let after = refine_checked(&room, &objects, &plan);

    assert!(
        unreachable_objects(&room, &after, REACH_CELL_CM).is_empty(),
        "{after:?}"
    );
    let fp = |name: &str| {
        after
            .iter()
            .find(|o| o.name == name)
            .expect("placed")
            .footprint()
    };
    assert!(
        disco_core::relations::side_of(&fp("nightstand-1"), &fp("bed-0")),
        "the moved nightstand stays beside the bed: {:?}",
        pose_of(&after, "nightstand-1")
    );
    assert_eq!(pose_of(&after, "bed-0"), ([140.0, 100.0], 0.0));
}

#[test]
fn without_a_door_a_walled_in_piece_is_left_where_it_stands() {
    // The sealed nightstand without a door: reach counts the largest free region, and the
    // repair leaves rooms without doors alone.
    let room = Room::rect(300.0, 350.0);
    let (objects, plan) = sealed_nightstand();
    let after = refine_checked(&room, &objects, &plan);
    assert_eq!(after, objects);
}
