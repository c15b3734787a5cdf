//! The PRT's tests: each repair (wall alignment, out of bounds, collisions, quarter turns, drops)
//! on small hand-made rooms, and properties over random noisy scenes: the result is always valid
//! and accounts for every object.

use super::*;
use disco_core::metrics::measure;
use disco_core::plan::ObjectConstraints;
use disco_core::synth;

/// A placed object whose category is its name up to the first dash (shared with the polygon
/// tests and the SRT's).
pub(crate) fn obj(name: &str, size: [f64; 3], pos: [f64; 2], rot: f64) -> PlacedObject {
    PlacedObject {
        name: name.into(),
        category: name.split('-').next().unwrap_or(name).into(),
        size,
        position: pos,
        rotation: rot,
        ..Default::default()
    }
}

/// A plan that puts each of `names` against a wall (shared with the polygon tests).
pub(super) fn walls(names: &[&str]) -> Plan {
    let mut plan = Plan::default();
    for n in names {
        plan.constraints.insert(
            n.to_string(),
            ObjectConstraints {
                against_wall: true,
                ..Default::default()
            },
        );
    }
    plan
}

const ROOM: Room = Room::rect(400.0, 350.0);

fn refine(objects: &[PlacedObject], plan: &Plan) -> Refined {
    PhysicalRefiner::default().refine(&ROOM, objects, plan)
}

fn pose(r: &Refined, name: &str) -> ([f64; 2], f64) {
    let o = r.objects.iter().find(|o| o.name == name).expect("placed");
    (o.position, o.rotation)
}

#[test]
fn a_valid_layout_is_left_alone() {
    let (scene, layout) = synth::bedroom();
    let r = PhysicalRefiner::default().refine(&scene.room, &layout.objects, &layout.plan);
    assert!(r.dropped.is_empty());
    assert!(
        r.moves
            .iter()
            .all(|m| m.displacement_cm == 0.0 && !m.rotated),
        "{:?}",
        r.moves
    );
    assert_eq!(r.objects, layout.objects);
}

#[test]
fn against_wall_object_is_turned_and_pulled_to_the_nearest_wall() {
    let bed = obj("bed-0", [160.0, 210.0, 100.0], [190.0, 230.0], 170.0);
    let r = refine(&[bed], &walls(&["bed-0"]));
    // Nearest wall to (190, 230) is the top one (120 cm away): back flush at y = 350.
    assert_eq!(pose(&r, "bed-0"), ([190.0, 245.0], 180.0));
    assert!((r.moves[0].displacement_cm - 15.0).abs() < 1e-9);
    assert!(r.moves[0].rotated);
    assert!(r.notes.is_empty());
}

#[test]
fn out_of_bounds_object_moves_the_least_distance_inside() {
    let r = refine(
        &[obj("cabinet-0", [100.0, 50.0, 90.0], [380.0, -10.0], 0.0)],
        &Plan::default(),
    );
    assert_eq!(pose(&r, "cabinet-0"), ([350.0, 25.0], 0.0));
}

#[test]
fn the_smaller_object_of_a_colliding_pair_moves() {
    let table = obj("table-0", [160.0, 90.0, 75.0], [200.0, 175.0], 0.0);
    let stool = obj("stool-0", [40.0, 40.0, 60.0], [200.0, 230.0], 0.0);
    let r = refine(&[stool, table], &Plan::default());
    assert_eq!(pose(&r, "table-0"), ([200.0, 175.0], 0.0));
    // Nearest free spot: flush above the table's top edge (y = 220 + 20).
    assert_eq!(pose(&r, "stool-0"), ([200.0, 240.0], 0.0));
    assert_eq!(measure_layout(&r).collision_pct, 0.0);
}

#[test]
fn full_wall_sends_the_object_to_another_wall() {
    // The bottom wall of a 400 cm room is filled by two 200 cm cabinets.
    let a = obj("cabinet-0", [200.0, 60.0, 90.0], [100.0, 30.0], 0.0);
    let b = obj("cabinet-1", [200.0, 60.0, 90.0], [300.0, 30.0], 0.0);
    let c = obj("shelf-0", [80.0, 40.0, 180.0], [200.0, 40.0], 0.0);
    let r = refine(&[a, b, c], &walls(&["cabinet-0", "cabinet-1", "shelf-0"]));
    let (pos, rot) = pose(&r, "shelf-0");
    let fp = r.objects[2].footprint();
    assert!(fp.against_wall(&ROOM).is_some(), "{pos:?} {rot}");
    assert_ne!(rot, 0.0, "the bottom wall is full");
    assert_eq!(measure_layout(&r).collision_pct, 0.0);
}

