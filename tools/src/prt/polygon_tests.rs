//! The PRT on real rooms: L-, U- and T-shaped floors, a slanted wall, doors and windows. Hand-made
//! cases, then properties over random outlines (a rectangle with notched or chamfered corners
//! and an optional notch in its top wall) with random openings: no collision, nothing outside the
//! outline, no keep-clear zone entered, and nothing dropped while the room has space to spare.

use super::tests::{obj, walls as against_walls};
use super::*;
use disco_core::geometry::Footprint;
use disco_core::layout::Layout;
use disco_core::metrics::measure;
use disco_core::plan::ObjectConstraints;
use disco_core::room::{Door, Window, validate_room};
use proptest::prelude::*;

fn door(wall: usize, at: f64, width: f64) -> Door {
    Door::new(wall, at, width)
}

fn window(wall: usize, at: f64, width: f64, sill: f64) -> Window {
    Window {
        wall,
        at,
        width,
        sill,
        height: 120.0,
    }
}

/// An L: 600 x 450 without its top-right 250 x 150.
fn l_room() -> Room {
    disco_core::synth::l_shaped_room()
}

/// A 500 x 400 room whose top-right corner is cut by a slanted wall (wall 2).
fn slanted_room() -> Room {
    Room::from_polygon(vec![
        [0.0, 0.0],
        [500.0, 0.0],
        [500.0, 250.0],
        [330.0, 400.0],
        [0.0, 400.0],
    ])
}

/// Every rule of a valid result (the PRT's own properties) on a polygon room: no area outside the
/// outline at all, and no zone entered by an object it binds.
fn check_valid(room: &Room, input: &[PlacedObject], r: &Refined) -> Result<(), TestCaseError> {
    super::tests::properties::check_valid(room, input, r)?;
    let layout = Layout {
        id: "p".into(),
        room: room.clone(),
        objects: r.objects.clone(),
        dropped: r.dropped.clone(),
        plan: Plan::default().into(),
        stats: Default::default(),
    };
    prop_assert_eq!(measure(&layout).oob_pct, 0.0);
    let zones = room.keep_clear();
    for o in &r.objects {
        for z in &zones {
            prop_assert!(
                !o.footprint().intrudes(z, o.size[2]),
                "{} enters {:?} at {:?}",
                o.name,
                z.kind,
                o.position
            );
        }
    }
    Ok(())
}

#[test]
fn an_l_room_keeps_objects_out_of_its_missing_corner_and_the_door() {
    let mut room = l_room();
    room.doors.push(door(0, 300.0, 90.0));
    room.windows.push(window(5, 200.0, 120.0, 90.0));
    let objects = vec![
        // In the missing corner: must come back into the L.
        obj("wardrobe-0", [120.0, 60.0, 200.0], [480.0, 380.0], 0.0),
        // Against the bottom wall right on the door: must slide off it.
        obj("cabinet-0", [100.0, 50.0, 90.0], [300.0, 25.0], 0.0),
        // Tall, against the left wall in front of the window: must leave the window's span.
        obj("shelf-0", [100.0, 40.0, 180.0], [20.0, 250.0], 90.0),
        // Low, under the window: may stay.
        obj("bench-0", [100.0, 40.0, 45.0], [20.0, 380.0], 90.0),
        // A rug on the door's zone: floor coverings may lie there.
        obj("rug-0", [140.0, 100.0, 1.0], [300.0, 60.0], 0.0),
    ];
    let plan = against_walls(&["wardrobe-0", "cabinet-0", "shelf-0"]);
    let r = PhysicalRefiner::default().refine(&room, &objects, &plan);
    check_valid(&room, &objects, &r).unwrap();
    assert!(r.dropped.is_empty(), "{:?}", r.dropped);
    let placed = |n: &str| r.objects.iter().find(|o| o.name == n).unwrap();
    for n in ["wardrobe-0", "cabinet-0", "shelf-0"] {
        let fp = placed(n).footprint();
        assert!(fp.against_wall(&room).is_some(), "{n} at {:?}", fp.center);
    }
    assert_eq!(placed("bench-0").position, [20.0, 380.0]);
    assert_eq!(placed("rug-0").position, [300.0, 60.0]);
}

