//! The rule SRT's tests.

use std::sync::Arc;

use super::*;
use disco_core::metrics::unreachable_objects;
use disco_core::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
use disco_core::roles::{Answer, Question, SceneContext};
use disco_core::scene::{Asset, Room, SceneSpec};

fn obj(name: &str, size: [f64; 3], pos: [f64; 2], rot: f64) -> PlacedObject {
    PlacedObject {
        name: name.into(),
        category: name.split('-').next().unwrap_or(name).into(),
        size,
        position: pos,
        rotation: rot,
    }
}

/// A cabinet in a corner, a wardrobe beside it, and a crate across the room that the plan
/// wants in front of the cabinet: every pose there leaves a strip of 10 cm before the cabinet.
fn crate_before_a_cabinet() -> (SrtRequest, ConstraintKind) {
    let room = Room::rect(400.0, 300.0);
    let objects = vec![
        obj("cabinet-0", [100.0, 45.0, 90.0], [50.0, 22.5], 0.0),
        obj("wardrobe-0", [60.0, 100.0, 200.0], [130.0, 50.0], 0.0),
        obj("crate-0", [100.0, 35.0, 50.0], [300.0, 200.0], 0.0),
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
        plan: plan.clone(),
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
        ctx: SceneContext {
            scene: Arc::new(scene),
            plan: Arc::new(plan),
        },
        layout,
        failed: vec![(question, answer)],
        movable: vec!["crate-0".into()],
        render: None,
    };
    (req, kind)
}

#[test]
fn a_move_that_would_wall_the_cabinet_in_is_not_made() {
    let (req, kind) = crate_before_a_cabinet();
    let layout = &req.layout;
    assert!(unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM).is_empty());
    let crate_ = layout.object("crate-0").unwrap();
    let cands = candidates(layout, crate_, &kind);
    assert!(!cands.is_empty());
    // Each pose that meets the relation walls the cabinet in: the move the SRT used to make.
    let mut meeting = 0;
    for p in &cands {
        let mut trial = layout.clone();
        set_pose(&mut trial, "crate-0", *p);
        if check_one(&trial, "crate-0", &kind) {
            meeting += 1;
            assert!(
                unreachable_objects(&trial.room, &trial.objects, REACH_CELL_CM)
                    .contains(&"cabinet-0".to_string()),
                "{p:?}"
            );
        }
    }
    assert!(meeting > 0, "some pose meets the relation");
    assert!(RuleSrt.repair(&req).is_empty(), "the crate stays");
}

#[test]
fn a_move_that_walls_nothing_in_is_made() {
    let (mut req, kind) = crate_before_a_cabinet();
    // Without the wardrobe the cabinet is reached from its side.
    req.layout.objects.retain(|o| o.name != "wardrobe-0");
    let moved = RuleSrt.repair(&req);
    assert_eq!(moved.len(), 1);
    let mut after = req.layout.clone();
    after.objects.retain(|o| o.name != "crate-0");
    after.objects.extend(moved);
    assert!(
        check_one(&after, "crate-0", &kind),
        "in front of the cabinet"
    );
    assert!(unreachable_objects(&after.room, &after.objects, REACH_CELL_CM).is_empty());
}