#[test]
fn no_wall_left_means_placed_anyway_with_a_note() {
    // A 100 x 100 room ringed by four 100 x 20 benches: the wall stretches are all taken.
    let room = Room::rect(100.0, 100.0);
    let mut objects = vec![
        obj("bench-0", [60.0, 20.0, 45.0], [40.0, 10.0], 0.0),
        obj("bench-1", [60.0, 20.0, 45.0], [90.0, 40.0], 270.0),
        obj("bench-2", [60.0, 20.0, 45.0], [60.0, 90.0], 180.0),
        obj("bench-3", [60.0, 20.0, 45.0], [10.0, 60.0], 90.0),
    ];
    objects.push(obj("lamp-0", [30.0, 30.0, 150.0], [50.0, 50.0], 0.0));
    let plan = walls(&["bench-0", "bench-1", "bench-2", "bench-3", "lamp-0"]);
    let r = PhysicalRefiner::default().refine(&room, &objects, &plan);
    assert!(r.dropped.is_empty());
    assert_eq!(r.objects[4].position, [50.0, 50.0]);
    assert_eq!(r.notes.len(), 1);
    assert!(
        r.notes[0].starts_with("lamp-0: no free stretch of wall"),
        "{:?}",
        r.notes
    );
}

#[test]
fn a_quarter_turn_is_tried_before_dropping() {
    let room = Room::rect(100.0, 300.0);
    let r = PhysicalRefiner::default().refine(
        &room,
        &[obj("sofa-0", [200.0, 80.0, 80.0], [50.0, 150.0], 0.0)],
        &Plan::default(),
    );
    assert!(r.dropped.is_empty());
    assert_eq!(r.objects[0].rotation, 90.0);
    assert!(r.notes[0].contains("turned to 90° to fit"), "{:?}", r.notes);
}

#[test]
fn drops_only_what_has_no_place_and_says_why() {
    let room = Room::rect(100.0, 100.0);
    let objects = [
        obj("crate-0", [100.0, 100.0, 50.0], [50.0, 50.0], 0.0),
        obj("crate-1", [50.0, 50.0, 50.0], [50.0, 50.0], 0.0),
        obj("piano-0", [150.0, 120.0, 100.0], [50.0, 50.0], 0.0),
    ];
    let r = PhysicalRefiner::default().refine(&room, &objects, &Plan::default());
    assert_eq!(r.objects.len(), 1);
    assert_eq!(r.objects[0].name, "crate-0");
    let reasons: Vec<(&str, &str)> = r
        .dropped
        .iter()
        .map(|d| (d.name.as_str(), d.reason.as_str()))
        .collect();
    assert!(
        reasons[0].0 == "crate-1" && reasons[0].1.starts_with("no collision-free place"),
        "{reasons:?}"
    );
    assert!(
        reasons[1].0 == "piano-0" && reasons[1].1.contains("does not fit the 100 x 100 cm room"),
        "{reasons:?}"
    );
}

#[test]
fn rugs_lie_under_furniture_but_not_on_each_other() {
    let bed = obj("bed-0", [160.0, 210.0, 100.0], [200.0, 245.0], 180.0);
    let rug = obj("rug-0", [200.0, 140.0, 1.0], [200.0, 150.0], 0.0);
    let mat = obj("mat-0", [80.0, 50.0, 2.0], [200.0, 150.0], 0.0);
    let r = refine(&[bed, rug, mat], &Plan::default());
    assert_eq!(pose(&r, "bed-0").0, [200.0, 245.0]);
    assert_eq!(pose(&r, "rug-0").0, [200.0, 150.0]);
    let mat = r.objects[2].footprint();
    assert!(
        !mat.collides(&r.objects[1].footprint()),
        "the mat moved off the rug"
    );
}

