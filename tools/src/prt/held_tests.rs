//! The PRT and objects off the floor: kept when valid, carried with their supports, put back on
//! them, set down on the floor with a note, moved along walls, dropped only with a reason.

use super::tests::obj;
use super::*;
use disco_core::geometry3d;
use disco_core::layout::Layout;
use disco_core::metrics::measure;
use disco_core::room::Door;

fn room() -> Room {
    let mut room = Room::rect(400.0, 350.0);
    room.doors.push(Door::new(0, 300.0, 90.0));
    room
}

fn refine(objects: &[PlacedObject]) -> Refined {
    PhysicalRefiner::default().refine(&room(), objects, &Plan::default())
}

fn on(o: PlacedObject, support: &str, elevation: f64) -> PlacedObject {
    PlacedObject {
        on: Some(support.into()),
        elevation,
        ..o
    }
}

fn hung(o: PlacedObject, wall: usize, elevation: f64) -> PlacedObject {
    PlacedObject {
        wall: Some(wall),
        elevation,
        ..o
    }
}

fn get<'a>(r: &'a Refined, name: &str) -> &'a PlacedObject {
    r.objects.iter().find(|o| o.name == name).expect("placed")
}

/// The layout is valid in 3D: nothing collides, nothing is unsupported or over an opening, every
/// object is placed or dropped with a reason, exactly once.
fn assert_valid(given: &[PlacedObject], r: &Refined) {
    let m = measure(&Layout {
        id: "t".into(),
        room: room(),
        objects: r.objects.clone(),
        dropped: r.dropped.clone(),
        plan: Plan::default().into(),
        stats: Default::default(),
    });
    assert!(m.colliding_pairs.is_empty(), "{:?}", m.colliding_pairs);
    assert!(m.unsupported.is_empty(), "{:?}", m.unsupported);
    assert!(m.over_openings.is_empty(), "{:?}", m.over_openings);
    assert_eq!(m.oob_pct, 0.0);
    assert_eq!(r.objects.len() + r.dropped.len(), given.len());
    assert!(r.dropped.iter().all(|d| !d.reason.is_empty()));
    let names: Vec<&str> = r.objects.iter().map(|o| o.name.as_str()).collect();
    let order: Vec<&str> = given
        .iter()
        .map(|o| o.name.as_str())
        .filter(|n| names.contains(n))
        .collect();
    assert_eq!(names, order, "objects come back in the caller's order");
}

fn nightstand() -> PlacedObject {
    obj("nightstand-0", [45.0, 40.0, 55.0], [30.0, 20.0], 0.0)
}

fn lamp(name: &str, at: [f64; 2]) -> PlacedObject {
    on(obj(name, [25.0, 25.0, 45.0], at, 0.0), "nightstand-0", 55.0)
}

#[test]
fn a_lamp_on_its_nightstand_is_left_alone_and_is_no_floor_obstacle() {
    let given = [nightstand(), lamp("lamp-0", [30.0, 20.0])];
    let r = refine(&given);
    assert_valid(&given, &r);
    assert_eq!(get(&r, "lamp-0"), &given[1]);
    assert_eq!(get(&r, "nightstand-0"), &given[0]);
    assert!(r.notes.is_empty(), "{:?}", r.notes);
    assert!(r.moves.iter().all(|m| m.displacement_cm == 0.0));
}

#[test]
fn a_lamp_is_carried_along_when_its_nightstand_moves() {
    // The nightstand stands in the bed; the PRT moves it (the smaller), and the lamp with it.
    let bed = obj("bed-0", [160.0, 200.0, 50.0], [120.0, 150.0], 0.0);
    let stand = obj("nightstand-0", [45.0, 40.0, 55.0], [190.0, 150.0], 0.0);
    let lamp = lamp("lamp-0", [195.0, 150.0]);
    let given = [bed, stand, lamp];
    let r = refine(&given);
    assert_valid(&given, &r);
    let (s, l) = (get(&r, "nightstand-0"), get(&r, "lamp-0"));
    assert_ne!(s.position, given[1].position, "the nightstand moved");
    assert_eq!(l.on.as_deref(), Some("nightstand-0"));
    assert_eq!(l.elevation, 55.0);
    // The same place on its top: 5 cm to the nightstand's right.
    let local = s.footprint().to_local(glam::DVec2::from(l.position));
    assert!(
        (local.x - 5.0).abs() < 1e-6 && local.y.abs() < 1e-6,
        "{local:?}"
    );
}

#[test]
fn a_lamp_off_its_top_or_at_the_wrong_height_is_put_back_on_it() {
    let given = [nightstand(), lamp("lamp-0", [80.0, 60.0])];
    let low = PlacedObject {
        elevation: 20.0,
        ..lamp("lamp-1", [30.0, 20.0])
    };
    for given in [given.to_vec(), vec![nightstand(), low]] {
        let r = refine(&given);
        assert_valid(&given, &r);
        let l = &r.objects[1];
        assert_eq!(l.on.as_deref(), Some("nightstand-0"));
        assert_eq!(geometry3d::surface_problem(l, &r.objects[0]), None, "{l:?}");
    }
}