#[test]
fn a_slanted_wall_holds_a_cabinet_flush() {
    let room = slanted_room();
    // Near the slanted wall, turned square: should end with its back on the slant.
    let objects = vec![obj("cabinet-0", [80.0, 40.0, 90.0], [400.0, 300.0], 0.0)];
    let r = PhysicalRefiner::default().refine(&room, &objects, &against_walls(&["cabinet-0"]));
    check_valid(&room, &objects, &r).unwrap();
    let fp = r.objects[0].footprint();
    assert_eq!(fp.against_wall(&room).map(|w| w.index()), Some(2));
    assert!(
        fp.center.distance(DVec2::new(400.0, 300.0)) < 60.0,
        "{fp:?}"
    );
}

#[test]
fn u_and_t_rooms_take_a_crowd_without_a_drop() {
    let u = Room::from_polygon(vec![
        [0.0, 0.0],
        [700.0, 0.0],
        [700.0, 500.0],
        [480.0, 500.0],
        [480.0, 220.0],
        [220.0, 220.0],
        [220.0, 500.0],
        [0.0, 500.0],
    ]);
    let t = Room::from_polygon(vec![
        [250.0, 0.0],
        [450.0, 0.0],
        [450.0, 300.0],
        [700.0, 300.0],
        [700.0, 500.0],
        [0.0, 500.0],
        [0.0, 300.0],
        [250.0, 300.0],
    ]);
    for room in [u, t] {
        let objects: Vec<PlacedObject> = (0..14)
            .map(|i| {
                let f = i as f64;
                obj(
                    &format!("box-{i}"),
                    [60.0 + 5.0 * (i % 3) as f64, 50.0, 80.0],
                    [350.0 + f, 400.0 - f],
                    0.0,
                )
            })
            .collect();
        let r = PhysicalRefiner::default().refine(&room, &objects, &against_walls(&["box-0"]));
        check_valid(&room, &objects, &r).unwrap();
        assert!(r.dropped.is_empty(), "{:?}", r.dropped);
    }
}

/// A random outline: a `w` x `d` rectangle whose corners may be notched (a rectangle cut out)
/// or chamfered (a slanted wall), and whose top wall may have a notch (a U).
fn outline() -> impl Strategy<Value = Vec<[f64; 2]>> {
    let corner = (0u8..3, 0.1f64..0.3, 0.1f64..0.3);
    (
        400.0f64..900.0,
        400.0f64..800.0,
        prop::array::uniform4(corner),
        (any::<bool>(), 0.3f64..0.6),
    )
        .prop_map(|(w, d, corners, (u, depth))| {
            let (w, d) = (w.round(), d.round());
            let cut = |k: usize| {
                let (kind, a, b) = corners[k];
                (kind, (a * w).round(), (b * d).round())
            };
            let mut pts: Vec<[f64; 2]> = Vec::new();
            // Each corner as (its point, the unit directions of the wall arriving and leaving).
            let spots = [
                ([0.0, 0.0], [0.0, 1.0], [1.0, 0.0]),
                ([w, 0.0], [-1.0, 0.0], [0.0, 1.0]),
                ([w, d], [0.0, -1.0], [-1.0, 0.0]),
                ([0.0, d], [1.0, 0.0], [0.0, -1.0]),
            ];
            for (k, (p, back, on)) in spots.into_iter().enumerate() {
                let (kind, a, b) = cut(k);
                // The lengths cut along the arriving and the leaving wall.
                let (la, ll) = if k % 2 == 0 { (b, a) } else { (a, b) };
                let arrive = [p[0] + back[0] * la, p[1] + back[1] * la];
                let leave = [p[0] + on[0] * ll, p[1] + on[1] * ll];
                match kind {
                    0 => pts.push(p),
                    1 => {
                        pts.push(arrive);
                        let inner = [arrive[0] + leave[0] - p[0], arrive[1] + leave[1] - p[1]];
                        pts.push(inner);
                        pts.push(leave);
                    }
                    _ => {
                        pts.push(arrive);
                        pts.push(leave);
                    }
                }
                if k == 2 && u {
                    // A notch in the top wall, between the two top corners' cuts.
                    let left = if cut(3).0 == 0 { 0.0 } else { cut(3).1 };
                    let right = if cut(2).0 == 0 { w } else { w - cut(2).1 };
                    let (x2, x1) = (right - 0.3 * (right - left), left + 0.3 * (right - left));
                    let low = [cut(0), cut(1)]
                        .iter()
                        .map(|c| if c.0 == 0 { 0.0 } else { c.2 })
                        .fold(0.0, f64::max);
                    let y = (d - depth * (d - low)).round();
                    if x2 - x1 > 60.0 && d - y > 40.0 {
                        pts.extend([[x2.round(), d], [x2.round(), y], [x1.round(), y]]);
                        pts.push([x1.round(), d]);
                    }
                }
            }
            pts
        })
}