#[test]
fn settled_objects_keep_their_place() {
    let desk = obj("desk-0", [120.0, 60.0, 75.0], [200.0, 30.0], 0.0);
    let cabinet = obj("cabinet-0", [200.0, 60.0, 90.0], [200.0, 60.0], 0.0);
    let settled: HashSet<String> = ["desk-0".to_string()].into();
    let r = PhysicalRefiner::default().refine_settled(
        &ROOM,
        &[desk.clone(), cabinet.clone()],
        &Plan::default(),
        &settled,
    );
    assert_eq!(
        pose(&r, "desk-0").0,
        [200.0, 30.0],
        "the settled desk stays"
    );
    let r = refine(&[desk, cabinet], &Plan::default());
    assert_eq!(
        pose(&r, "cabinet-0").0,
        [200.0, 60.0],
        "without precedence the larger cabinet stays"
    );
}

#[test]
fn non_finite_positions_start_from_the_centre() {
    let r = refine(
        &[obj("box-0", [50.0, 50.0, 50.0], [f64::NAN, 3.0], 0.0)],
        &Plan::default(),
    );
    assert_eq!(pose(&r, "box-0").0, [200.0, 175.0]);
}

fn measure_layout(r: &Refined) -> disco_core::metrics::Metrics {
    measure(&Layout {
        id: "t".into(),
        room: ROOM,
        objects: r.objects.clone(),
        dropped: r.dropped.clone(),
        plan: Plan::default().into(),
        stats: Default::default(),
    })
}

use disco_core::layout::Layout;

pub(super) mod properties {
    use proptest::prelude::*;

    use super::*;

    /// A room, objects covering at most `max_cover` of its floor (at least one object), noisy
    /// poses (some outside the room, some tilted), and random against-wall flags.
    pub(in crate::prt) fn scene(
        max_cover: f64,
        min_cover: f64,
    ) -> impl Strategy<Value = (Room, Vec<PlacedObject>, Plan)> {
        (150.0..900.0f64, 150.0..900.0f64, any::<u64>()).prop_map(move |(w, d, seed)| {
            let room = Room::rect(w.round(), d.round());
            let mut rng = fastrand::Rng::with_seed(seed);
            let side = room.width.min(room.depth);
            let mut objects = Vec::new();
            let mut plan = Plan::default();
            let mut covered = 0.0;
            let target = min_cover + rng.f64() * (max_cover - min_cover);
            while objects.is_empty() || covered < target * room.area() {
                let ow = (10.0 + rng.f64() * (side * 0.5 - 10.0)).round();
                let od = (10.0 + rng.f64() * (side * 0.5 - 10.0)).round();
                if covered + ow * od > max_cover * room.area() {
                    if objects.is_empty() {
                        continue;
                    }
                    break;
                }
                covered += ow * od;
                let flat = rng.f64() < 0.1;
                let name = format!("thing-{}", objects.len());
                let rotation = if rng.bool() {
                    90.0 * f64::from(rng.u8(0..4))
                } else {
                    rng.f64() * 360.0
                };
                objects.push(PlacedObject {
                    name: name.clone(),
                    category: "thing".into(),
                    size: [ow, od, if flat { 1.0 } else { 80.0 }],
                    position: [
                        -0.2 * room.width + rng.f64() * 1.4 * room.width,
                        -0.2 * room.depth + rng.f64() * 1.4 * room.depth,
                    ],
                    rotation,
                    ..Default::default()
                });
                if rng.f64() < 0.4 {
                    plan.constraints.insert(
                        name,
                        ObjectConstraints {
                            against_wall: true,
                            ..Default::default()
                        },
                    );
                }
            }
            (room, objects, plan)
        })
    }