#[test]
fn lamps_share_a_top_and_the_one_without_room_stands_on_the_floor_with_a_note() {
    let table = obj("table-0", [120.0, 60.0, 75.0], [200.0, 200.0], 0.0);
    let lamp = |name: &str| {
        on(
            obj(name, [40.0, 40.0, 40.0], [200.0, 200.0], 0.0),
            "table-0",
            75.0,
        )
    };
    let given = [
        table,
        lamp("lamp-0"),
        lamp("lamp-1"),
        lamp("lamp-2"),
        lamp("lamp-3"),
    ];
    let r = refine(&given);
    assert_valid(&given, &r);
    let on_table = r.objects.iter().filter(|o| o.on.is_some()).count();
    assert_eq!(
        on_table, 3,
        "three 40 cm lamps fit a 120 cm top, side by side"
    );
    let down = r.objects.iter().find(|o| o.name == "lamp-3").unwrap();
    assert_eq!((down.on.clone(), down.elevation), (None, 0.0));
    assert!(
        r.notes.iter().any(
            |n| n.starts_with("lamp-3: no room left on top of table-0; it stands on the floor")
        ),
        "{:?}",
        r.notes
    );
}

#[test]
fn nothing_stays_on_a_chair_or_on_what_is_not_placed() {
    let chair = obj("chair-0", [50.0, 50.0, 45.0], [200.0, 200.0], 0.0);
    let vase = on(
        obj("vase-0", [20.0, 20.0, 30.0], [200.0, 200.0], 0.0),
        "chair-0",
        45.0,
    );
    let ghost = on(
        obj("book-0", [20.0, 20.0, 5.0], [300.0, 300.0], 0.0),
        "shelf-9",
        100.0,
    );
    let given = [chair, vase, ghost];
    let r = refine(&given);
    assert_valid(&given, &r);
    assert!(
        r.objects
            .iter()
            .skip(1)
            .all(|o| o.on_floor() && o.elevation == 0.0)
    );
    assert_eq!(r.notes.len(), 2, "{:?}", r.notes);
    assert!(r.notes[1].contains("holds nothing"), "{:?}", r.notes);
    assert!(r.notes[0].contains("not placed"), "{:?}", r.notes);
}

#[test]
fn a_floating_object_is_set_down_with_a_note() {
    let given = [PlacedObject {
        elevation: 30.0,
        ..obj("shelf-0", [60.0, 30.0, 90.0], [200.0, 200.0], 0.0)
    }];
    let r = refine(&given);
    assert_valid(&given, &r);
    assert_eq!(r.objects[0].elevation, 0.0);
    assert_eq!(r.objects[0].position, given[0].position);
    assert!(
        r.notes[0].contains("nothing held it 30 cm above the floor"),
        "{:?}",
        r.notes
    );
}

#[test]
fn a_painting_stays_on_its_wall_and_moves_off_a_door_or_from_behind_a_wardrobe() {
    // Bottom wall (0): the door spans x 255..345. Left wall (3): back at x = 0.
    let painting = |name: &str, at: [f64; 2], rot: f64, wall: usize| {
        hung(obj(name, [80.0, 4.0, 60.0], at, rot), wall, 120.0)
    };
    let fine = painting("painting-0", [2.0, 250.0], 90.0, 3);
    let over_door = painting("painting-1", [300.0, 2.0], 0.0, 0);
    let behind = painting("painting-2", [2.0, 100.0], 90.0, 3);
    let wardrobe = obj("wardrobe-0", [120.0, 60.0, 200.0], [30.0, 100.0], 90.0);
    let sofa = obj("sofa-0", [200.0, 90.0, 90.0], [45.0, 250.0], 90.0);
    let given = [wardrobe, sofa, fine.clone(), over_door, behind];
    let r = refine(&given);
    assert_valid(&given, &r);
    assert_eq!(get(&r, "painting-0"), &fine, "above the sofa it may stay");
    let moved = get(&r, "painting-1");
    assert_eq!((moved.wall, moved.elevation), (Some(0), 120.0));
    assert!(moved.position[0] <= 215.0 + 1e-6, "{moved:?}");
    let moved = get(&r, "painting-2");
    assert_eq!(moved.elevation, 120.0);
    assert!(geometry3d::wall_problem(moved, &room(), moved.wall.unwrap()).is_none());
}

