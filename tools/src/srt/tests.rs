//! The rule SRT's tests.

use std::sync::Arc;

use super::*;
use crate::prt::tests::obj;
use disco_core::metrics::unreachable_objects;
use disco_core::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
use disco_core::roles::{Answer, Question, SceneContext};
use disco_core::scene::{Asset, Room, SceneSpec};

/// A cabinet in a corner, a wardrobe beside it, and a crate above that the plan wants in front
/// of the cabinet: of the poses there, the one straight ahead (the nearest) leaves 30 cm either
/// side of the crate, too little to reach the cabinet; those shifted 20 cm aside leave enough.
fn crate_before_a_cabinet() -> (SrtRequest, ConstraintKind) {
    let mut room = Room::rect(400.0, 300.0);
    room.doors.push(disco_core::room::Door::new(2, 200.0, 90.0));
    let objects = vec![
        obj("cabinet-0", [100.0, 45.0, 90.0], [50.0, 22.5], 0.0),
        obj("wardrobe-0", [60.0, 100.0, 200.0], [130.0, 50.0], 0.0),
        obj("crate-0", [40.0, 35.0, 50.0], [50.0, 250.0], 0.0),
    ];
    let kind = ConstraintKind::Relation {
        relation: Relation::InFrontOf,
        target: "cabinet-0".into(),
    };
    let mut plan = Plan::default();
    plan.constraints.insert(
        "crate-0".into(),
        ObjectConstraints {
            relations: vec![RelationSpec {
                relation: Relation::InFrontOf,
                target: "cabinet-0".into(),
            }],
            ..Default::default()
        },
    );
    let scene = SceneSpec {
        id: "t".into(),
        prompt: String::new(),
        room_type: "storage room".into(),
        room: room.clone(),
        assets: objects
            .iter()
            .map(|o| Asset::new(&o.name, &o.category, o.size))
            .collect(),
    };
    let layout = Layout {
        id: "t".into(),
        room,
        objects,
        dropped: Vec::new(),
        plan: plan.clone().into(),
        stats: Default::default(),
    };
    let question = Question {
        id: 0,
        text: "Is crate-0 in front of cabinet-0?".into(),
        subject: Some("crate-0".into()),
        constraint: Some(kind.clone()),
    };
    let answer = Answer {
        id: 0,
        yes: false,
        reason: "it is across the room".into(),
    };
    let req = SrtRequest {
        ctx: SceneContext::new(Arc::new(scene), Arc::new(plan)),
        layout,
        failed: vec![(question, answer)],
        movable: vec!["crate-0".into()],
        render: None,
    };
    (req, kind)
}

#[test]
fn of_equally_good_moves_one_that_walls_nothing_in_is_made() {
    let (req, kind) = crate_before_a_cabinet();
    let layout = &req.layout;
    assert!(unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM).is_empty());
    // The nearest pose that meets the relation, the move the SRT used to make, walls the
    // cabinet in.
    let mut nearest = layout.clone();
    set_pose(
        &mut nearest,
        "crate-0",
        Pose {
            center: DVec2::new(50.0, 72.5),
            rotation: 0.0,
        },
    );
    assert!(check_one(&nearest, "crate-0", &kind));
    assert_eq!(
        unreachable_objects(&nearest.room, &nearest.objects, REACH_CELL_CM),
        vec!["cabinet-0".to_string()]
    );
    let moved = RuleSrt.repair(&req);
    assert_eq!(moved.len(), 1, "the crate moves");
    let mut after = layout.clone();
    after.objects.retain(|o| o.name != "crate-0");
    after.objects.extend(moved);
    assert!(
        check_one(&after, "crate-0", &kind),
        "in front of the cabinet"
    );
    assert!(unreachable_objects(&after.room, &after.objects, REACH_CELL_CM).is_empty());
}