    /// Every rule of a valid result: inside, no collisions (floor coverings among themselves
    /// too), every asset exactly once with its size unchanged, dropped ones with a reason.
    pub(in crate::prt) fn check_valid(
        room: &Room,
        input: &[PlacedObject],
        r: &Refined,
    ) -> Result<(), TestCaseError> {
        let layout = Layout {
            id: "p".into(),
            room: room.clone(),
            objects: r.objects.clone(),
            dropped: r.dropped.clone(),
            plan: Plan::default().into(),
            stats: Default::default(),
        };
        let m = measure(&layout);
        prop_assert_eq!(m.collision_pct, 0.0, "collisions: {:?}", m.colliding_pairs);
        prop_assert!(m.oob_pct < 1e-6, "OOB {}", m.oob_pct);
        for o in &r.objects {
            prop_assert!(o.footprint().inside(room), "{} outside", o.name);
        }
        // Floor coverings must not overlap each other either.
        let flat: Vec<_> = r
            .objects
            .iter()
            .filter(|o| o.is_flat())
            .map(|o| o.footprint())
            .collect();
        for (i, a) in flat.iter().enumerate() {
            for b in &flat[i + 1..] {
                prop_assert!(!a.collides(b));
            }
        }
        // Every asset exactly once, sizes unchanged, dropped ones with a reason.
        let mut names: Vec<&str> = r
            .objects
            .iter()
            .map(|o| o.name.as_str())
            .chain(r.dropped.iter().map(|d| d.name.as_str()))
            .collect();
        names.sort_unstable();
        let mut expected: Vec<&str> = input.iter().map(|o| o.name.as_str()).collect();
        expected.sort_unstable();
        prop_assert_eq!(names, expected);
        for o in &r.objects {
            let orig = input.iter().find(|i| i.name == o.name).unwrap();
            prop_assert_eq!(o.size, orig.size);
        }
        prop_assert!(r.dropped.iter().all(|d| !d.reason.is_empty()));
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        #[test]
        fn up_to_forty_percent_cover_is_always_fully_placed((room, objects, plan) in scene(0.40, 0.05)) {
            let refiner = PhysicalRefiner::default();
            let r = refiner.refine(&room, &objects, &plan);
            check_valid(&room, &objects, &r)?;
            prop_assert!(r.dropped.is_empty(), "dropped {:?}", r.dropped);
            prop_assert_eq!(&refiner.refine(&room, &objects, &plan), &r, "not deterministic");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

        #[test]
        fn overfull_rooms_stay_valid_and_account_for_everything((room, objects, plan) in scene(1.5, 0.6)) {
            let r = PhysicalRefiner::default().refine(&room, &objects, &plan);
            check_valid(&room, &objects, &r)?;
        }
    }
}

#[test]
fn a_piece_pushed_in_front_of_a_cabinet_does_not_wall_it_in() {
    use disco_core::metrics::{REACH_CELL_CM, unreachable_objects};
    // A crate overlapping a cabinet in the corner: its nearest valid point is flush against the
    // cabinet's front, across all of it, where nobody could open the cabinet.
    let mut room = ROOM;
    room.doors.push(disco_core::room::Door::new(2, 200.0, 90.0));
    let cabinet = obj("cabinet-0", [100.0, 45.0, 90.0], [50.0, 22.5], 0.0);
    let crate_ = obj("crate-0", [120.0, 35.0, 50.0], [60.0, 60.0], 0.0);
    let pushed = obj("crate-0", [120.0, 35.0, 50.0], [60.0, 62.5], 0.0);
    assert_eq!(
        unreachable_objects(&room, &[cabinet.clone(), pushed], REACH_CELL_CM),
        vec!["cabinet-0".to_string()],
        "the nearest valid point walls the cabinet in"
    );
    let r = PhysicalRefiner::default().refine(&room, &[cabinet.clone(), crate_], &Plan::default());
    assert!(r.dropped.is_empty());
    assert_eq!(
        pose(&r, "cabinet-0"),
        (cabinet.position, 0.0),
        "the cabinet stays"
    );
    let (at, _) = pose(&r, "crate-0");
    assert_ne!(at, [60.0, 62.5]);
    assert!(
        unreachable_objects(&room, &r.objects, REACH_CELL_CM).is_empty(),
        "crate at {at:?}"
    );
    let m = measure(&Layout {
        id: "t".into(),
        room: room.clone(),
        objects: r.objects.clone(),
        dropped: r.dropped.clone(),
        plan: Plan::default().into(),
        stats: Default::default(),
    });
    assert_eq!((m.collision_pct, m.oob_pct), (0.0, 0.0));
}