/// Doors and windows at random on random walls, each kept only if the room stays valid.
fn openings(room: Room, seed: u64) -> Room {
    let mut rng = fastrand::Rng::with_seed(seed);
    let mut room = room;
    let walls = room.walls();
    for k in 0..rng.usize(0..5) {
        let wall = &walls[rng.usize(0..walls.len())];
        let width = (60.0 + rng.f64() * 80.0).round();
        if wall.length() < width + 20.0 {
            continue;
        }
        let at = (width / 2.0 + 10.0 + rng.f64() * (wall.length() - width - 20.0)).round();
        let mut next = room.clone();
        if k % 2 == 0 {
            next.doors.push(door(wall.index, at, width));
        } else {
            next.windows
                .push(window(wall.index, at, width, 60.0 + rng.f64() * 40.0));
        }
        if validate_room(std::path::Path::new("r.json"), "room", &next).is_ok() {
            room = next;
        }
    }
    room
}

/// A room, and objects up to `largest` cm wide covering up to `cover` of its free floor, some
/// wanting a wall. (Overfull rooms get larger objects: every object left without a place costs a
/// search of the whole floor, so hundreds of small ones would make the test slow, not stricter.)
fn scene(cover: f64, largest: f64) -> impl Strategy<Value = (Room, Vec<PlacedObject>, Plan)> {
    (outline(), any::<u64>()).prop_map(move |(pts, seed)| {
        let room = openings(Room::from_polygon(pts), seed);
        let mut rng = fastrand::Rng::with_seed(seed ^ 0x5eed);
        let zone_area: f64 = room.keep_clear().iter().map(zone_area).sum();
        let free = room.area() - zone_area;
        let mut objects = Vec::new();
        let mut plan = Plan::default();
        let mut covered = 0.0;
        while covered < cover * free {
            let ow = (20.0 + rng.f64() * (largest - 20.0)).round();
            let od = (20.0 + rng.f64() * (0.75 * largest - 20.0)).round();
            if covered + ow * od > cover * free {
                break;
            }
            covered += ow * od;
            let name = format!("thing-{}", objects.len());
            let height = [1.0, 45.0, 80.0, 200.0][rng.usize(0..4)];
            objects.push(obj(
                &name,
                [ow, od, height],
                [rng.f64() * room.width, rng.f64() * room.depth],
                if rng.bool() {
                    90.0 * f64::from(rng.u8(0..4))
                } else {
                    rng.f64() * 360.0
                },
            ));
            if rng.f64() < 0.4 {
                plan = add_wall(plan, &name);
            }
        }
        (room, objects, plan)
    })
}

fn add_wall(mut plan: Plan, name: &str) -> Plan {
    plan.constraints.insert(
        name.to_string(),
        ObjectConstraints {
            against_wall: true,
            ..Default::default()
        },
    );
    plan
}

fn zone_area(z: &disco_core::room::KeepClear) -> f64 {
    let c = &z.corners;
    (c[1] - c[0]).length() * (c[3] - c[0]).length()
}

// Case counts are kept modest so the whole suite stays quick; shrinking is capped so that a
// failure reports in seconds rather than minutes.
proptest! {
    #![proptest_config(ProptestConfig { cases: 32, max_shrink_iters: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_outlines_are_valid_rooms(pts in outline()) {
        let room = Room::from_polygon(pts);
        prop_assert!(validate_room(std::path::Path::new("r.json"), "room", &room).is_ok(), "{:?}", room.polygon);
    }

    #[test]
    fn polygon_rooms_with_openings_are_furnished_validly_and_completely(
        (room, objects, plan) in scene(0.25, 100.0)
    ) {
        let refiner = PhysicalRefiner::default();
        let r = refiner.refine(&room, &objects, &plan);
        check_valid(&room, &objects, &r)?;
        prop_assert!(r.dropped.is_empty(), "dropped {:?} in {:?}", r.dropped, room);
        prop_assert_eq!(&refiner.refine(&room, &objects, &plan), &r, "not deterministic");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, max_shrink_iters: 64, ..ProptestConfig::default() })]

    #[test]
    fn overfull_polygon_rooms_stay_valid((room, objects, plan) in scene(1.2, 250.0)) {
        let r = PhysicalRefiner::default().refine(&room, &objects, &plan);
        check_valid(&room, &objects, &r)?;
    }
}

#[test]
fn a_footprint_in_the_missing_corner_is_outside() {
    let fp = Footprint::new(DVec2::new(480.0, 380.0), 120.0, 60.0, 0.0);
    assert!(!fp.inside(&l_room()));
}