#[test]
fn paintings_with_no_free_wall_are_dropped_with_the_reason_not_stacked() {
    let small = Room::rect(100.0, 100.0);
    let given: Vec<PlacedObject> = (0..5)
        .map(|i| {
            hung(
                obj(
                    &format!("painting-{i}"),
                    [90.0, 4.0, 60.0],
                    [50.0, 2.0],
                    0.0,
                ),
                0,
                120.0,
            )
        })
        .collect();
    let r = PhysicalRefiner::default().refine(&small, &given, &Plan::default());
    assert_eq!(r.objects.len(), 4, "one per wall");
    assert_eq!(r.dropped.len(), 1);
    assert!(
        r.dropped[0]
            .reason
            .contains("no free stretch of wall at 120 cm")
    );
    let walls: std::collections::HashSet<usize> = r.objects.iter().filter_map(|o| o.wall).collect();
    assert_eq!(walls.len(), 4);
    for (i, a) in r.objects.iter().enumerate() {
        assert!(geometry3d::wall_problem(a, &small, a.wall.unwrap()).is_none());
        for b in &r.objects[i + 1..] {
            assert!(!geometry3d::collide(a, b), "{a:?} / {b:?}");
        }
    }
}

mod properties {
    use proptest::prelude::*;

    use super::*;
    use crate::prt::tests::properties::scene;

    /// A room with floor objects (some of them rugs), and objects off the floor among them:
    /// things on random supports (rugs and missing ones included) at noisy heights and places,
    /// things on random walls (missing ones included) at random heights, floating things.
    fn with_held() -> impl Strategy<Value = (Room, Vec<PlacedObject>, Plan)> {
        (scene(0.35, 0.05), any::<u64>()).prop_map(|((mut room, mut objects, plan), seed)| {
            let mut rng = fastrand::Rng::with_seed(seed);
            room.doors.push(Door::new(0, room.width / 2.0, 80.0));
            let floor = objects.len();
            for k in 0..rng.usize(1..8) {
                let size = [
                    (10.0 + rng.f64() * 50.0).round(),
                    (5.0 + rng.f64() * 40.0).round(),
                    (5.0 + rng.f64() * 60.0).round(),
                ];
                let noisy = |rng: &mut fastrand::Rng, at: [f64; 2]| {
                    [
                        at[0] + rng.f64() * 60.0 - 30.0,
                        at[1] + rng.f64() * 60.0 - 30.0,
                    ]
                };
                let mut o = PlacedObject {
                    name: format!("held-{k}"),
                    category: "held".into(),
                    size,
                    ..Default::default()
                };
                match rng.u8(0..4) {
                    0 | 1 => {
                        let s = &objects[rng.usize(0..objects.len())];
                        o.position = noisy(&mut rng, s.position);
                        o.rotation = s.rotation;
                        o.elevation = s.top() + if rng.bool() { 0.0 } else { rng.f64() * 20.0 };
                        o.on = Some(if rng.u8(0..8) == 0 {
                            "ghost".to_string()
                        } else {
                            s.name.clone()
                        });
                    }
                    2 => {
                        o.position = [rng.f64() * room.width, rng.f64() * room.depth];
                        o.rotation = 90.0 * f64::from(rng.u8(0..4));
                        o.elevation = (rng.f64() * 200.0).round();
                        o.wall = Some(rng.usize(0..5));
                    }
                    _ => {
                        o.position = [rng.f64() * room.width, rng.f64() * room.depth];
                        o.elevation = (rng.f64() * 100.0).round();
                    }
                }
                objects.push(o);
            }
            // Some held things stand on other held things.
            if objects.len() > floor + 1 && rng.bool() {
                let top = objects[floor].clone();
                let last = objects.last_mut().expect("held");
                last.wall = None;
                last.elevation = top.top();
                last.on = Some(top.name);
            }
            (room, objects, plan)
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn objects_off_the_floor_end_valid_and_accounted_for((room, objects, plan) in with_held()) {
            let r = PhysicalRefiner::default().refine(&room, &objects, &plan);
            let layout = Layout {
                id: "p".into(),
                room: room.clone(),
                objects: r.objects.clone(),
                dropped: r.dropped.clone(),
                plan: plan.clone().into(),
                stats: Default::default(),
            };
            let m = measure(&layout);
            prop_assert!(m.colliding_pairs.is_empty(), "{:?}", m.colliding_pairs);
            prop_assert!(m.unsupported.is_empty(), "{:?}", m.unsupported);
            prop_assert!(m.over_openings.is_empty(), "{:?}", m.over_openings);
            prop_assert!(m.oob_pct < 1e-9, "{}", m.oob_pct);
            prop_assert_eq!(r.objects.len() + r.dropped.len(), objects.len());
            prop_assert!(r.dropped.iter().all(|d| !d.reason.is_empty()));
            for o in &r.objects {
                let given = objects.iter().find(|g| g.name == o.name).expect("known");
                prop_assert_eq!(o.size, given.size);
            }
            // Same output twice.
            let again = PhysicalRefiner::default().refine(&room, &objects, &plan);
            prop_assert_eq!(again.objects, r.objects);
        }
    }
}
