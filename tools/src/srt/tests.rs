//! The rule SRT's tests.

use std::sync::Arc;

use super::*;
use crate::prt::tests::obj;
use disco_core::layout::PlacedObject;
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

/// The L-shaped home office of `bench/requests/r02-home-office-L`: main area below, a recess
/// top left, the door on the right wall (so wall 5, the left one, is opposite it).
fn l_office(
    objects: Vec<PlacedObject>,
    subject: &str,
    place: Place,
    against_wall: bool,
) -> SrtRequest {
    let mut room = Room::from_polygon(vec![
        [0.0, 0.0],
        [500.0, 0.0],
        [500.0, 250.0],
        [280.0, 250.0],
        [280.0, 420.0],
        [0.0, 420.0],
    ]);
    room.doors.push(disco_core::room::Door::new(1, 125.0, 85.0));
    let mut plan = Plan::default();
    plan.constraints.insert(
        subject.into(),
        ObjectConstraints {
            place: Some(place.clone()),
            against_wall,
            ..Default::default()
        },
    );
    let scene = SceneSpec {
        id: "t".into(),
        prompt: String::new(),
        room_type: "home office".into(),
        room: room.clone(),
        assets: objects
            .iter()
            .map(|o| Asset::new(&o.name, &o.category, o.size))
            .collect(),
    };
    let kind = ConstraintKind::Place(place);
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
        text: format!("Is it true that {subject} stands {}?", kind_words(&kind)),
        subject: Some(subject.into()),
        constraint: Some(kind),
    };
    let answer = Answer {
        id: 0,
        yes: false,
        reason: "measured: elsewhere".into(),
    };
    SrtRequest {
        ctx: SceneContext::new(Arc::new(scene), Arc::new(plan)),
        layout,
        failed: vec![(question, answer)],
        movable: vec![subject.into()],
        render: None,
    }
}

fn kind_words(kind: &ConstraintKind) -> String {
    match kind {
        ConstraintKind::Place(p) => p.to_string(),
        _ => String::new(),
    }
}

#[test]
fn a_piece_out_of_its_zone_is_moved_into_it_clear_of_the_others() {
    let place = Place {
        zone: Some("recess".into()),
        ..Default::default()
    };
    let req = l_office(
        vec![
            obj("armchair", [80.0, 80.0, 90.0], [400.0, 100.0], 0.0),
            obj("desk", [140.0, 70.0, 75.0], [150.0, 300.0], 180.0),
        ],
        "armchair",
        place.clone(),
        false,
    );
    let kind = ConstraintKind::Place(place);
    assert!(!check_one(&req.layout, "armchair", &kind));
    let moves = RuleSrt.repair(&req);
    assert_eq!(moves.len(), 1, "{moves:?}");
    let mut after = req.layout.clone();
    after.objects[0] = moves[0].clone();
    assert!(check_one(&after, "armchair", &kind), "{:?}", moves[0]);
    let (a, d) = (after.objects[0].footprint(), after.objects[1].footprint());
    assert!(a.inside(&after.room) && !a.collides(&d), "{:?}", moves[0]);
}

#[test]
fn a_piece_on_the_wrong_wall_goes_to_the_wall_its_place_names() {
    let place = Place {
        wall: Some(disco_core::room::analysis::WallRole::OppositeDoor),
        ..Default::default()
    };
    // A bookshelf with its back on the bottom wall; the plan wants it against a wall, the one
    // opposite the door (the left one, x = 0).
    let req = l_office(
        vec![obj("bookshelf-0", [80.0, 35.0, 190.0], [300.0, 17.5], 0.0)],
        "bookshelf-0",
        place.clone(),
        true,
    );
    let kind = ConstraintKind::Place(place);
    assert!(!check_one(&req.layout, "bookshelf-0", &kind));
    let moves = RuleSrt.repair(&req);
    assert_eq!(moves.len(), 1, "{moves:?}");
    let mut after = req.layout.clone();
    after.objects[0] = moves[0].clone();
    assert!(check_one(&after, "bookshelf-0", &kind), "{:?}", moves[0]);
    // Flush on the left wall, turned into the room (front to +x).
    assert!((moves[0].position[0] - 17.5).abs() < 1.0, "{:?}", moves[0]);
    assert_eq!(moves[0].rotation, 90.0);
}

#[test]
fn a_piece_asked_to_face_or_stand_near_a_door_is_turned_or_moved_to_it() {
    // The L office: its door on wall 1 (x = 500), centred at y = 125.
    let mut req = l_office(
        vec![obj("printer-0", [50.0, 50.0, 95.0], [100.0, 100.0], 0.0)],
        "printer-0",
        Place::default(),
        false,
    );
    let near = ConstraintKind::Relation {
        relation: Relation::Near,
        target: "door-0".into(),
    };
    let faces = ConstraintKind::Facing {
        target: "door-0".into(),
    };
    let mut plan = (*req.ctx.plan).clone();
    plan.constraints.insert(
        "printer-0".into(),
        ObjectConstraints {
            relations: vec![RelationSpec {
                relation: Relation::Near,
                target: "door-0".into(),
            }],
            facing: Some("door-0".into()),
            ..Default::default()
        },
    );
    req.ctx.plan = Arc::new(plan.clone());
    req.layout.plan = Arc::new(plan);
    assert!(!check_one(&req.layout, "printer-0", &near));
    assert!(!check_one(&req.layout, "printer-0", &faces));
    let question = |id: usize, kind: &ConstraintKind| {
        (
            Question {
                id,
                text: String::new(),
                subject: Some("printer-0".into()),
                constraint: Some(kind.clone()),
            },
            Answer {
                id,
                yes: false,
                reason: "measured".into(),
            },
        )
    };
    req.failed = vec![question(0, &near), question(1, &faces)];
    let moves = RuleSrt.repair(&req);
    assert_eq!(moves.len(), 1, "{moves:?}");
    let mut after = req.layout.clone();
    after.objects[0] = moves[0].clone();
    assert!(check_one(&after, "printer-0", &near), "{:?}", moves[0]);
    assert!(check_one(&after, "printer-0", &faces), "{:?}", moves[0]);
    assert!(after.objects[0].footprint().inside(&after.room));
}
